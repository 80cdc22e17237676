"""Fonts in, against fontTools (an independent reader): every glyph of a TrueType font
(DejaVu Sans, from Debian's fonts-dejavu-core) read as path curves has, contour by contour,
the segments fontTools draws into a RecordingPen — quadratic splines decomposed with
``decomposeQuadraticSegment`` (implied on-curve points are exact midpoints), lines where
fontTools draws lines, the closing line only where the last point differs from the first
— and its glyphs' lengths, areas and boxes agree with fontTools' PerimeterPen, AreaPen and
BoundsPen."""

import math
import os

import numpy as np
import pytest

import splinescope as ss

try:
    import fontTools  # noqa: F401
except ImportError:  # pragma: no cover - scripts/python-dev installs it
    pytest.fail("fonttools is missing: it is a test extra, scripts/python-dev installs it", pytrace=False)
from fontTools.pens.areaPen import AreaPen  # noqa: E402
from fontTools.pens.boundsPen import BoundsPen  # noqa: E402
from fontTools.pens.basePen import decomposeQuadraticSegment  # noqa: E402
from fontTools.pens.recordingPen import DecomposingRecordingPen  # noqa: E402
from fontTools.ttLib import TTFont  # noqa: E402

DEJAVU = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"

if not os.path.exists(DEJAVU):  # pragma: no cover - the test script installs it
    pytest.fail(
        f"{DEJAVU} is missing: install Debian's fonts-dejavu-core (sudo apt-get install fonts-dejavu-core)",
        pytrace=False,
    )


def fonttools_contours(glyphset, name):
    """The glyph's contours as fontTools draws them: lists of segments, each a list of
    points (start point first), quadratic splines decomposed."""
    # Composite glyphs drawn as their components' contours, transformed.
    pen = DecomposingRecordingPen(glyphset)
    glyphset[name].draw(pen)
    contours, current, at, start = [], [], None, None
    for op, args in pen.value:
        if op == "moveTo":
            current, at = [], args[0]
            start = at
        elif op == "lineTo":
            current.append([at, args[0]])
            at = args[0]
        elif op == "qCurveTo":
            pts = list(args)
            if pts[-1] is None:
                # A contour of off-curve points only: fontTools closes it on the implied
                # point between the last and the first.
                pts = pts[:-1]
                first = tuple((a + b) / 2 for a, b in zip(pts[-1], pts[0]))
                at = first
                start = first
                pts = pts + [first]
            for c, p in decomposeQuadraticSegment(pts):
                current.append([at, c, p])
                at = p
        elif op == "curveTo":
            current.append([at, *args])
            at = args[-1]
        elif op in ("closePath", "endPath"):
            if op == "closePath" and current and tuple(at) != tuple(start):
                current.append([at, start])
            if current:
                contours.append(current)
            current = []
    return contours


def ours(glyph):
    scene = ss.load(DEJAVU, glyphs=[glyph])
    out = []
    for c in scene.curves:
        segs = [np.asarray(s[2])[:, :2].tolist() for s in c.segments()]
        out.append(segs)
    return out, scene


def same_cycle(a, b):
    """Whether contour `b` is contour `a` started at another segment."""
    if len(a) != len(b):
        return False
    key = [[tuple(map(float, p)) for p in s] for s in b]
    seq = [[tuple(map(float, p)) for p in s] for s in a]
    return any(seq[k:] + seq[:k] == key for k in range(len(seq)))


@pytest.fixture(scope="module")
def font():
    return TTFont(DEJAVU)


def test_every_glyph_has_fonttools_segments(font):
    glyphset = font.getGlyphSet()
    order = font.getGlyphOrder()
    # Every glyph at once, on the grid (in glyph order, a cell of 1.25 em): each glyph's
    # contours moved back by its cell's corner (the next test checks the grid).
    scene = ss.load(DEJAVU)
    cell = 1.25 * font["head"].unitsPerEm
    columns = math.ceil(math.sqrt(len(order)))
    by_glyph = {}
    for c in scene.curves:
        by_glyph.setdefault(c.name.rpartition(" contour ")[0], []).append(c)
    mismatched = []
    glyf, hmtx = font["glyf"], font["hmtx"]
    placed_by_phantoms = []
    for i, name in enumerate(order):
        dx, dy = (i % columns) * cell, -(i // columns) * cell
        # TrueType places a glyph by its phantom points, the first at xMin − lsb: where
        # the left side bearing in hmtx differs from the header's xMin (6 glyphs of
        # DejaVu Sans, their headers' xMin 1 unit off), a FreeType-style reader (skrifa)
        # may move the outline by the difference; fontTools draws the raw coordinates.
        # There, and only there, either placement is accepted.
        g = glyf[name]
        shifts = [0.0]
        if g.numberOfContours != 0 and g.xMin != hmtx[name][1]:
            shifts.append(float(hmtx[name][1] - g.xMin))
            placed_by_phantoms.append(name)
        theirs = fonttools_contours(glyphset, name)
        mine = [
            [(np.asarray(s[2])[:, :2] - [dx, dy]).tolist() for s in c.segments()]
            for c in by_glyph.get(name, [])
        ]
        if len(mine) != len(theirs):
            mismatched.append((name, f"{len(mine)} contours, fontTools {len(theirs)}"))
            continue
        moved = lambda c, sh: [[[p[0] - sh, p[1]] for p in s] for s in c]  # noqa: E731
        if not any(
            all(same_cycle(moved(m, sh), t) for m, t in zip(mine, theirs)) for sh in shifts
        ):
            mismatched.append((name, f"contours differ: {mine[0][:2]} against {theirs[0][:2]}"))
    assert len(order) > 3000
    assert len(placed_by_phantoms) <= 6, placed_by_phantoms
    assert not mismatched, mismatched[:10]


def test_every_glyph_on_the_grid_is_the_glyph_read_alone(font):
    """All glyphs at once (on a grid in glyph order) are each glyph, moved: the same
    contours in the same order."""
    scene = ss.load(DEJAVU)
    assert len(scene.curves) > 10_000
    for name in ["a", "B", "ampersand", "uni0416"]:
        alone = ss.load(DEJAVU, glyphs=[name]).curves
        on_grid = [c for c in scene.curves if c.name.rpartition(" contour ")[0] == name]
        assert len(on_grid) == len(alone)
        for a, g in zip(alone, on_grid):
            d = np.asarray(g.control_points) - np.asarray(a.control_points)
            assert np.all(d == d[0]), name


@pytest.mark.parametrize("name", ["a", "B", "g", "at", "ampersand", "Aring", "uni0416", "Oslash"])
def test_lengths_areas_and_boxes_agree_with_fonttools_pens(font, name):
    assert name in font.getGlyphOrder(), name
    glyphset = font.getGlyphSet()
    scene = ss.load(DEJAVU, glyphs=[name])
    assert scene.curves, name
    # Area: fontTools' AreaPen (signed, the font's winding); ours, the sum of each
    # closed contour's signed area.
    ap = AreaPen(glyphset)
    glyphset[name].draw(ap)
    area = sum(c.signed_area() for c in scene.curves)
    assert abs(area - ap.value) <= 1e-9 * max(1.0, abs(ap.value)), (area, ap.value)
    bp = BoundsPen(glyphset)
    glyphset[name].draw(bp)
    boxes = np.array([c.bbox() for c in scene.curves])
    lo = boxes[:, 0, :2].min(axis=0)
    hi = boxes[:, 1, :2].max(axis=0)
    assert np.allclose([*lo, *hi], bp.bounds, atol=1e-9), ([*lo, *hi], bp.bounds)
    # Length: against the arc length of fontTools' own quadratic segments by dense
    # Gauss-Legendre quadrature (PerimeterPen's tolerance is looser than ours).
    total = 0.0
    x, w = np.polynomial.legendre.leggauss(32)
    u = 0.5 * (x + 1)
    for contour in fonttools_contours(glyphset, name):
        for s in contour:
            p = np.asarray(s, dtype=float)
            if len(p) == 2:
                total += float(np.linalg.norm(p[1] - p[0]))
            else:
                d = 2 * ((1 - u)[:, None] * (p[1] - p[0]) + u[:, None] * (p[2] - p[1]))
                total += float(0.5 * np.sum(w * np.linalg.norm(d, axis=1)))
    length = sum(c.length() for c in scene.curves)
    assert abs(length - total) <= 1e-9 * total, (length, total)


def test_text_is_laid_out_by_the_advances_with_a_warning(font):
    with pytest.warns(UserWarning, match="no shaping and no kerning"):
        scene = ss.load(DEJAVU, text="AV")
    hmtx = font["hmtx"]
    cmap = font.getBestCmap()
    adv = hmtx[cmap[ord("A")]][0]
    a_only = ss.load(DEJAVU, glyphs=[cmap[ord("A")]])
    v_only = ss.load(DEJAVU, glyphs=[cmap[ord("V")]])
    n_a = len(a_only.curves)
    assert len(scene.curves) == n_a + len(v_only.curves)
    # V sits one advance of A to the right.
    got = np.asarray(scene.curves[n_a].control_points)
    want = np.asarray(v_only.curves[0].control_points) + [adv, 0.0]
    assert np.array_equal(got, want)


def test_bad_requests_are_scene_errors_naming_what(font):
    with pytest.raises(ss.SceneError, match="no glyph of that name"):
        ss.load(DEJAVU, glyphs=["no-such-glyph"])
    with pytest.raises(ss.SceneError, match="has 6"):
        ss.load(DEJAVU, glyphs=["gid999999"])
    with pytest.raises(ss.SceneError, match="not a variable font"):
        ss.load(DEJAVU, variations={"wght": 700})
    with pytest.raises(ss.SceneError, match="no font at index 3"):
        ss.load(DEJAVU, index=3)

"""CFF fonts in, against fontTools: every glyph of a CFF font (Cantarell, from Debian's
fonts-cantarell) read as the cubic segments fontTools draws (zero-length lines the font
draws included), lengths, areas and boxes against fontTools' pens; and a CFF font built
here with fractional coordinates (16.16 fixed-point values that need more bits than an
``f32`` has) read to the bit."""

import math
import os

import numpy as np
import pytest

import splinescope as ss

try:
    import fontTools  # noqa: F401
except ImportError:  # pragma: no cover - scripts/python-dev installs it
    pytest.fail("fonttools is missing: it is a test extra, scripts/python-dev installs it", pytrace=False)
from fontTools.fontBuilder import FontBuilder  # noqa: E402
from fontTools.pens.areaPen import AreaPen  # noqa: E402
from fontTools.pens.boundsPen import BoundsPen  # noqa: E402
from fontTools.pens.t2CharStringPen import T2CharStringPen  # noqa: E402
from fontTools.ttLib import TTFont  # noqa: E402

from test_fonts import fonttools_contours, same_cycle  # noqa: E402

CANTARELL = "/usr/share/fonts/opentype/cantarell/Cantarell-Regular.otf"

if not os.path.exists(CANTARELL):  # pragma: no cover - the test script installs it
    pytest.fail(
        f"{CANTARELL} is missing: install Debian's fonts-cantarell (sudo apt-get install fonts-cantarell)",
        pytrace=False,
    )


@pytest.fixture(scope="module")
def font():
    return TTFont(CANTARELL)


def test_every_cff_glyph_has_fonttools_segments(font):
    assert "CFF " in font and "glyf" not in font
    glyphset = font.getGlyphSet()
    order = font.getGlyphOrder()
    scene = ss.load(CANTARELL)
    cell = 1.25 * font["head"].unitsPerEm
    columns = math.ceil(math.sqrt(len(order)))
    by_glyph = {}
    for c in scene.curves:
        by_glyph.setdefault(c.name.rpartition(" contour ")[0], []).append(c)
    mismatched = []
    zero_length = 0
    for i, name in enumerate(order):
        dx, dy = (i % columns) * cell, -(i // columns) * cell
        theirs = fonttools_contours(glyphset, name)
        zero_length += sum(1 for c in theirs for s in c if len(s) == 2 and tuple(s[0]) == tuple(s[1]))
        mine = [
            [(np.asarray(s[2])[:, :2] - [dx, dy]).tolist() for s in c.segments()]
            for c in by_glyph.get(name, [])
        ]
        if len(mine) != len(theirs) or not all(same_cycle(m, t) for m, t in zip(mine, theirs)):
            mismatched.append(name)
    assert len(order) > 1000
    assert zero_length > 0, "the font draws lines of length zero; they are kept"
    assert not mismatched, mismatched[:10]


@pytest.mark.parametrize("name", ["a", "B", "g", "at", "ampersand", "OE", "eight"])
def test_cff_lengths_areas_and_boxes_agree_with_fonttools_pens(font, name):
    glyphset = font.getGlyphSet()
    scene = ss.load(CANTARELL, glyphs=[name])
    ap = AreaPen(glyphset)
    glyphset[name].draw(ap)
    area = sum(c.signed_area() for c in scene.curves)
    assert abs(area - ap.value) <= 1e-9 * max(1.0, abs(ap.value)), (area, ap.value)
    bp = BoundsPen(glyphset)
    glyphset[name].draw(bp)
    boxes = np.array([c.bbox() for c in scene.curves])
    lo, hi = boxes[:, 0, :2].min(axis=0), boxes[:, 1, :2].max(axis=0)
    assert np.allclose([*lo, *hi], bp.bounds, atol=1e-9), ([*lo, *hi], bp.bounds)
    # Length against Gauss-Legendre quadrature of fontTools' own cubics.
    x, w = np.polynomial.legendre.leggauss(48)
    u = (0.5 * (x + 1))[:, None]
    total = 0.0
    for contour in fonttools_contours(glyphset, name):
        for s in contour:
            p = np.asarray(s, dtype=float)
            if len(p) == 2:
                total += float(np.linalg.norm(p[1] - p[0]))
            else:
                d = 3 * ((1 - u) ** 2 * (p[1] - p[0]) + 2 * u * (1 - u) * (p[2] - p[1]) + u**2 * (p[3] - p[2]))
                total += float(0.5 * np.sum(w * np.linalg.norm(d, axis=1)))
    length = sum(c.length() for c in scene.curves)
    assert abs(length - total) <= 1e-9 * total, (length, total)


def test_fractional_cff_coordinates_arrive_to_the_bit(tmp_path):
    # 16.16 values with 26 and more significant bits: an f32 would round them.
    pts = [(1000.1234588623047, 17.000015258789062), (2047.99998474121, 300.5), (12.25, 1999.9999847412109)]
    fb = FontBuilder(1000, isTTF=False)
    fb.setupGlyphOrder([".notdef", "frac"])
    fb.setupCharacterMap({ord("f"): "frac"})
    pen = T2CharStringPen(600, None, roundTolerance=0)
    pen.moveTo(pts[0])
    pen.curveTo(pts[1], pts[2], (0.5, 0.25))
    pen.lineTo((0.5, 0.25))
    pen.closePath()
    notdef = T2CharStringPen(500, None)
    notdef.moveTo((0, 0))
    notdef.lineTo((10, 0))
    notdef.lineTo((10, 10))
    notdef.closePath()
    fb.setupCFF("Frac", {"FullName": "Frac"}, {".notdef": notdef.getCharString(), "frac": pen.getCharString()}, {})
    fb.setupHorizontalMetrics({".notdef": (500, 0), "frac": (600, 0)})
    fb.setupHorizontalHeader(ascent=800, descent=-200)
    fb.setupNameTable({"familyName": "Frac", "styleName": "Regular"})
    fb.setupOS2()
    fb.setupPost()
    path = os.path.join(tmp_path, "frac.otf")
    fb.save(path)
    glyphset = TTFont(path).getGlyphSet()
    theirs = fonttools_contours(glyphset, "frac")
    scene = ss.load(path, glyphs=["frac"])
    mine = [[np.asarray(s[2])[:, :2].tolist() for s in c.segments()] for c in scene.curves]
    assert len(mine) == len(theirs) == 1
    assert same_cycle(mine[0], theirs[0]), (mine, theirs)
    # And the values are the 16.16 ones, which f32 cannot hold.
    flat = [v for s in mine[0] for p in s for v in p]
    assert 1000.1234588623047 in flat and float(np.float32(1000.1234588623047)) != 1000.1234588623047

"""A variable TrueType font away from its default location, against fontTools: a font
built here with two axes, an avar map, a simple glyph whose tuples leave points out (their
deltas inferred by OpenType's interpolation), an intermediate region, and a composite
glyph whose component offsets move — every outline point within 1e-6 font units of
fontTools' at locations on and between the masters, exactly at the default."""

import numpy as np
import pytest

import splinescope as ss

try:
    import fontTools  # noqa: F401
except ImportError:  # pragma: no cover - scripts/python-dev installs it
    pytest.fail("fonttools is missing: it is a test extra, scripts/python-dev installs it", pytrace=False)
from fontTools.fontBuilder import FontBuilder  # noqa: E402
from fontTools.pens.ttGlyphPen import TTGlyphPen  # noqa: E402
from fontTools.ttLib import TTFont, newTable  # noqa: E402
from fontTools.ttLib.tables.TupleVariation import TupleVariation  # noqa: E402

from test_fonts import fonttools_contours  # noqa: E402


def _font(path):
    fb = FontBuilder(1000, isTTF=True)
    fb.setupGlyphOrder([".notdef", "A", "B", "AB"])
    fb.setupCharacterMap({ord("A"): "A", ord("B"): "B", ord("C"): "AB"})

    def outline(draw):
        pen = TTGlyphPen(None)
        draw(pen)
        return pen.glyph()

    def a(pen):
        pen.moveTo((100, 0))
        pen.qCurveTo((150, 400), (300, 700), (420, 350), (500, 0))  # implied on-curve points
        pen.lineTo((300, -100))
        pen.closePath()
        pen.moveTo((200, 100))
        pen.lineTo((260, 300))
        pen.lineTo((320, 100))
        pen.closePath()

    def b(pen):
        pen.moveTo((0, 0))
        pen.lineTo((0, 600))
        pen.qCurveTo((300, 600), (300, 300))
        pen.qCurveTo((300, 0), (0, 0))
        pen.closePath()

    ab = TTGlyphPen({"A": None, "B": None})
    ab.addComponent("A", (1, 0, 0, 1, 0, 0))
    ab.addComponent("B", (0.75, 0, 0.25, 1, 550, 20))
    fb.setupGlyf({".notdef": outline(lambda p: None), "A": outline(a), "B": outline(b), "AB": ab.glyph()})
    fb.setupHorizontalMetrics({".notdef": (500, 0), "A": (600, 100), "B": (400, 0), "AB": (1000, 100)})
    fb.setupHorizontalHeader(ascent=800, descent=-200)
    fb.setupNameTable({"familyName": "V", "styleName": "Regular"})
    fb.setupOS2()
    fb.setupPost()
    fb.setupFvar([("wght", 100, 400, 900, "Weight"), ("wdth", 75, 100, 125, "Width")], [])
    avar = newTable("avar")
    # Normalised wght 0.6 (700) maps to 0.3 (550).
    avar.segments = {"wght": {-1.0: -1.0, 0.0: 0.0, 0.6: 0.3, 1.0: 1.0}, "wdth": {-1.0: -1.0, 0.0: 0.0, 1.0: 1.0}}
    fb.font["avar"] = avar
    # A: 11 points (7 + 3... its two contours) and 4 phantoms. One tuple with every point,
    # one leaving most out (inferred), one on an intermediate region of both axes.
    glyf = fb.font["glyf"]
    n = len(glyf["A"].coordinates) + 4
    assert n == 13
    full = [(13 * (i % 3) - 5, 7 * (i % 4) - 9) for i in range(n)]
    sparse = [None] * n
    sparse[0], sparse[3], sparse[6] = (20, -10), (-15, 30), (8, 8)
    inter = [(3, 4)] * n
    b_deltas = [(i * 5 - 7, 11 - 3 * i) for i in range(len(glyf["B"].coordinates) + 4)]
    fb.setupGvar(
        {
            "A": [
                TupleVariation({"wght": (0, 1.0, 1.0)}, full),
                TupleVariation({"wdth": (0, 1.0, 1.0)}, sparse),
                TupleVariation({"wght": (0.2, 0.5, 0.8), "wdth": (-1.0, -0.5, 0.0)}, inter),
            ],
            "B": [TupleVariation({"wght": (-1.0, -1.0, 0)}, b_deltas)],
            "AB": [TupleVariation({"wght": (0, 1.0, 1.0)}, [(0, 0), (40, -25), (0, 0), (0, 0), (0, 0), (0, 0)])],
        }
    )
    fb.save(path)


def _points(contours):
    return [np.asarray(p, dtype=float)[:, :2] for c in contours for s in c for p in [s]]


@pytest.mark.parametrize(
    "location",
    [
        {},
        {"wght": 900.0},
        {"wght": 650.0},
        {"wght": 777.75, "wdth": 87.5},
        {"wght": 777.7, "wdth": 112.3},
        {"wght": 250.0, "wdth": 80.0},
        {"wght": 100.0, "wdth": 125.0},
    ],
)
def test_variable_outlines_agree_with_fonttools(tmp_path, location):
    path = str(tmp_path / "v.ttf")
    _font(path)
    font = TTFont(path)
    gs = font.getGlyphSet(location=location) if location else font.getGlyphSet()
    for name in ["A", "B", "AB"]:
        theirs = fonttools_contours(gs, name)
        scene = ss.load(path, glyphs=[name], variations=location or None)
        mine = [[np.asarray(s[2])[:, :2] for s in c.segments()] for c in scene.curves]
        assert len(mine) == len(theirs), (name, len(mine), len(theirs))
        for m, t in zip(mine, theirs):
            assert len(m) == len(t), (name, location)
            # The same cycle of segments, to 1e-6 font units (exactly at the default).
            best = min(
                max(float(np.abs(m[(i + k) % len(m)] - np.asarray(t[i], dtype=float)).max()) for i in range(len(t)))
                if all(len(m[(i + k) % len(m)]) == len(t[i]) for i in range(len(t)))
                else float("inf")
                for k in range(len(m))
            )
            tol = 0.0 if not location else 1e-6
            assert best <= tol, (name, location, best)

"""A variable CFF2 font away from its default location, against fontTools: a font built
here with two axes, an avar map, five regions (one per axis, one on the negative side, an
intermediate master and a corner), deltas that are not whole units, and a contour that
returns to its start only at the default (its closing line comes and goes) — every point
within 1e-6 font units of fontTools' at locations on and between the masters, exactly at
the default. (Blends evaluated in 16.16 from a location rounded to 2.14 are off by up to
6·10⁻⁴ units here: the test fails for such a reader.)

`python crates/python/tests/test_fonts_cff2_variable.py OUT.otf` writes the font (the
fuzz's seed `tests/fonts/variable-cff2.otf` is that file)."""

import sys

import numpy as np
import pytest

import splinescope as ss

try:
    import fontTools  # noqa: F401
except ImportError:  # pragma: no cover - scripts/python-dev installs it
    pytest.fail("fonttools is missing: it is a test extra, scripts/python-dev installs it", pytrace=False)
from fontTools.fontBuilder import FontBuilder  # noqa: E402
from fontTools.misc.psCharStrings import T2CharString  # noqa: E402
from fontTools.ttLib import TTFont, newTable  # noqa: E402

from test_fonts import fonttools_contours  # noqa: E402

REGIONS = [
    {"wght": (0, 1, 1)},
    {"wdth": (0, 1, 1)},
    {"wght": (-1, -1, 0)},
    {"wght": (0, 0.5, 1)},  # an intermediate master
    {"wght": (0, 1, 1), "wdth": (0, 1, 1)},  # a corner
]


def _blend(values, deltas):
    """A CFF2 blend: the values, then each value's deltas (one per region), the count."""
    out = list(values)
    for d in deltas:
        out += list(d)
    return out + [len(values), "blend"]


Z = [0, 0, 0, 0, 0]


def _a():
    p = _blend([100, 0], [[13, 7, -9, 5.5, 3], Z]) + ["rmoveto"]
    p += _blend([300, 0], [[17, 11, -3, 2.25, -7], Z]) + ["rlineto"]
    p += _blend(
        [50, 100, 60, 200, 0, 150],
        [[1, 2, 3, 4, 5], [7, 0, 0, 1, 0], [3, 3, 3, 3, 3], [-5, 1, 0, 0, 2], [0, 0, 11, 0, 0], [13, 0, 0, 0, 7]],
    ) + ["rrcurveto"]
    p += _blend([-200, 50], [[9, 0, 1, 0, 1], [3, 1, 0, 0, 1]]) + ["rlineto"]
    p += _blend([150, 150], [[1.5, 0, 0, 0, 0], [0, 0, 0, 2.5, 0]]) + ["rmoveto"]
    p += _blend(
        [40, 0, 20, 40, 0, 20],
        [[1, 0, 0, 0, 0], Z, [2, 1, 1, 1, 1], [0, 1, 0, 0, 0], Z, [3, 0, 0, 0, 3]],
    ) + ["rrcurveto"]
    return p


def _b():
    # A triangle that returns to its start at the default only: the last line's deltas
    # do not cancel the others'.
    p = [100, 0, "rmoveto"]
    p += _blend([200, 0], [[10.75, 0, 0, 0, 0], Z]) + ["rlineto"]
    p += _blend([-100, 150], [Z, [0, 6.5, 0, 0, 0]]) + ["rlineto"]
    p += [-100, -150, "rlineto"]
    return p


def build(path):
    fb = FontBuilder(1000, isTTF=False)
    fb.setupGlyphOrder([".notdef", "A", "B"])
    fb.setupCharacterMap({ord("A"): "A", ord("B"): "B"})
    fb.setupNameTable({"familyName": "V2", "styleName": "Regular"})
    fb.setupFvar([("wght", 100, 400, 900, "Weight"), ("wdth", 75, 100, 125, "Width")], [])
    charstrings = {
        ".notdef": T2CharString(program=[]),
        "A": T2CharString(program=_a()),
        "B": T2CharString(program=_b()),
    }
    fb.setupCFF2(charstrings, regions=REGIONS)
    fb.setupCFF2Regions(REGIONS)
    fb.setupHorizontalMetrics({".notdef": (500, 0), "A": (600, 100), "B": (400, 100)})
    fb.setupHorizontalHeader(ascent=800, descent=-200)
    fb.setupOS2()
    fb.setupPost()
    avar = newTable("avar")
    avar.segments = {"wght": {-1.0: -1.0, 0.0: 0.0, 0.3: 0.6, 1.0: 1.0}, "wdth": {-1.0: -1.0, 0.0: 0.0, 1.0: 1.0}}
    fb.font["avar"] = avar
    fb.save(path)


@pytest.mark.parametrize(
    "location",
    [
        {},
        {"wght": 900.0},
        {"wght": 650.0},
        {"wght": 550.0},
        {"wght": 637.0, "wdth": 111.3},
        {"wght": 777.0, "wdth": 80.0},
        {"wght": 123.4, "wdth": 124.0},
        {"wght": 100.0, "wdth": 125.0},
    ],
)
def test_cff2_outlines_agree_with_fonttools(tmp_path, location):
    path = str(tmp_path / "v.otf")
    build(path)
    font = TTFont(path)
    gs = font.getGlyphSet(location=location) if location else font.getGlyphSet()
    for name in ["A", "B"]:
        theirs = fonttools_contours(gs, name)
        scene = ss.load(path, glyphs=[name], variations=location or None)
        mine = [[np.asarray(s[2])[:, :2] for s in c.segments()] for c in scene.curves]
        assert len(mine) == len(theirs), (name, len(mine), len(theirs))
        for m, t in zip(mine, theirs):
            assert len(m) == len(t), (name, location, len(m), len(t))
            worst = max(float(np.abs(a - np.asarray(b, dtype=float)).max()) for a, b in zip(m, t))
            tol = 0.0 if not location else 1e-6
            assert worst <= tol, (name, location, worst)


def test_the_closing_line_follows_the_location(tmp_path):
    # B's last point is its first at the default (three segments, no closing line) and
    # not elsewhere (a closing line, as fontTools' contour has).
    path = str(tmp_path / "v.otf")
    build(path)
    assert len(ss.load(path, glyphs=["B"]).curves[0].segments()) == 3
    moved = ss.load(path, glyphs=["B"], variations={"wght": 900.0})
    assert len(moved.curves[0].segments()) == 4


def test_past_64_regions_at_a_location_the_reader_says_it_rounds(tmp_path):
    # 65 regions that all count at wght 900: evaluated in 16.16, with a warning that says
    # so, still near fontTools'.
    regions = [{"wght": (0, 1, 1)}] * 65
    fb = FontBuilder(1000, isTTF=False)
    fb.setupGlyphOrder([".notdef", "A"])
    fb.setupCharacterMap({ord("A"): "A"})
    fb.setupNameTable({"familyName": "V3", "styleName": "Regular"})
    fb.setupFvar([("wght", 100, 400, 900, "Weight")], [])
    program = _blend([100, 0], [[0.25] * 65, [0] * 65]) + ["rmoveto", 300, 0, "rlineto", 0, 300, "rlineto"]
    fb.setupCFF2({".notdef": T2CharString(program=[]), "A": T2CharString(program=program)}, regions=regions)
    fb.setupCFF2Regions(regions)
    fb.setupHorizontalMetrics({".notdef": (500, 0), "A": (600, 100)})
    fb.setupHorizontalHeader(ascent=800, descent=-200)
    fb.setupOS2()
    fb.setupPost()
    path = str(tmp_path / "many.otf")
    fb.save(path)
    with pytest.warns(UserWarning, match="65 variation regions count at this location"):
        scene = ss.load(path, glyphs=["A"], variations={"wght": 700.0})
    theirs = fonttools_contours(TTFont(path).getGlyphSet(location={"wght": 700.0}), "A")
    first = np.asarray(scene.curves[0].segments()[0][2])[0, :2]
    assert np.abs(first - np.asarray(theirs[0][0][0], dtype=float)).max() <= 1e-2


if __name__ == "__main__":
    build(sys.argv[1])

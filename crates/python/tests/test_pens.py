"""The fontTools pen protocol both ways: glyphs drawn by fontTools into ScenePen are the
glyphs splinescope reads from the font itself, curves drawn into fontTools' RecordingPen
replay into ScenePen unchanged, and what the protocol cannot say is refused."""

import math

import numpy as np
import pytest

import splinescope as ss
from splinescope.pens import PenError, ScenePen

try:
    from fontTools.pens.recordingPen import RecordingPen
    from fontTools.ttLib import TTFont
except ImportError:  # pragma: no cover - scripts/python-dev installs it
    pytest.fail("fonttools is missing: it is a test extra, scripts/python-dev installs it", pytrace=False)

DEJAVU = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"


def segments(curve):
    return [np.asarray(s[2])[:, :2].tolist() for s in curve.segments()]


def same_cycle(a, b):
    if len(a) != len(b):
        return False
    return any(a[k:] + a[:k] == b for k in range(len(a)))


def test_glyphs_drawn_by_fonttools_into_a_scene_pen_are_the_fonts_own():
    font = TTFont(DEJAVU)
    gs = font.getGlyphSet()
    glyf, hmtx = font["glyf"], font["hmtx"]
    order = font.getGlyphOrder()
    checked = 0
    for name in order[::25] + ["Aacute", "ampersand", "uni1F35"]:
        g = glyf[name]
        if g.numberOfContours != 0 and g.xMin != hmtx[name][1]:
            continue  # placed by phantom points (docs/formats.md): compared in test_fonts
        pen = ScenePen(glyph_set=gs, name=name)
        gs[name].draw(pen)
        mine = pen.scene.curves
        theirs = ss.load(DEJAVU, glyphs=[name]).curves
        assert len(mine) == len(theirs), name
        for k, (a, b) in enumerate(zip(mine, theirs)):
            assert a.closed and b.closed
            assert same_cycle(segments(a), segments(b)), (name, k)
            assert a.name == f"{name} contour {k}"
        checked += 1
    assert checked > 200


def test_a_curve_drawn_into_a_recording_pen_replays_into_a_scene_pen_unchanged():
    h = math.sqrt(0.5)
    curves = [
        ss.load(DEJAVU, glyphs=["g"]).curves[0],
        ss.Path([[[0, 0], [1, 0]], [[1, 0], [2, 1], [3, 0], [4, 2]], [[4, 2], [5, 3], [6, 0]]]),
        ss.Bezier([[0, 0], [1, 2], [2, 0]]),
    ]
    for c in curves:
        rec = RecordingPen()
        c.draw(rec)
        ops = [op for op, _ in rec.value]
        assert ops[0] == "moveTo" and ops[-1] in ("closePath", "endPath")
        assert set(ops) <= {"moveTo", "lineTo", "qCurveTo", "curveTo", "closePath", "endPath"}
        pen = ScenePen()
        rec.replay(pen)
        back = pen.scene.curves[0]
        assert segments(back) == segments(c)
    # Rational segments and degrees above 3 cannot be said as they are: they go through
    # to_cubics within the tolerance (checked against the closed form: the quarter arc's
    # cubics stay within it of the unit circle), and the rest as they are.
    arc = ss.Path([([[1, 0], [1, 1], [0, 1]], [1, h, 1]), [[0, 1], [-1, 1]]])
    rec = RecordingPen()
    arc.draw(rec, tolerance=1e-7)
    ops = [op for op, _ in rec.value]
    assert ops[0] == "moveTo" and ops[-2:] == ["lineTo", "endPath"]
    assert set(ops[1:-2]) == {"curveTo"}
    pen = ScenePen()
    rec.replay(pen)
    drawn = pen.scene.curves[0]
    ts = np.linspace(0, len(drawn.segments()) - 1, 2000)
    r = np.linalg.norm(np.asarray(drawn.eval(ts)), axis=1)
    assert np.abs(r - 1).max() <= 1e-7
    quintic = ss.Bezier([[0, 0], [1, 1], [2, 0], [3, 1], [4, 0], [5, 1]])
    rec = RecordingPen()
    quintic.draw(rec)
    pen = ScenePen()
    rec.replay(pen)
    back = pen.scene.curves[0]
    # Within the default tolerance, 1e-6 of the box's diagonal: sampled both ways.
    diag = float(np.linalg.norm(np.subtract(*quintic.bbox()[::-1])))
    pts = np.asarray(quintic.eval(np.linspace(0, 1, 500)))
    _, d = back.nearest(pts)
    assert d.max() <= 1e-6 * diag


def test_a_scene_pen_takes_truetype_splines_and_refuses_what_is_out_of_order():
    pen = ScenePen()
    # Two off-curve points: an implied on-curve point at their midpoint.
    pen.moveTo((0, 0))
    pen.qCurveTo((1, 2), (3, 2), (4, 0))
    pen.closePath()
    c = pen.scene.curves[0]
    assert segments(c) == [
        [[0.0, 0.0], [1.0, 2.0], [2.0, 2.0]],
        [[2.0, 2.0], [3.0, 2.0], [4.0, 0.0]],
        [[4.0, 0.0], [0.0, 0.0]],
    ]
    # A contour of off-curve points only (None last): it starts between the last and first.
    pen = ScenePen()
    pen.qCurveTo((0, 0), (2, 0), (2, 2), (0, 2), None)
    pen.closePath()
    c = pen.scene.curves[0]
    assert c.closed and len(c.segments()) == 4
    assert segments(c)[0][0] == [0.0, 1.0]
    with pytest.raises(PenError, match="moveTo first"):
        ScenePen().lineTo((1, 1))
    with pytest.raises(PenError, match="no glyph set holds the component 'A'"):
        ScenePen().addComponent("A", (1, 0, 0, 1, 0, 0))

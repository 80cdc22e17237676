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
    # Rational segments and degrees above 3 cannot be said.
    arc = ss.Path([([[1, 0], [1, 1], [0, 1]], [1, h, 1])])
    with pytest.raises(PenError, match="segment 0 is rational"):
        arc.draw(RecordingPen())
    with pytest.raises(PenError, match="segment 0 has degree 5"):
        ss.Bezier([[0, 0], [1, 1], [2, 0], [3, 1], [4, 0], [5, 1]]).draw(RecordingPen())


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

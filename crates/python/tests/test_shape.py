"""Curvature combs and shape markers from Python (``Scene.render/png/export(...,
comb=..., inflections=..., curvature_extrema=..., intersections=...)``), read back
against closed forms: a circle's comb hairs in an SVG end ``s / r`` beyond it on its
radii; a render with a comb is inked where the hairs are; bad arguments are refused
naming them."""

import json
import math
import re

import numpy as np
import pytest

import splinescope as ss

from test_render import BACKENDS, render_or_fail


def bare(curves):
    """A scene of ``curves`` without control polygons or points."""
    doc = json.loads(ss.Scene(curves).to_json())
    for c in doc["curves"]:
        c.setdefault("style", {}).update({"polygon": False, "points": False})
    return ss.Scene.from_json(json.dumps(doc))


def circle_scene(r):
    return bare([ss.Nurbs.circle([0.0, 0.0], r)])


def segments_of(svg):
    """Every straight two-point run ``M x y L x y`` of the SVG's paths."""
    out = []
    for d in re.findall(r'<path[^>]* d="([^"]+)"', svg):
        for m in re.finditer(r"M\s*([-\d.e]+)[ ,]([-\d.e]+)\s*L\s*([-\d.e]+)[ ,]([-\d.e]+)(?=\s*(?:M|$))", d):
            out.append(tuple(float(v) for v in m.groups()))
    return out


def test_an_svg_comb_of_a_circle_ends_scale_over_radius_beyond_it(tmp_path):
    r, s, size = 2.0, 0.2, 400
    plain, combed = tmp_path / "plain.svg", tmp_path / "comb.svg"
    scene = circle_scene(r)
    scene.export(plain, width=size, height=size)
    scene.export(combed, width=size, height=size, comb=s)
    hairs = segments_of(combed.read_text())
    assert len(hairs) >= 4 * 20, hairs[:3]
    assert not segments_of(plain.read_text()), "no comb without asking"
    # The view fits the circle: its centre at the page's, 0.9 · size / (2 r) points per
    # unit.
    c = size / 2
    unit = 0.9 * size / (2 * r)
    for x0, y0, x1, y1 in hairs:
        a = math.hypot(x0 - c, y0 - c) / unit
        b = math.hypot(x1 - c, y1 - c) / unit
        # Written to a few decimals: within 1e-3 points.
        assert abs(a - r) < 1e-2 / unit and abs(b - (r + s / r)) < 1e-2 / unit, (a, b)
        # Foot and tip on one radius.
        cross = (x0 - c) * (y1 - c) - (y0 - c) * (x1 - c)
        assert abs(cross) < 1e-1 * unit, (x0, y0, x1, y1)


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_render_with_a_comb_is_inked_where_the_hairs_are(backend):
    r, s, size = 2.0, 0.4, 400
    scene = circle_scene(r)
    plain = render_or_fail(scene, size, size, backend=backend)
    combed = render_or_fail(scene, size, size, backend=backend, comb=s)
    marked = render_or_fail(scene, size, size, backend=backend, curvature_extrema=True)
    bg = plain[0, 0]
    unit = 0.9 * size / (2 * r)
    inked = 0
    for k in range(64):
        a = 2 * math.pi * k / 64
        q = (r + 0.5 * s / r) * unit
        x, y = round(size / 2 + q * math.cos(a)), round(size / 2 - q * math.sin(a))
        patch = lambda img: img[y - 1 : y + 2, x - 1 : x + 2].reshape(-1, 4)
        assert (patch(plain) == bg).all(), "nothing drawn there without a comb"
        inked += int((patch(combed) != bg).any())
    assert inked >= 16, inked
    # A circle has constant curvature: no extremum, so no marker changes the picture.
    assert np.array_equal(marked, plain)


@pytest.mark.parametrize("backend", BACKENDS)
def test_markers_change_the_picture_where_the_analysis_finds_them(backend):
    s_curve = ss.Bezier([[0, 0], [1, 2], [1, -2], [2, 0]])
    scene = bare([s_curve])
    plain = render_or_fail(scene, 300, 300, backend=backend)
    marked = render_or_fail(scene, 300, 300, backend=backend, inflections=True)
    changed = np.argwhere((plain != marked).any(axis=2))
    assert len(changed), "the inflection marker is drawn"
    # Around the inflection (1, 0) — the view's centre — only.
    centre = np.array([150, 150])
    assert np.abs(changed - centre).max() <= 8, changed.min(axis=0)


@pytest.mark.parametrize(
    "comb, error, words",
    [
        (-1.0, ss.SceneError, "comb scale -1"),
        (0, ss.SceneError, "comb scale 0"),
        (float("nan"), ss.SceneError, "comb scale nan"),
        ("wide", TypeError, "comb"),
    ],
)
def test_bad_comb_arguments_are_refused_naming_them(tmp_path, comb, error, words):
    scene = circle_scene(1.0)
    with pytest.raises(error, match=re.escape(words)):
        scene.export(tmp_path / "x.svg", comb=comb)
    assert not (tmp_path / "x.svg").exists()
    with pytest.raises(TypeError, match="inflections"):
        scene.render(10, 10, inflections="yes")


def test_a_comb_cap_cuts_every_longer_hair_to_it(tmp_path):
    # r = 2, s = 0.4: every hair 0.2 long (inside the page). The view fits the circle
    # (0.9 of the page: 2r / 0.9 units tall): a cap of 0.02 of it is ≈ 0.089 units.
    r, s, size = 2.0, 0.4, 400
    scene = circle_scene(r)
    unit = 0.9 * size / (2 * r)
    view = size / unit
    c = size / 2
    for cap, want in [(0.02, 0.02 * view), (0.9, s / r), (None, s / r)]:
        path = tmp_path / f"cap-{cap}.svg"
        scene.export(path, width=size, height=size, comb=s, comb_cap=cap)
        hairs = segments_of(path.read_text())
        assert len(hairs) >= 4 * 20, (cap, hairs[:3])
        for x0, y0, x1, y1 in hairs:
            length = math.hypot(x1 - x0, y1 - y0) / unit
            assert abs(length - want) < 1e-2, (cap, length, want)
            # Still outward along the radius.
            assert math.hypot(x1 - c, y1 - c) > math.hypot(x0 - c, y0 - c)


@pytest.mark.parametrize("cap", [0, -0.5, float("nan"), float("inf")])
def test_bad_comb_caps_are_refused_naming_them(tmp_path, cap):
    with pytest.raises(ss.SceneError, match="comb cap"):
        circle_scene(1.0).export(tmp_path / "x.svg", comb=True, comb_cap=cap)
    assert not (tmp_path / "x.svg").exists()
    with pytest.raises(TypeError, match="comb_cap"):
        circle_scene(1.0).render(10, 10, comb=True, comb_cap="wide")


@pytest.mark.parametrize("backend", BACKENDS)
def test_joint_markers_mark_the_kink(backend):
    # A triple knot at 1: a kink at (3, 1), the view's centre; nothing else is marked.
    s = ss.BSpline(
        [0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 2],
        [[1, -1], [2, 0.5], [2, 1], [3, 1], [4, 1], [4, 1.5], [5, 3]],
        4,
    )
    scene = bare([s])
    plain = render_or_fail(scene, 300, 300, backend=backend)
    marked = render_or_fail(scene, 300, 300, backend=backend, joints=True)
    changed = np.argwhere((plain != marked).any(axis=2))
    assert len(changed), "the kink is marked"
    centre = np.array([150, 150])
    assert np.abs(changed - centre).max() <= 8, changed.min(axis=0)
    with pytest.raises(TypeError, match="joints"):
        scene.render(10, 10, joints="yes")

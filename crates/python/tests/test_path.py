"""The path family from Python: segments kept exactly as given, a circle of rational
quarter arcs against its closed forms, joints moved together, bad paths refused naming
the segment or the joint."""

import math

import numpy as np
import pytest

import splinescope as ss

H = math.sqrt(0.5)


def circle(cx=0.0, cy=0.0, r=1.0):
    """Four rational quadratic quarter arcs, closed."""
    corners = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (1, 0)]
    segments = []
    for q in range(4):
        pts = [[cx + r * x, cy + r * y] for x, y in corners[2 * q : 2 * q + 3]]
        segments.append((pts, [1.0, H, 1.0]))
    return ss.Path(segments, closed=True)


def test_segments_are_kept_exactly_and_cover_k_to_k_plus_one():
    p = ss.Path([[[0, 0], [1, 0]], [[1, 0], [2, 1], [3, 0]], ([[3, 0], [4, 1], [5, 0]], [1, 2, 1])])
    assert p.family == "path" and not p.closed
    assert p.domain() == (0.0, 3.0)
    segs = p.segments()
    assert [len(s[2]) - 1 for s in segs] == [1, 2, 2]
    assert [(s[0], s[1]) for s in segs] == [(0.0, 1.0), (1.0, 2.0), (2.0, 3.0)]
    # The rational segment keeps its weights; the polynomial ones have none.
    assert len(segs[0]) == 3 and len(segs[1]) == 3
    assert np.array_equal(segs[2][3], [1.0, 2.0, 1.0])
    # The quadratic's middle at t = 1.5: (P0 + 2 P1 + P2) / 4.
    assert np.array_equal(p.eval(1.5), [2.0, 0.5])
    # Shared end points listed once.
    assert p.control_points.shape == (6, 2)
    q = ss.Curve.from_dict(p.to_dict())
    assert q.to_dict() == p.to_dict()


@pytest.mark.parametrize("r", [1.0, 10.0, 1e-3])
def test_a_circle_of_quarter_arcs_has_the_circles_length_area_and_curvature(r):
    c = circle(3.0, -2.0, r)
    assert abs(c.length() - 2 * math.pi * r) <= 1e-12 * max(r, 1.0)
    assert abs(c.signed_area() - math.pi * r * r) <= 1e-12 * max(r * r, 1.0)
    t = np.linspace(0.0, 4.0, 4001)
    d = np.linalg.norm(c.eval(t) - [3.0, -2.0], axis=1)
    assert np.max(np.abs(d - r)) <= 1e-14 * (r + 4.0)
    k = c.curvature(t[1:-1])
    assert np.allclose(k * r, 1.0, rtol=1e-9)
    # Every joint is G2 (the arcs meet with one tangent and one curvature).
    j = c.joints()
    assert j.shape[0] == 4
    assert np.all(j[:, 2] < 1e-12) and np.all(j[:, 3] < 1e-9)


def test_moving_a_joint_moves_both_segments():
    p = ss.Path([[[0, 0], [1, 0]], [[1, 0], [2, 1], [3, 0]]])
    p = p.move_point(1, [1.0, -1.0])
    assert isinstance(p, ss.Path)
    segs = p.segments()
    assert np.array_equal(segs[0][2][1], [1.0, -1.0])
    assert np.array_equal(segs[1][2][0], [1.0, -1.0])


@pytest.mark.parametrize(
    "segments,closed,path,words",
    [
        ([[[0, 0], [1, 0]], [[1, 1e-3], [2, 0]]], False, "segments", "joint 0"),
        ([[[0, 0], [1, 0]]], True, "segments", "joint 0"),
        ([], False, "segments", "at least 1 segment"),
        ([[[0, 0], [1, 0]], ([[1, 0], [2, 0]], [1.0, -1.0])], False, "segments[1].weights[1]", "weight"),
        ([[[0, 0], [1, 0, 0]]], False, "segments[0].points", ""),
    ],
)
def test_bad_paths_are_refused_naming_the_segment_or_the_joint(segments, closed, path, words):
    with pytest.raises((ss.SceneError, ValueError)) as e:
        ss.Path(segments, closed=closed)
    assert getattr(e.value, "path", "").endswith(path), (e.value, getattr(e.value, "path", None))
    assert words in str(e.value)


def test_a_path_must_have_one_dimension():
    with pytest.raises(ss.SceneError) as e:
        ss.Path([[[0, 0], [1, 0]], [[1, 0, 0], [2, 0, 0]]])
    assert e.value.path == "segments[1].points"


def test_load_reads_svg_as_paths_with_a_warning_for_what_it_leaves_out(tmp_path):
    f = tmp_path / "logo.svg"
    f.write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">'
        '<circle cx="50" cy="50" r="10" stroke="red" fill="none"/>'
        '<path d="M 10 10 Q 20 0 30 10 T 50 10" stroke="blue"/>'
        "<text>not a curve</text></svg>"
    )
    with pytest.warns(UserWarning, match=r"left out \(not curves\): 1 <text>"):
        scene = ss.load(f)
    assert len(scene.curves) == 2
    circle = scene.curves[0]
    assert isinstance(circle, ss.Path) and circle.closed
    assert abs(circle.length() - 20 * math.pi) <= 1e-12
    # The quadratics stay quadratics; T reflects the control point.
    segs = scene.curves[1].segments()
    assert [len(s[2]) for s in segs] == [3, 3]
    assert np.allclose(segs[1][2][1], [40.0, 100.0 - 20.0])


def test_a_bad_svg_file_is_a_scene_error_naming_the_file_and_the_line(tmp_path):
    f = tmp_path / "bad.svg"
    f.write_text("<svg>\n<path d='M 0 0 L'/></svg>")
    with pytest.raises(ss.SceneError, match=r"bad\.svg:2: <path>: path data"):
        ss.load(f)

"""Values that travel: every curve class and ``Scene`` pickle (protocols 2–5) and copy,
bit for bit; equality and hashing by value; ``__all__`` names only the public API; and
curves shipped to other processes — a process pool, joblib, a two-worker Dask cluster —
evaluate and render as they do here. Every entry point that starts worker processes is
guarded and bounded in time."""

import copy
import pickle
import re

import numpy as np
import pytest

import splinescope as ss

from conftest import SCENES

PROTOCOLS = [2, 3, 4, 5]


def shipped_curves():
    """Every curve of every shipped scene, and the stress generator's of every family."""
    out = []
    for path in sorted(SCENES.glob("*.json")):
        try:
            scene = ss.Scene.load(path)
        except ss.SceneError:
            continue
        out.extend((f"{path.name}[{i}]", c) for i, c in enumerate(scene.curves))
    return out


def exact_state(curve):
    """Every number that defines a curve, as raw bytes: its segments' control points,
    weights and ranges, its control points and its scene-format text."""
    parts = [curve.family.encode(), str(curve.dim).encode(), curve.control_points.tobytes()]
    for seg in curve.segments():
        parts.extend(np.asarray(x, dtype=np.float64).tobytes() for x in seg)
    return parts, json_numbers(curve.to_dict())


def json_numbers(obj):
    """Every number of a JSON value, as float64 bytes (so -0.0 and 0.0 differ)."""
    if isinstance(obj, dict):
        return [(k, json_numbers(v)) for k, v in sorted(obj.items())]
    if isinstance(obj, list):
        return [json_numbers(v) for v in obj]
    if isinstance(obj, (int, float)) and not isinstance(obj, bool):
        return np.float64(obj).tobytes()
    return obj


CURVES = shipped_curves()


@pytest.mark.parametrize("name, curve", CURVES, ids=[n for n, _ in CURVES])
def test_every_shipped_curve_pickles_and_copies_bit_for_bit(name, curve):
    want = exact_state(curve)
    for protocol in PROTOCOLS:
        back = pickle.loads(pickle.dumps(curve, protocol=protocol))
        assert type(back) is type(curve)
        assert exact_state(back) == want, f"{name}, protocol {protocol}"
        assert back == curve and hash(back) == hash(curve)
    for c in (copy.copy(curve), copy.deepcopy(curve)):
        assert exact_state(c) == want and c == curve
    t = np.linspace(*curve.domain(), 33)
    assert np.array_equal(pickle.loads(pickle.dumps(curve)).eval(t), curve.eval(t))


STRESS = [(f, d) for f in ss.FAMILY_NAMES for d in (2, 3, 7)]


@pytest.mark.parametrize("family, degree", STRESS, ids=[f"{f}-{d}" for f, d in STRESS])
def test_generated_curves_of_every_family_pickle_bit_for_bit(family, degree):
    # Random doubles need all 17 digits: the text round trip must keep every bit.
    scene = ss.stress_scene(20, family, degree, seed=7)
    for curve in scene.curves:
        want = exact_state(curve)
        for protocol in PROTOCOLS:
            back = pickle.loads(pickle.dumps(curve, protocol=protocol))
            assert exact_state(back) == want and back == curve
    back = pickle.loads(pickle.dumps(scene))
    assert back == scene and hash(back) == hash(scene)
    assert [exact_state(c) for c in back.curves] == [exact_state(c) for c in scene.curves]


@pytest.mark.parametrize("path", sorted(SCENES.glob("*.json")), ids=lambda p: p.name)
def test_every_shipped_scene_pickles_with_its_form(path, tmp_path):
    try:
        scene = ss.Scene.load(path)
    except ss.SceneError:
        pytest.skip(f"{path.name} is refused on purpose")
    for protocol in PROTOCOLS:
        back = pickle.loads(pickle.dumps(scene, protocol=protocol))
        assert back == scene and hash(back) == hash(scene)
        # The form too: saved, it writes the file's bytes.
        back.save(tmp_path / "back.json")
        assert (tmp_path / "back.json").read_bytes() == path.read_bytes()
    assert copy.deepcopy(scene) == scene and copy.copy(scene) == scene


def test_equality_is_by_value_bit_for_bit():
    p = [[0.0, 0.0], [1.0, 2.0], [3.0, 1.0]]
    a, b = ss.Bezier(p), ss.Bezier(p)
    assert a == b and hash(a) == hash(b) and len({a, b}) == 1
    assert a != ss.Bezier([[0.0, 0.0], [1.0, 2.0], [3.0, np.nextafter(1.0, 2.0)]])
    assert a != ss.Bezier([[-0.0, 0.0], [1.0, 2.0], [3.0, 1.0]]), "-0 and 0 differ in bits"
    assert a != ss.RationalBezier(p, [1.0, 1.0, 1.0]), "another family"
    assert a != ss.Curve.from_dict(a.to_dict(), dim=3), "another dimension"
    assert (a == "a string") is False
    # Scenes compare by value, whatever the form of their text.
    s = ss.Scene([a])
    spaced = ss.Scene.from_json(s.to_json().replace(",", ", "))
    assert spaced == s and hash(spaced) == hash(s)
    assert ss.Scene([a, b]) != s


def test_the_module_exports_only_its_api():
    public = set(ss.__all__)
    assert {"Bezier", "Scene", "load", "stress_scene", "CurveError"} <= public
    for name in ("Any", "Dict", "List", "np", "json", "Union"):
        assert name not in public and name not in dir(ss)
    for name in public:
        assert hasattr(ss, name), name


def test_out_is_written_in_place_and_refused_when_it_does_not_fit():
    c = ss.BSpline([0, 0, 0, 0, 0.5, 1, 1, 1, 1], [[0, 0], [1, 2], [2, -1], [3, 1], [4, 0]], 4)
    t = np.linspace(0.0, 1.0, 101)
    for method, shape in (
        (c.eval, (101, 2)),
        (lambda t, out: c.derivative(t, 2, out=out), (101, 2)),
        (c.curvature, (101,)),
    ):
        want = method(t, None)
        out = np.full(shape, np.nan)
        got = method(t, out)
        assert got is out and np.array_equal(out, want)
    scalar = np.empty(())
    assert c.curvature(0.25, out=scalar) is scalar and scalar == c.curvature(0.25)
    bad = [
        (np.empty((101, 2), np.float32), "dtype float32"),
        (np.empty((100, 2)), "shape (100, 2), expected (101, 2)"),
        (np.empty((2, 101)).T, "C-contiguous"),
        ([[0.0, 0.0]] * 101, "not list"),
    ]
    for out, words in bad:
        with pytest.raises(ss.CurveError, match=re.escape(words)) as e:
            c.eval(t, out=out)
        assert e.value.path == "out"
    frozen = np.empty((101, 2))
    frozen.flags.writeable = False
    with pytest.raises(ss.CurveError, match="read-only"):
        c.eval(t, out=frozen)
    # Memory shared with the parameters being read is refused, not overwritten.
    buf = np.zeros(404)
    view_t, view_out = buf[:101], buf[:202].reshape(101, 2)
    view_t[:] = t
    with pytest.raises(ss.CurveError, match="shares memory"):
        c.eval(view_t, out=view_out)
    assert np.array_equal(view_t, t)

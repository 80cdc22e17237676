"""Every error class with the command line's message and path; the bad-input corpora
and mutated scenes and requests through the bindings (an exception of the module's, never
a crash or a panic); scenes saved without loss; several threads at once."""

import json
import random
import threading
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

import splinescope as ss

from conftest import ROOT, SCENES

BAD_SCENES = sorted((ROOT / "tests" / "bad_scenes").glob("*.json"))
BAD_REQUESTS = sorted(
    p for p in (ROOT / "tests" / "bad_requests").glob("*.json") if p.name != "scene.json"
)


def test_the_classes_are_value_errors_except_the_gpus():
    for cls in (ss.SceneError, ss.CurveError, ss.SolveError, ss.ImageError):
        assert issubclass(cls, ss.SplinescopeError)
        assert issubclass(cls, ValueError)
    assert issubclass(ss.GpuError, RuntimeError)
    assert ss.SceneError.__module__ == "splinescope"


@pytest.mark.parametrize("path", BAD_SCENES, ids=lambda p: p.stem)
def test_bad_scenes_fail_as_the_command_line_says(cli, path):
    out = cli("check", path, check=False)
    assert out.returncode != 0
    with pytest.raises(ss.SceneError) as e:
        ss.load(path)
    assert out.stderr.strip() == f"error: {e.value}", (out.stderr, str(e.value))
    # The offending value's JSON path, named in the message; empty for the document as a
    # whole (the message then names no path, and never "(root)").
    assert e.value.path in str(e.value)
    assert "(root)" not in str(e.value)
    if path.stem in ("empty-file", "not-json", "root-is-array"):
        assert e.value.path == ""
    else:
        assert e.value.path
    # The same text read from a string: the same error, without the file name.
    text = path.read_text(errors="replace")
    with pytest.raises(ss.SceneError) as e2:
        ss.Scene.from_json(text)
    assert str(e.value).endswith(str(e2.value))


@pytest.mark.parametrize("path", BAD_REQUESTS, ids=lambda p: p.stem)
def test_bad_requests_fail_as_the_command_line_says(cli, path, tmp_path):
    scene_path = ROOT / "tests" / "bad_requests" / "scene.json"
    out = cli("solve", scene_path, path, "-o", tmp_path / "out.json", check=False)
    assert out.returncode != 0
    scene = ss.load(scene_path)
    with pytest.raises(ss.SolveError) as e:
        ss.solve(scene, path.read_text())
    assert out.stderr.strip().endswith(str(e.value)), (out.stderr, str(e.value))
    assert not (tmp_path / "out.json").exists()


def test_curve_errors_name_the_value():
    b = ss.Bezier([[0, 0], [1, 1], [2, 0]])
    with pytest.raises(ss.CurveError) as e:
        b.eval(np.array([0.0, 0.5, 2.0]))
    assert e.value.path == "t[2]" and "t[2] = 2 is outside the domain [0, 1]" in str(e.value)
    with pytest.raises(ss.CurveError, match="t = NaN is outside"):
        b.eval(float("nan"))
    with pytest.raises(ValueError, match=r"shape \(2, 2\)"):
        b.eval(np.zeros((2, 2)))
    with pytest.raises(ss.CurveError, match=r"derivative: order = 3 is not between 1 and 2"):
        b.derivative(0.5, 3)
    with pytest.raises(ss.CurveError, match="knot insertion|inserted on the control polygon"):
        b.insert_knot(0.5)
    with pytest.raises(ss.CurveError, match="at least 2 points"):
        ss.Bezier([[0, 0], [1, 1]]).remove_point(0)
    with pytest.raises(ss.SceneError) as e:
        ss.Bezier([[0, 0], [1, np.inf]])
    assert e.value.path == "points[1][1]"
    with pytest.raises(ss.SceneError, match=r"shape \(3,\)"):
        ss.Bezier([0, 1, 2])
    m = ss.ModifiedBezier([[0, 0], [1, 1], [2, 0]], 0.5, [0, 1])
    with pytest.raises(ss.SceneError) as e:
        m.t_star = 1.0
    assert e.value.path == "t_star" and "open interval (0, 1)" in str(e.value)
    assert m.t_star == 0.5  # a refused value changes nothing
    n = ss.Nubmp(np.random.default_rng(1).uniform(size=(7, 2)), "clamped_uniform", 4)
    with pytest.raises(ss.SceneError, match="sums to"):
        n.set_group(2, [0.5, 0.6])


def test_image_and_gpu_errors():
    a = np.zeros((4, 5, 4), np.uint8)
    with pytest.raises(ss.ImageError, match="differs from the reference"):
        ss.compare_images(a, np.zeros((5, 4, 4), np.uint8))
    with pytest.raises(ss.ImageError, match="uint8"):
        ss.compare_images(a.astype(np.float32), a)
    with pytest.raises(ss.ImageError) as e:
        ss.compare_images(a, a, "channel=300")
    assert e.value.path == "tolerance"
    scene = ss.Scene([ss.Bezier([[0, 0], [1, 1]])])
    with pytest.raises(ss.GpuError, match="unknown GPU backend"):
        scene.render(10, 10, backend="glide")
    with pytest.raises(ss.GpuError, match="tolerance"):
        scene.render(10, 10, tolerance_px=0.0)


def mutate(value, rng):
    """One random change deep inside a JSON value."""
    if isinstance(value, dict) and value and rng.random() < 0.8:
        key = rng.choice(list(value))
        choice = rng.random()
        if choice < 0.15:
            del value[key]
        elif choice < 0.3:
            value[key] = rng.choice([None, "x", -1, 0, 1e308, [], {}, True, 2**64])
        else:
            value[key] = mutate(value[key], rng)
        return value
    if isinstance(value, list) and value and rng.random() < 0.8:
        i = rng.randrange(len(value))
        choice = rng.random()
        if choice < 0.2:
            del value[i]
        elif choice < 0.3:
            value.append(value[i])
        else:
            value[i] = mutate(value[i], rng)
        return value
    return rng.choice([None, "nan", -1e308, 1e-320, 0, -3, 0.5, 7, [0, 0], {"group": 0}, 1e30])


def test_mutated_scenes_and_requests_raise_the_modules_errors_only():
    rng = random.Random(20261202)
    scenes = [json.loads(p.read_text()) for p in sorted(SCENES.glob("*.json"))]
    requests = [json.loads(p.read_text()) for p in sorted((SCENES / "requests").glob("*.json"))]
    base = ss.load(SCENES / "solve_demo.json")
    ok = failed = 0
    for i in range(600):
        doc = mutate(json.loads(json.dumps(rng.choice(scenes))), rng)
        try:
            scene = ss.Scene.from_json(json.dumps(doc))
        except ss.SplinescopeError:
            failed += 1
            continue
        ok += 1
        for c in scene.curves:
            a, b = c.domain()
            vals = c.eval(np.linspace(a, b, 9))
            assert np.isfinite(vals).all(), (i, c)
            c.inspect()
        request = mutate(json.loads(json.dumps(rng.choice(requests))), rng)
        try:
            new, report = ss.solve(base, request)
        except ss.SplinescopeError:
            continue
        for c in new.curves:
            assert np.isfinite(c.control_points).all()
    assert ok > 20 and failed > 20, (ok, failed)


@pytest.mark.parametrize("path", sorted(SCENES.glob("*.json")), ids=lambda p: p.stem)
def test_unedited_load_and_save_keeps_the_bytes(path, tmp_path):
    out = tmp_path / path.name
    ss.load(path).save(out)
    assert out.read_bytes() == path.read_bytes()


def test_a_solved_scene_saves_what_the_command_line_writes(cli, tmp_path):
    src = SCENES / "solve_demo.json"
    for name in ("single_target.json", "all_methods.json"):
        req = SCENES / "requests" / name
        new, report = ss.solve(ss.load(src), json.loads(req.read_text()))
        out = tmp_path / "python.json"
        new.save(out)
        cli("solve", src, req, "-o", tmp_path / "cli.json")
        assert out.read_bytes() == (tmp_path / "cli.json").read_bytes(), name
        again = ss.load(out)
        for a, b in zip(again.curves, new.curves):
            np.testing.assert_array_equal(a.control_points, b.control_points)
    with pytest.raises(ss.SceneError, match="cannot write"):
        new.save(tmp_path / "no" / "such" / "dir" / "x.json")


def test_solvers_pass_through_their_targets_and_keep_tangents():
    b = ss.Bezier([[0, 0], [1, 2], [3, 2], [4, 0]])
    moved, report = b.pass_through([2, 3], t=0.5)
    np.testing.assert_allclose(moved.eval(0.5), [2, 3], atol=1e-12)
    assert report["method"] == "single_target"
    kept, _ = b.pass_through_keeping_tangents([2, 3], t=0.5)
    np.testing.assert_allclose(kept.eval(0.5), [2, 3], atol=1e-12)
    d0, d1 = b.derivative(np.array([0.0, 1.0]))
    k0, k1 = kept.derivative(np.array([0.0, 1.0]))
    assert abs(d0[0] * k0[1] - d0[1] * k0[0]) < 1e-12 and np.dot(d0, k0) > 0
    assert abs(d1[0] * k1[1] - d1[1] * k1[0]) < 1e-12 and np.dot(d1, k1) > 0
    targets = np.array([[1, 1.8], [3, 1.2]])
    many, _ = b.pass_through_all(targets, params=[0.3, 0.7])
    np.testing.assert_allclose(many.eval(np.array([0.3, 0.7])), targets, atol=1e-12)
    # Minimal: no other change of the moved points passes through the target with a
    # smaller total displacement (the least-squares change is along the basis values).
    # Here the interior points move (the report says which): Δ_i = B_i(½) d / Σ B_j(½)².
    delta = moved.control_points - b.control_points
    assert report["moved"] == [1, 2]
    w = np.array([0.0, 0.375, 0.375, 0.0])
    need = np.array([2, 3]) - b.eval(0.5)
    np.testing.assert_allclose(delta, np.outer(w, need) / np.dot(w, w), atol=1e-12)
    with pytest.raises(ss.SolveError, match="outside the domain"):
        b.pass_through([2, 3], t=1.5)


def test_nubmp_constrained_modification_moves_its_point():
    scene = ss.load(SCENES / "paper001_fig1.json")
    n = next(c for c in scene.curves if c.family == "nubmp")
    a, b = n.domain()
    tau = a + 0.4 * (b - a)
    target = n.eval(tau) + np.array([0.0, 0.05])[: n.dim]
    info = n.inspect()
    group = info["at_tau"]["group"] if "at_tau" in info else None
    for g in range(len(info.get("groups", [])) or 8):
        try:
            moved, report = n.constrained(target, tau, g if group is None else group)
        except ss.SolveError:
            continue
        np.testing.assert_allclose(moved.eval(tau), target, atol=1e-9)
        assert report["method"] == "nubmp_constrained"
        return
    pytest.fail("no group could move the point")


def test_several_threads_evaluate_render_free_and_agree():
    rng = np.random.default_rng(4)
    curve = ss.BSpline("clamped_uniform", rng.uniform(-1, 1, (200, 2)), 4)
    t = np.sort(rng.uniform(*curve.domain(), 200_000))
    want = curve.eval(t)
    barrier = threading.Barrier(4)

    def work(_):
        barrier.wait()
        return curve.eval(t)

    with ThreadPoolExecutor(4) as pool:
        for got in pool.map(work, range(4)):
            np.testing.assert_array_equal(got, want)
    # The GIL is released during the work: another thread runs meanwhile.
    ticks = []
    stop = threading.Event()

    def ticker():
        while not stop.is_set():
            ticks.append(1)

    th = threading.Thread(target=ticker)
    th.start()
    for _ in range(5):
        curve.eval(t)
    stop.set()
    th.join()
    assert len(ticks) > 5

"""Curves and scenes shipped to other processes — a process pool, joblib's, a real
two-worker Dask cluster — give what they give here: evaluation bit for bit, renders
pixel for pixel. Workers start as fresh interpreters (``spawn``) and are sent only
splinescope's own objects and functions (no function of this test module, which they
could not import); every wait is bounded."""

import concurrent.futures as cf
import multiprocessing as mp

import numpy as np
import pytest

import splinescope as ss

from test_render import BACKENDS

# Seconds any one wait on workers may take before the test fails.
WAIT = 180


def extra(name):
    """A test extra, or a failure saying how to install it (never a skip)."""
    try:
        return __import__(name, fromlist=["_"])
    except ImportError as e:  # pragma: no cover - depends on the environment
        pytest.fail(f"{name} is a test extra: scripts/python-dev installs it ({e})")


def curves():
    """A few curves of every family, planar and 3D."""
    out = []
    for family in ss.FAMILY_NAMES:
        out.extend(ss.stress_scene(2, family, 3, seed=3).curves)
    out.append(ss.Bezier([[0, 0, 0], [1, 2, 1], [3, 1, -1], [4, 0, 2]]))
    return out


def params(curve, n=1001):
    return np.linspace(*curve.domain(), n)


def test_a_process_pool_evaluates_shipped_curves_as_here():
    shipped = curves()
    with cf.ProcessPoolExecutor(2, mp_context=mp.get_context("spawn")) as pool:
        futures = [pool.submit(c.eval, params(c)) for c in shipped]
        got = [f.result(timeout=WAIT) for f in futures]
        # Whole curves travel too, and come back equal.
        back = pool.submit(ss.Curve.to_dict, shipped[0]).result(timeout=WAIT)
    for c, g in zip(shipped, got):
        assert np.array_equal(g, c.eval(params(c))), c
    assert back == shipped[0].to_dict()


def test_joblib_evaluates_shipped_curves_as_here():
    joblib = extra("joblib")
    shipped = curves()
    got = joblib.Parallel(n_jobs=2, backend="loky", timeout=WAIT)(
        joblib.delayed(c.curvature)(params(c)) for c in shipped
    )
    for c, g in zip(shipped, got):
        assert np.array_equal(g, c.curvature(params(c)), equal_nan=True), c


@pytest.fixture(scope="module")
def cluster():
    """A two-worker local Dask cluster (two processes, one thread each)."""
    distributed = extra("distributed")
    with distributed.LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=True,
        dashboard_address=None,
        silence_logs=40,
    ) as c, distributed.Client(c, timeout=WAIT) as client:
        client.wait_for_workers(2, timeout=WAIT)
        yield client


def test_dask_array_map_blocks_evaluates_on_two_workers_as_here(cluster):
    da = extra("dask.array")
    curve = ss.stress_scene(1, "nurbs", 3, seed=11).curves[0]
    a, b = curve.domain()
    t = da.linspace(a, b, 400_000, chunks=50_000)
    points = da.map_blocks(
        curve.eval, t, new_axis=1, chunks=(t.chunks[0], (curve.dim,)), dtype=np.float64
    )
    got = cluster.compute(points).result(timeout=WAIT)
    local_t = cluster.compute(t).result(timeout=WAIT)
    assert got.shape == (400_000, curve.dim)
    assert np.array_equal(got, curve.eval(local_t))
    # Both workers took part.
    assert len(cluster.scheduler_info()["workers"]) == 2


@pytest.mark.parametrize("backend", BACKENDS)
def test_dask_bag_renders_scenes_on_two_workers_as_here(cluster, backend):
    db = extra("dask.bag")
    scenes = [ss.stress_scene(9, f, 3, seed=5) for f in ("bezier", "nurbs", "nubmp")]
    shipped = db.from_sequence(scenes, npartitions=2).map(
        ss.Scene.render, width=160, height=100, backend=backend
    )
    try:
        images = cluster.compute(shipped).result(timeout=WAIT)
    except ss.GpuError as e:  # pragma: no cover - depends on the machine
        pytest.fail(f"a worker could not render: {e}")
    for scene, image in zip(scenes, images):
        here = scene.render(160, 100, backend=backend)
        report = ss.compare_images(image, here, "channel=0,pixels=0%")
        assert report["matches"], report


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_scene_rendered_in_another_process_is_the_same_picture(backend):
    # Default palette colours and a solve's annotations travel exactly too.
    scene = ss.Scene([ss.Bezier([[0, 0], [1, 2], [3, 1]]), ss.Nurbs.circle([1, 0], 1.0)])
    scene, _ = scene.solve({"method": "single_target", "curve": 0, "target": [1.5, 1.5]})
    here = scene.render(160, 100, backend=backend)
    with cf.ProcessPoolExecutor(1, mp_context=mp.get_context("spawn")) as pool:
        there = pool.submit(ss.Scene.render, scene, 160, 100, 0.25, backend).result(timeout=WAIT)
    assert np.array_equal(here, there)

"""10⁸ parameters of a cubic B-spline evaluated through Dask: a local cluster of one
worker process, then of two (one thread each, the module pinned to one thread in each),
the same graph — ``dask.array.map_blocks(curve.eval, …)`` over chunks of 10⁶ parameters,
summed on the workers so that only the sums travel back. Prints one JSON object with
both times and their ratio. Run by scripts/bench-python."""

import json
import time

import numpy as np

N = 100_000_000
CHUNK = 1_000_000


def run(workers):
    import dask.array as da
    from distributed import Client, LocalCluster

    import splinescope as ss

    rng = np.random.default_rng(1)
    knots = np.concatenate([[0.0] * 4, np.sort(rng.uniform(0, 1, 996)), [1.0] * 4])
    curve = ss.BSpline(knots, rng.uniform(-1, 1, (1000, 2)), 4)
    with LocalCluster(
        n_workers=workers,
        threads_per_worker=1,
        processes=True,
        dashboard_address=None,
        silence_logs=40,
        env={"RAYON_NUM_THREADS": "1"},
    ) as cluster, Client(cluster) as client:
        client.wait_for_workers(workers, timeout=120)
        # j / (N − 1): exactly 0 and 1 at the ends (da.linspace may overshoot 1 by an ulp).
        t = da.arange(N, chunks=CHUNK, dtype=np.float64) / (N - 1)
        points = da.map_blocks(curve.eval, t, new_axis=1, chunks=(t.chunks[0], (2,)), dtype=np.float64)
        total = points.sum(axis=0)
        # Once to warm the workers (imports, the curve's first use), then timed.
        client.compute(total).result(timeout=600)
        best = float("inf")
        for _ in range(3):
            start = time.perf_counter()
            value = client.compute(total).result(timeout=600)
            best = min(best, time.perf_counter() - start)
    return best, value


def main():
    one, v1 = run(1)
    two, v2 = run(2)
    assert np.allclose(v1, v2, rtol=1e-12), (v1, v2)
    print(
        json.dumps(
            {
                "parameters": N,
                "chunk": CHUNK,
                "one_worker_s": one,
                "two_workers_s": two,
                "two_over_one": one / two,
            }
        )
    )


if __name__ == "__main__":
    main()

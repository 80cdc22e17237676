"""Structured fuzzing of the Python module: curves from the repository's scenes and from
seeds with extreme rational weights, mutated field by field (extreme, subnormal and
non-finite numbers, other types, arrays cut short or grown, keys removed, families
swapped), then every method called with random and hostile arguments.

Invariants:

* only the module's exceptions (``SplinescopeError`` and its subclasses, ``GpuError``),
  ``TypeError`` or ``ValueError`` are raised, each with a message; never an
  ``AttributeError``, ``IndexError``, ``KeyError``, ``OverflowError`` or a Rust panic;
* finite input inside the domain gives finite output (a curvature of NaN only where the
  first derivative is 0);
* a solve that returns meets its targets (or says it was solved in least squares);
* every call returns within a time bound (the caller bounds memory and the whole run).

Run by ``test_fuzz.py`` in a child process (a bounded number of cases from a fixed
seed), or for a while from a fresh seed: ``scripts/fuzz --only python --minutes N``.
Prints one JSON line: the cases, the seed and the failures.
"""

from __future__ import annotations

import json
import math
import random
import sys
import tempfile
import time
import traceback
from pathlib import Path

import numpy as np

import splinescope as ss

ROOT = Path(__file__).resolve().parents[3]
ALLOWED = (ss.SplinescopeError, ss.GpuError, TypeError, ValueError)
EXTREMES = [
    0.0, -0.0, 5e-324, -5e-324, 2.2250738585072014e-308, 1e-300, 1e-12, 0.5, 1.0, -1.0,
    2.0, 3.0, 1e15, 1e20, 1e38, 1e300, 1e308, -1e308, sys.float_info.max,
    -sys.float_info.max, math.nan, math.inf, -math.inf,
]
INTS = [0, 1, 2, 3, 5, -1, -2**31, 2**31, 2**40, 2**63, 2**64, 2**100, 7, 64, 65, 1000, 1001]
FAMILIES = ["bezier", "modified_bezier", "interpolation", "bspline", "nubmp", "rational_bezier", "nurbs", "path"]
SLOW = 5.0  # seconds one call may take


def seeds() -> list:
    curves = []
    for path in sorted((ROOT / "scenes").glob("*.json")):
        doc = json.loads(path.read_text())
        curves.extend(doc.get("curves", []))
    curves += [
        {"type": "rational_bezier", "points": [[0, 0], [1, 2], [3, 0]], "weights": [1e300, 1e300, 2e300]},
        {"type": "rational_bezier", "points": [[0, 1], [2, 3], [4, 1], [5, 2]], "weights": [1e-300, 3e-300, 1e-300, 2e-300]},
        {"type": "rational_bezier", "points": [[0, 0], [1, 2], [3, 0.5], [4, 3]], "weights": [2.0**-1000, 1, 1, 2.0**1000]},
        {"type": "nurbs", "points": [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1], [1, 0]],
         "weights": [1, 0.7071067811865476, 1, 0.7071067811865476, 1, 0.7071067811865476, 1, 0.7071067811865476, 1],
         "knots": [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1], "order": 3},
        {"type": "bezier", "points": [[0, 0, 0], [1e-310, 2e-310, 1e-310], [3e-310, 0, 0]]},
    ]
    return curves


def paths(v, prefix=()):
    yield prefix
    if isinstance(v, dict):
        for k, x in v.items():
            yield from paths(x, prefix + (k,))
    elif isinstance(v, list):
        for i, x in enumerate(v):
            yield from paths(x, prefix + (i,))


def mutate(doc, rng: random.Random):
    doc = json.loads(json.dumps(doc))
    for _ in range(rng.randint(0, 3)):
        all_paths = list(paths(doc))
        path = rng.choice(all_paths)
        if not path:
            continue
        parent = doc
        for step in path[:-1]:
            parent = parent[step]
        key = path[-1]
        value = parent[key]
        r = rng.random()
        if r < 0.4:
            parent[key] = rng.choice(EXTREMES)
        elif r < 0.5:
            parent[key] = rng.choice([None, True, "x", [], {}, -1, "clamped_uniform", 2**70, 3.5])
        elif r < 0.6 and isinstance(value, list) and value:
            del value[rng.randrange(len(value)):]
        elif r < 0.7 and isinstance(value, list) and value:
            item = rng.choice(value)
            value.extend([item] * rng.choice([1, 3, 40]))
        elif r < 0.8 and isinstance(value, dict) and value:
            del value[rng.choice(list(value))]
        elif r < 0.9 and isinstance(parent, dict) and key == "type":
            parent[key] = rng.choice(FAMILIES)
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            parent[key] = value * rng.choice([-1, 2, 1e-300, 1e300]) if math.isfinite(value) else 0
    return doc


def number(rng: random.Random, lo: float = 0.0, hi: float = 1.0):
    r = rng.random()
    if r < 0.6:
        return rng.uniform(lo, hi)
    if r < 0.7:
        return rng.choice([lo, hi])
    if r < 0.9:
        return rng.choice(EXTREMES)
    return rng.choice([None, "0.5", [0.5], np.float32(0.25), np.int64(0), 10**400, True])


def whole(rng: random.Random):
    r = rng.random()
    if r < 0.7:
        return rng.choice(INTS)
    return rng.choice([1.0, 2.5, "3", None, True, np.int64(3), np.uint8(2), -0.0])


class Fuzz:
    def __init__(self, seed: int):
        self.rng = random.Random(seed)
        self.seed = seed
        self.failures: list = []
        self.cases = 0
        self.calls = 0
        self.outcomes = {"returned": 0, "refused": 0}
        self.tmp = Path(tempfile.mkdtemp(prefix="splinescope-fuzz-"))

    def fail(self, what: str) -> None:
        self.failures.append(what)

    def call(self, what: str, fn, *args, **kwargs):
        """Calls ``fn``; returns its result or None when it raised an allowed exception."""
        self.calls += 1
        started = time.monotonic()
        try:
            out = fn(*args, **kwargs)
            self.outcomes["returned"] += 1
            return out
        except ALLOWED as e:
            self.outcomes["refused"] += 1
            if not str(e):
                self.fail(f"{what}: {type(e).__name__} without a message")
            if isinstance(e, ss.SplinescopeError) and not hasattr(e, "path"):
                self.fail(f"{what}: {type(e).__name__} without a path: {e}")
            return None
        except BaseException as e:  # noqa: BLE001 - the point is to catch anything else
            if isinstance(e, KeyboardInterrupt):
                raise
            self.fail(f"{what}: {type(e).__name__}: {e}\n{traceback.format_exc(limit=3)}")
            return None
        finally:
            took = time.monotonic() - started
            if took > SLOW:
                self.fail(f"{what}: took {took:.1f} s")

    def finite(self, what: str, value) -> None:
        a = np.asarray(value, dtype=np.float64)
        if not np.all(np.isfinite(a)):
            self.fail(f"{what}: a non-finite value {a.ravel()[~np.isfinite(a.ravel())][:3]}")

    def curve_case(self, docs: list) -> None:
        rng = self.rng
        doc = mutate(rng.choice(docs), rng)
        label = json.dumps(doc, default=str)[:400]
        c = self.call(f"from_dict {label}", ss.Curve.from_dict, doc)
        if c is None:
            return
        a, b = c.domain()
        inside = [a, b, 0.5 * (a + b)] + [rng.uniform(a, b) for _ in range(3)]
        for t in inside:
            p = self.call(f"eval({t!r}) of {label}", c.eval, t)
            if p is not None:
                self.finite(f"eval({t!r}) of {label}", p)
            for order in (1, 2):
                d = self.call(f"derivative({t!r}, {order}) of {label}", c.derivative, t, order)
                if d is not None:
                    self.finite(f"derivative({t!r}, {order}) of {label}", d)
            k = self.call(f"curvature({t!r}) of {label}", c.curvature, t)
            if k is not None and not (isinstance(k, float) and math.isnan(k)):
                self.finite(f"curvature({t!r}) of {label}", k)
                if k < 0:
                    self.fail(f"curvature({t!r}) of {label}: negative {k}")
            elif k is not None:
                d1 = self.call("derivative for NaN curvature", c.derivative, t, 1)
                if d1 is not None and np.any(np.asarray(d1) != 0):
                    self.fail(f"curvature({t!r}) of {label}: NaN where P' = {d1}")
        arr = np.array(inside)
        for name in ("eval", "derivative", "curvature"):
            out = self.call(f"{name}(array) of {label}", getattr(c, name), arr)
            if out is not None:
                out = np.asarray(out)
                if name == "curvature":
                    out = out[~np.isnan(out)]
                self.finite(f"{name}(array) of {label}", out)
        # Hostile arguments to every method.
        self.call("eval(hostile)", c.eval, number(rng, a, b))
        self.call("derivative(hostile)", c.derivative, number(rng, a, b), whole(rng))
        self.call("curvature(hostile)", c.curvature, number(rng, a, b))
        s = self.call("sample", c.sample, whole(rng))
        if s is not None:
            self.finite(f"sample of {label}", s)
        self.call("segments", c.segments)
        self.call("inspect", c.inspect)
        self.call("summary", c.summary)
        self.call("repr", repr, c)
        self.call("insert_knot", c.insert_knot, number(rng, a, b))
        self.call("insert_point", c.insert_point, [number(rng, -2, 2) for _ in range(c.dim)])
        self.call("remove_point", c.remove_point, whole(rng))
        self.call("elevate", c.elevate, whole(rng))
        target = [number(rng, -2, 3) for _ in range(c.dim)]
        for method, kwargs in (
            ("pass_through", {"t": number(rng, a, b) if rng.random() < 0.7 else None,
                              "first": whole(rng) if rng.random() < 0.3 else None,
                              "count": whole(rng) if rng.random() < 0.3 else None}),
            ("pass_through_keeping_tangents", {"t": number(rng, a, b) if rng.random() < 0.7 else None}),
        ):
            out = self.call(f"{method}{kwargs} of {label}", getattr(c, method), target, **kwargs)
            if out is not None:
                self.solved(f"{method}{kwargs} of {label}", out, [target], c)
        targets = [[number(rng, -2, 3) for _ in range(c.dim)] for _ in range(rng.randint(1, 4))]
        params = [number(rng, a, b) for _ in targets] if rng.random() < 0.6 else None
        out = self.call(f"pass_through_all({targets}, {params}) of {label}", c.pass_through_all, targets, params)
        if out is not None:
            self.solved(f"pass_through_all of {label}", out, targets, c)
        # The analysis: hostile arguments refused, answers finite.
        length = self.call("length", c.length, number(rng, a, b), number(rng, a, b), rng.choice([1e-12, 1e-6, 0.0, -1.0, math.nan, "x"]))
        if length is not None:
            self.finite(f"length of {label}", length)
        self.call("parameter_at_length", c.parameter_at_length, number(rng, 0.0, 2.0))
        box = self.call("bbox", c.bbox)
        if box is not None:
            self.finite(f"bbox of {label}", box)
        for name in ("extrema", "inflections", "cusps", "curvature_extrema", "signed_area", "self_intersections"):
            out = self.call(f"{name} of {label}", getattr(c, name))
            if out is not None:
                self.finite(f"{name} of {label}", out)
        # Joints: finite parameters, gaps and angles (0 to π); a jump from 0 to 2, or inf
        # where a speed vanishes, never NaN.
        j = self.call(f"joints of {label}", c.joints)
        if j is not None:
            j = np.asarray(j, dtype=np.float64).reshape(-1, 4)
            self.finite(f"joints of {label}", j[:, :3])
            if ((j[:, 2] < 0) | (j[:, 2] > math.pi + 1e-12)).any():
                self.fail(f"joints of {label}: an angle outside [0, π]: {j[:, 2]}")
            jump = j[:, 3]
            if np.isnan(jump).any() or ((jump < 0) | ((jump > 2 + 1e-9) & np.isfinite(jump))).any():
                self.fail(f"joints of {label}: a curvature jump outside [0, 2]: {jump}")
        other = (self.call("other", ss.Curve.from_dict, rng.choice(docs)) if rng.random() < 0.5 else c) or c
        st = self.call(f"intersect of {label}", c.intersect, rng.choice([other, None, 3]))
        if st is not None:
            self.finite(f"intersect of {label}", st)
        self.call("to_dict round trip", lambda: ss.Curve.from_dict(c.to_dict()))
        many = self.call("eval_many", ss.eval_many, [c, c] if rng.random() < 0.8 else [c, None], whole(rng))
        if many is not None:
            self.finite(f"eval_many of {label}", many)
        if rng.random() < 0.1:
            scene = self.call("Scene", ss.Scene, [c], name=rng.choice([None, "s", "a\x01", 3]))
            if scene is not None:
                ext = rng.choice(["svg", "pdf"])
                self.call(
                    "export",
                    scene.export,
                    self.tmp / f"f.{ext}",
                    width=rng.choice([1, 10, 50, 400, 16385, 0, 2.5]),
                    height=rng.choice([1, 10, 300, -3]),
                    tolerance=rng.choice([0.01, 1e-6, 1e-14, 5.0, math.nan, -1.0]),
                    labels=rng.choice([True, False, "yes"]),
                    legend=rng.choice([True, False]),
                )
                self.call("to_json", lambda: ss.Scene.from_json(scene.to_json()))

    def analysis_case(self) -> None:
        """The analysis against what geometry guarantees, on curves at the extremes:
        coordinates from 1e-300 to 1e300, weights as far apart as 1e600. A length (with
        its stated error) lies between the chord and the control polygon; the box holds
        dense samples of the curve and lies in the control points' box; a line's hits lie
        on the line; a parameter at a length inside the curve is in the domain, one beyond
        it is refused."""
        rng = self.rng
        degree = rng.choice([1, 2, 3, 3, 5, 7])
        scale = rng.choice([1.0, 1.0, 1e-300, 1e-150, 1e150, 1e200, 1e300, 1e-10, 1e10])
        pts = np.array([[rng.uniform(-4, 4), rng.uniform(-4, 4)] for _ in range(degree + 1)]) * scale
        far = [1e-300, 1e-100, 1e-20, 1.0, 1e20, 1e100, 1e300]
        rational = rng.random() < 0.6
        # Weights far apart at moderate scales; at the ends of the double range, moderate
        # weights (a weight times a coordinate must stay a normal double: the documented
        # limit).
        extreme_scale = not (1e-100 <= scale <= 1e100)
        weights = [
            rng.choice(far) if rng.random() < 0.5 and not extreme_scale else rng.uniform(0.1, 10)
            for _ in pts
        ]
        label = f"degree {degree} ×{scale:g} weights {weights if rational else None}: {pts.tolist()}"
        c = self.call(
            f"curve {label}",
            ss.RationalBezier if rational else ss.Bezier,
            *((pts, weights) if rational else (pts,)),
        )
        if c is None:
            return
        report = self.call(f"analyze {label}", c.analyze)
        if report is not None:
            length, error = report["length"], report["length_error"]
            chord = float(np.linalg.norm((pts[-1] - pts[0]) / scale)) * scale
            polygon = float(np.sum(np.linalg.norm(np.diff(pts / scale, axis=0), axis=1))) * scale
            slack = 1e-12 * polygon
            if not (length + error >= chord - slack and length - error <= polygon + slack):
                self.fail(
                    f"length of {label}: {length} ± {error} outside [chord {chord}, polygon {polygon}]"
                )
        box = self.call(f"bbox {label}", c.bbox)
        if box is not None:
            box = np.asarray(box)
            samples = np.asarray(c.eval(np.linspace(0.0, 1.0, 2001)))
            span = float(np.abs(pts).max())
            slack = 1e-9 * span
            if np.any(samples < box[0] - slack) or np.any(samples > box[1] + slack):
                self.fail(f"bbox of {label}: {box.tolist()} misses a sample of the curve")
            if np.any(box[0] < pts.min(axis=0) - slack) or np.any(box[1] > pts.max(axis=0) + slack):
                self.fail(f"bbox of {label}: {box.tolist()} leaves the control points' box")
        p = np.array([rng.uniform(-4, 4), rng.uniform(-4, 4)]) * scale
        q = p + np.array([rng.uniform(-1, 1), rng.uniform(-1, 1)]) * rng.choice([scale, 1e-300, 1e-200, 5e-324])
        hits = self.call(f"intersect_line {p.tolist()} {q.tolist()} of {label}", c.intersect_line, p, q)
        if hits is not None:
            params = hits[0]
            d = q - p
            unit = d / np.abs(d).max()
            for t, lam in np.asarray(params).reshape(-1, 2):
                if not np.isfinite(lam):
                    self.fail(f"intersect_line of {label}: λ = {lam} is not finite")
                    continue
                # The curve's point at the hit lies on the line (where its parameter is a
                # double: rounding puts the rest between two doubles). With weights more
                # than 2^40 apart, evaluation in t loses terms to underflow (u³ of a tiny
                # u) that the analysis keeps (it works in the logistic parameter): no
                # check there.
                if rational and max(weights) / min(weights) > 2.0**40:
                    continue
                at = np.asarray(c.eval(t))
                off = abs(float(np.cross(unit, (at - p)))) / float(np.linalg.norm(unit))
                if 0.0 < t < 1.0 and off > 1e-6 * span:
                    self.fail(f"intersect_line of {label}: the curve at the hit t = {t} is {off} off the line")
        if report is not None and report["length"] > 0:
            total = report["length"]
            t = self.call(f"parameter_at_length of {label}", c.parameter_at_length, rng.uniform(0, total))
            if t is not None and not (0.0 <= t <= 1.0):
                self.fail(f"parameter_at_length of {label}: {t} outside the domain")
            # Beyond the length by more than the (absolute) accuracy, 1e-12.
            for beyond in (2 * total, 1e308, math.inf):
                if beyond > total * (1 + 1e-9) + 1.1e-12:
                    try:
                        out = c.parameter_at_length(beyond)
                        self.fail(f"parameter_at_length({beyond}) of {label} (length {total}): {out}, not refused")
                    except ALLOWED:
                        pass

    def solved(self, what: str, out, targets, original) -> None:
        """A returned solve meets each target within 1e-7 of the target's and the original
        curve's size (the module promises 1e-9 of the terms it sums), unless it says it
        was solved in least squares."""
        curve, report = out
        size = float(np.abs(original.control_points).max())
        params = report.get("params") or ([report["t"]] if "t" in report else None)
        if params is None:
            return
        least = report.get("least_squares", False)
        for t, target in zip(params, targets):
            if t is None:
                continue
            try:
                p = np.asarray(curve.eval(t))
            except ALLOWED as e:
                self.fail(f"{what}: the solved curve cannot be evaluated at its target's t = {t}: {e}")
                continue
            target = np.asarray(target, dtype=float)
            gap = float(np.abs(p[: len(target)] - target).max())
            scale = float(np.abs(target).max()) + size + 1e-300
            if not least and not gap <= 1e-7 * scale:
                self.fail(f"{what}: misses its target by {gap} at t = {t} ({report})")

    def run(self, cases: int, seconds: float) -> None:
        docs = seeds()
        started = time.monotonic()
        while True:
            if seconds > 0 and time.monotonic() - started > seconds:
                break
            if seconds <= 0 and self.cases >= cases:
                break
            self.curve_case(docs)
            self.analysis_case()
            self.cases += 1
            if len(self.failures) >= 10:
                break


def main(argv: list) -> int:
    seed, cases, seconds = 20261202, 2000, 0.0
    args = list(argv)
    while args:
        flag = args.pop(0)
        if flag == "--seed":
            seed = int(args.pop(0))
        elif flag == "--cases":
            cases = int(args.pop(0))
        elif flag == "--seconds":
            seconds = float(args.pop(0))
        else:
            print(f"usage: fuzz_module.py [--seed S] [--cases N] [--seconds T], not {flag}", file=sys.stderr)
            return 2
    f = Fuzz(seed)
    started = time.monotonic()
    f.run(cases, seconds)
    print(json.dumps({
        "cases": f.cases,
        "calls": f.calls,
        "seed": seed,
        "seconds": round(time.monotonic() - started, 1),
        "outcomes": f.outcomes,
        "failures": f.failures,
    }))
    return 1 if f.failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

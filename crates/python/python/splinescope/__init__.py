"""splinescope for Python: curve families, least-squares shape modification and GPU
rendering on numpy arrays.

Curves take the scene format's fields (``docs/scene-format.md``) and are checked exactly
as ``splinescope check`` checks a scene file, with the same messages. Points are
``(N, 2)`` or ``(N, 3)`` float64 arrays; results keep the dimension of the input.

Families (each class's docstring states its formula and paper):

* :class:`Bezier` — Bézier curves of any degree (paper 002).
* :class:`ModifiedBezier` — ``R(t) = Q(t) + S(t) v`` with a C¹ bump ``S`` (paper 002, §4).
* :class:`Interpolation` — cubic Bézier interpolation, plain or modified (paper 002, §5).
* :class:`BSpline` — non-uniform B-splines (paper 001, §2), to and from scipy.
* :class:`Nubmp` — B-splines with multiple shape parameters (paper 001, §3–5).
* :class:`RationalBezier` — rational Bézier curves (conics exactly).
* :class:`Path` — Bézier segments of any degree (each may be rational) joined end to end.
* :class:`Nurbs` — NURBS curves (the exact circle: :meth:`Nurbs.circle`).

Papers: 000 — least-squares shape modification of Bézier curves; 001 — NUBMP curves;
002 — the modified Bézier curve and cubic interpolation (texts and a clean statement of
the mathematics in the repository's ``docs/math.md``).
"""

from __future__ import annotations

import json
import warnings
import re
from typing import Any, Dict, Iterator, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _splinescope as _native
from ._splinescope import (
    CurveError,
    GpuError,
    ImageError,
    SceneError,
    SolveError,
    SplinescopeError,
)

__all__ = [
    "Curve",
    "Bezier",
    "ModifiedBezier",
    "Interpolation",
    "BSpline",
    "Nubmp",
    "RationalBezier",
    "Nurbs",
    "Path",
    "Scene",
    "load",
    "stress_scene",
    "solve",
    "eval_many",
    "intersections",
    "join",
    "fit_bezier",
    "fit_bspline",
    "fit_path",
    "compare_images",
    "FAMILY_NAMES",
    "SOLVE_METHODS",
    "SplinescopeError",
    "SceneError",
    "CurveError",
    "SolveError",
    "ImageError",
    "GpuError",
]



def __dir__() -> List[str]:
    """The public API (``__all__``) and the version: not the names the module imports."""
    return sorted(__all__ + ["__version__"])


__version__: str = _native.__version__
#: The families' names in scene files, in the order of the family table.
FAMILY_NAMES: List[str] = list(_native.FAMILY_NAMES)
#: The solve methods of ``docs/solve-format.md``.
SOLVE_METHODS: List[str] = list(_native.SOLVE_METHODS)

ArrayLike = Any
Report = Dict[str, Any]


def _error(cls: type, message: str, path: str) -> Exception:
    e = cls(message)
    e.path = path  # type: ignore[attr-defined]
    return e


def _no_strings(value: Any, what: str) -> None:
    """A :class:`TypeError` naming ``what`` where ``value`` holds text (numpy would read
    ``"0.5"`` as a number)."""
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{what} must be numbers, not {type(value).__name__} {value!r}")
    if isinstance(value, (list, tuple, np.ndarray)):
        try:
            kind = np.asarray(value).dtype.kind
        except (TypeError, ValueError):
            return  # ragged: refused below as not numbers
        if kind in "USO" and any(
            isinstance(x, (str, bytes, np.str_, np.bytes_)) for x in np.asarray(value).flat
        ):
            raise TypeError(f"{what} must be numbers, not text ({_short(value)})")


def _short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _array(value: ArrayLike, what: str, shape_ok: Any, expected: str) -> np.ndarray:
    """``value`` as a float64 array of an accepted shape with finite numbers, or a
    :class:`SceneError` naming ``what``."""
    _no_strings(value, what)
    try:
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError, OverflowError) as e:
        raise _error(SceneError, f"{what}: not numbers ({e})", what) from None
    if not shape_ok(a.shape):
        raise _error(SceneError, f"{what} must be {expected}; got shape {a.shape}", what)
    _finite(a, what)
    return a


def _points(points: ArrayLike, what: str) -> Tuple[List[List[float]], int]:
    """Points as JSON lists, checked: shape (N, 2) or (N, 3), finite numbers."""
    a = _array(
        points,
        what,
        lambda s: len(s) == 2 and s[1] in (2, 3),
        "an array of shape (N, 2) or (N, 3)",
    )
    return a.tolist(), int(a.shape[1])


def _point(p: ArrayLike, what: str) -> List[float]:
    return _array(
        p, what, lambda s: len(s) == 1 and s[0] in (2, 3), "a point of 2 or 3 numbers"
    ).tolist()


def _numbers(v: ArrayLike, what: str) -> List[float]:
    return _array(v, what, lambda s: len(s) == 1, "a 1-D array of numbers").tolist()


def _finite(a: np.ndarray, what: str) -> None:
    bad = np.argwhere(~np.isfinite(a))
    if len(bad):
        index = "".join(f"[{int(i)}]" for i in bad[0])
        value = a[tuple(bad[0])]
        raise _error(
            SceneError,
            f"{what}{index}: {value} is not a finite number",
            f"{what}{index}",
        )


def _int(x: Any, what: str, lo: int = 0, hi: int = 2**63 - 1, method: str = "") -> int:
    """``x`` as a whole number in ``lo..=hi``: a :class:`TypeError` for anything that is
    not an integer (a float, a bool, a string), a :class:`CurveError` (a ``ValueError``)
    for one out of range, each naming the argument and the method."""
    where = f"{method}: " if method else ""
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, np.integer)):
        raise TypeError(
            f"{where}{what} must be a whole number (int), not {type(x).__name__} {x!r}"
        )
    v = int(x)
    if v < lo or v > hi:
        # In words; a bound only the machine sets (2⁶³ − 1 and above) is not worth saying.
        if hi >= 2**63 - 1:
            why = f"is below {lo}" if v < lo else "is too large"
        else:
            why = f"is not between {lo} and {hi}"
        raise _error(CurveError, f"{where}{what} = {v} {why}", what)
    return v


def _bool(x: Any, what: str, method: str = "") -> bool:
    """``x`` as ``True``/``False``; a :class:`TypeError` naming the argument otherwise."""
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    where = f"{method}: " if method else ""
    raise TypeError(f"{where}{what} must be True or False, not {type(x).__name__} {x!r}")


def _hits(st: Any, kinds: Any, errors: Any, want_kinds: bool, want_errors: bool) -> Any:
    """The pairs alone, or with the kinds and/or the error bounds asked for, in that order."""
    if not (want_kinds or want_errors):
        return st
    extras = ([kinds] if want_kinds else []) + ([errors] if want_errors else [])
    return tuple([st] + extras)


def _str(x: Any, what: str, method: str = "") -> str:
    """``x`` if it is a string; a :class:`TypeError` naming the argument otherwise."""
    if isinstance(x, str):
        return x
    where = f"{method}: " if method else ""
    raise TypeError(f"{where}{what} must be a string, not {type(x).__name__} {x!r}")


def _float(x: Any, what: str, method: str = "") -> float:
    """``x`` as a float (a number of any kind); a :class:`TypeError` naming the argument
    for anything else. Its range is the method's to check."""
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, float, np.integer, np.floating)):
        where = f"{method}: " if method else ""
        raise TypeError(f"{where}{what} must be a number, not {type(x).__name__} {x!r}")
    try:
        return float(x)
    except OverflowError:
        raise _error(CurveError, f"{method}: {what} = {x} is beyond float64", what) from None


def _short_array(a: np.ndarray) -> str:
    """An array on one line as numpy prints it, elided past four rows."""
    text = np.array2string(
        np.asarray(a), separator=", ", threshold=8, edgeitems=2, max_line_width=10**6,
        precision=6, suppress_small=True,
    )
    # One line, without numpy's column padding.
    return re.sub(r"\[\s+", "[", re.sub(r"\s+", " ", text))


def _curve(c: Any, what: str) -> Any:
    """The native curve of ``c``; a :class:`TypeError` naming ``what`` when ``c`` is not
    a :class:`Curve`."""
    if not isinstance(c, Curve):
        raise TypeError(
            f"{what} must be a Curve (Bezier, BSpline, Nurbs, …), not {type(c).__name__} {c!r}"
        )
    return c._c


def _json(v: Any, path: str) -> Any:
    """``v`` as plain JSON data (numpy arrays and scalars converted), every number finite:
    a :class:`SceneError` naming the path of a NaN or infinity (``points[2][1]``,
    ``shape[0].values[1]``), a :class:`TypeError` naming the path of a value JSON cannot
    hold."""
    if isinstance(v, np.ndarray):
        v = v.tolist()
    elif isinstance(v, np.generic):
        v = v.item()
    if v is None or isinstance(v, (bool, str)):
        return v
    if isinstance(v, int):
        return v
    if isinstance(v, float):
        if not np.isfinite(v):
            raise _error(SceneError, f"{path or 'value'}: {v} is not a finite number", path)
        return v
    if isinstance(v, dict):
        out = {}
        for k, x in v.items():
            if not isinstance(k, str):
                raise TypeError(f"{path or 'the object'}: key {k!r} is not a string")
            out[k] = _json(x, f"{path}.{k}" if path else k)
        return out
    if isinstance(v, (list, tuple)):
        return [_json(x, f"{path}[{i}]") for i, x in enumerate(v)]
    raise TypeError(f"{path or 'value'}: {type(v).__name__} {v!r} is not JSON data")


def _dumps(obj: Any, path: str = "") -> str:
    return json.dumps(_json(obj, path), allow_nan=False)


def _number(x: Any, what: str) -> float:
    try:
        v = float(x)
    except (TypeError, ValueError, OverflowError):
        raise _error(SceneError, f"{what}: {x!r} is not a number", what) from None
    if not np.isfinite(v):
        raise _error(SceneError, f"{what}: {v} is not a finite number", what)
    return v


def _curve_from_state(text: str, dim: int) -> "Curve":
    """A pickled curve back from its scene-format text and dimension."""
    return Curve._wrap(_native._Curve.from_json(text, dim))


class Curve:
    """A curve of one of the families; construct it through its family's class.

    Every method takes parameters ``t`` as a number (results of shape ``(dim,)``) or a
    1-D array (results ``(N, dim)``); contiguous float64 arrays are read without a copy.
    A parameter outside the domain is refused (:class:`CurveError` naming it).
    """

    __slots__ = ("_c",)
    _family = ""

    def __init__(self) -> None:  # pragma: no cover - abstract
        raise TypeError("construct a curve through its family: Bezier, BSpline, …")

    # -- construction ---------------------------------------------------------------

    def _set(self, obj: Dict[str, Any], dim: Optional[int]) -> None:
        self._c = _native._Curve.from_json(_dumps(obj), dim)

    @staticmethod
    def _wrap(native: Any, dim: Optional[int] = None) -> "Curve":
        if dim is not None and native.dim != dim:
            native = _native._Curve.from_json(native.to_json(), dim)
        cls = _CLASSES.get(native.family, Curve)
        c = cls.__new__(cls)
        c._c = native
        return c

    @staticmethod
    def from_dict(obj: Dict[str, Any], dim: Optional[int] = None) -> "Curve":
        """A curve from a scene file's curve object (``{"type": "bezier", …}``)."""
        if not isinstance(obj, dict):
            raise TypeError(f"from_dict: obj must be a dict (a curve object), not {type(obj).__name__}")
        if dim is not None:
            dim = _int(dim, "dim", 2, 3, "from_dict")
        return Curve._wrap(_native._Curve.from_json(_dumps(obj), dim))

    def to_dict(self) -> Dict[str, Any]:
        """The curve object of the scene format."""
        return json.loads(self._c.to_json())

    def _with(self, **fields: Any) -> "Curve":
        obj = self.to_dict()
        obj.update(fields)
        return Curve.from_dict(obj, self.dim)

    # -- what it is -----------------------------------------------------------------

    @property
    def family(self) -> str:
        """The family's name in scene files."""
        return self._c.family

    @property
    def dim(self) -> int:
        """Coordinates per point in results: 2 or 3."""
        return self._c.dim

    @property
    def name(self) -> Optional[str]:
        return self._c.name

    @property
    def control_points(self) -> np.ndarray:
        """The points the user places: control points, or the interpolated points."""
        return self._c.control_points()

    def domain(self) -> Tuple[float, float]:
        """The parameter domain ``(a, b)``."""
        return self._c.domain()

    def summary(self) -> str:
        return self._c.summary()

    def __repr__(self) -> str:
        # Family, name, shape and a short view of the points, numpy-style (elided past a
        # few rows): enough to tell two curves apart at a prompt.
        name = f"{self.name!r}, " if self.name else ""
        points = _short_array(self.control_points)
        return f"{type(self).__name__}({name}{self.summary()}, dim={self.dim}, points={points})"

    def _repr_svg_(self) -> str:
        """A notebook's picture of the curve: an SVG figure of a scene of it alone,
        labelled."""
        return Scene([self]).svg(480, 300)

    # -- a value: pickling, copies, equality ---------------------------------------

    def _key(self) -> Tuple[int, str]:
        # The scene-format text writes every number in its shortest round-trip form, so
        # two curves have the same text exactly when their numbers are the same bit for
        # bit (and their family, name and style the same).
        return (self.dim, self._c.to_json())

    def __reduce__(self) -> Tuple[Any, Tuple[str, int]]:
        """Pickles (protocols 2–5) as the scene-format text and the dimension: unpickled,
        every coordinate, knot, weight and shape parameter is the same double."""
        return (_curve_from_state, (self._c.to_json(), self.dim))

    def __copy__(self) -> "Curve":
        # Curves are immutable (every edit makes a new one): a copy may share the value.
        return Curve._wrap(self._c)

    def __deepcopy__(self, memo: Dict[int, Any]) -> "Curve":
        return _curve_from_state(self._c.to_json(), self.dim)

    def __eq__(self, other: object) -> bool:
        """Equal: the same family, dimension, name, style and numbers, bit for bit."""
        if not isinstance(other, Curve):
            return NotImplemented
        return self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    # -- evaluation -----------------------------------------------------------------

    def eval(self, t: ArrayLike, out: Optional[np.ndarray] = None) -> np.ndarray:
        """``P(t)``: shape ``(dim,)`` for a number, ``(N, dim)`` for an array.

        ``out``: numpy's convention — a C-contiguous, writeable float64 array of that
        shape, written in place and returned (a loop that evaluates the same number of
        parameters each step allocates nothing); any other array is refused with a
        :class:`CurveError` naming ``out``."""
        return self._c.eval(t, out)

    __call__ = eval

    def derivative(
        self, t: ArrayLike, order: int = 1, out: Optional[np.ndarray] = None
    ) -> np.ndarray:
        """The first or second derivative with respect to ``t`` (``out`` as for
        :meth:`eval`)."""
        return self._c.derivative(t, _int(order, "order", 1, 2, "derivative"), out)

    def curvature(
        self, t: ArrayLike, out: Optional[np.ndarray] = None, signed: bool = False
    ) -> Union[float, np.ndarray]:
        """``κ = |P′ × P″| / |P′|³``; NaN where ``P′ = 0``. With ``signed=True`` (planar
        curves), negative where the curve turns right — the convention of
        :meth:`curvature_extrema`'s third column. ``out``: a float64 array of shape ``(N,)``
        (``()`` for a number), written in place and returned."""
        return self._c.curvature(t, out, _bool(signed, "signed", "curvature"))

    def sample(self, n: int) -> np.ndarray:
        """``n`` points at uniform parameters over the domain, ends included (``n`` at
        least 2 and within the sample limit, ``SPLINESCOPE_MAX_SAMPLES``)."""
        return self._c.sample(_int(n, "n", 2, 2**64 - 1, "sample"))

    def draw(self, pen: Any, tolerance: Optional[float] = None) -> None:
        """Draws the curve into a fontTools pen (any object with ``moveTo``, ``lineTo``,
        ``qCurveTo``, ``curveTo``, ``closePath``, ``endPath``): its segments as they are —
        lines, quadratics, cubics — closed with ``closePath`` for a closed path (its
        closing line implied). A rational segment or one of degree above 3 goes through
        :meth:`to_cubics` within ``tolerance`` (default: 10⁻⁶ of the curve's bounding box
        diagonal)."""
        from .pens import draw

        draw(self, pen, tolerance)

    def segments(self) -> List[Tuple[Any, ...]]:
        """The exact Bézier segments, ``(t0, t1, control points)`` each; a rational
        segment is ``(t0, t1, control points, weights)``."""
        return self._c.segments()

    def inspect(self) -> Dict[str, Any]:
        """The curve's derived data, as ``splinescope inspect`` reports it."""
        return json.loads(self._c.inspect_json())

    # -- analysis (docs/math.md §7) ------------------------------------------------

    def length(
        self, t0: Optional[float] = None, t1: Optional[float] = None, accuracy: float = 1e-12
    ) -> float:
        """The arc length from ``t0`` to ``t1`` (default: the whole domain; negative when
        ``t1 < t0``), within ``accuracy`` (absolute): adaptive Gauss–Kronrod quadrature of
        ``|C′|`` on the exact segments, its error bound kept."""
        return self._c.length(
            None if t0 is None else _float(t0, "t0", "length"),
            None if t1 is None else _float(t1, "t1", "length"),
            _float(accuracy, "accuracy", "length"),
        )

    def parameter_at_length(self, s: float, accuracy: float = 1e-12) -> float:
        """The parameter where the arc length from the domain's start is ``s``."""
        return self._c.parameter_at_length(
            _float(s, "s", "parameter_at_length"),
            _float(accuracy, "accuracy", "parameter_at_length"),
        )

    def bbox(self) -> np.ndarray:
        """The tight axis-aligned box of the curve (not of its control points):
        ``(2, dim)``, the smallest corner then the largest."""
        return self._c.bbox()

    def extrema(self, axis: Optional[int] = None) -> np.ndarray:
        """The parameters where a coordinate's derivative vanishes (every axis, or
        ``axis``: 0, 1 or 2), sorted."""
        return self._c.extrema(None if axis is None else _int(axis, "axis", 0, 2, "extrema"))

    def inflections(self) -> np.ndarray:
        """The parameters where ``C′ × C″`` changes sign (2D), cusps excluded."""
        return self._c.inflections()

    def cusps(self) -> np.ndarray:
        """The parameters where the velocity vanishes (2D)."""
        return self._c.cusps()

    def curvature_extrema(self) -> np.ndarray:
        """The local extrema of the curvature's magnitude ``|κ|`` (2D), as designers name
        them — the sharpest point of a bend is a maximum, whichever way it turns; the
        zeros of ``κ`` are :meth:`inflections`, not minima. ``(K, 4)``: the parameter,
        ``|κ|``, the signed ``κ`` (negative turning right, as ``curvature(t,
        signed=True)``), and ``+1`` for a maximum or ``−1`` for a minimum of ``|κ|``."""
        return self._c.curvature_extrema()

    def joints(self) -> np.ndarray:
        """Continuity where one lowered segment meets the next (a B-spline's knots, a
        bump's ends, an interpolation's data points), then a closed curve's seam: ``(K,
        4)`` — the parameter, the gap between the two ends, the angle between the
        tangents in radians, and the relative jump of the curvature vector
        ``|K⁻ − K⁺| / max(|K⁻|, |K⁺|)`` (``inf`` where a speed vanishes). A joint is G2
        when the gap, angle and jump are at rounding level (``1e-12`` of the size,
        ``1e-9`` rad, ``1e-8``), G1 with a jump, G0 with an angle (docs/math.md §9)."""
        return self._c.joints()

    def signed_area(self) -> float:
        """The signed area the curve encloses (2D, positive counter-clockwise); an open
        curve is closed by the chord from its end to its start."""
        return self._c.signed_area()

    def is_closed(self) -> bool:
        """Whether the curve ends where it starts."""
        return self._c.is_closed()

    def intersect(self, other: "Curve", kinds: bool = False, errors: bool = False) -> Any:
        """Where this curve meets ``other`` (2D): a ``(K, 2)`` array of parameter pairs
        ``(s, t)`` sorted by ``s`` (``s`` this curve's). With ``kinds=True``, also the list
        of ``"crossing"`` / ``"tangent"``; with ``errors=True``, also a ``(K, 2)`` array of
        bounds on each pair's errors ``(error_s, error_t)`` — for a crossing a few ε times
        its condition number, for a tangency the band where the curves stay within the
        resolution (docs/math.md §7). The extras follow the pairs in that order.
        Coincident stretches: :meth:`overlaps`."""
        if kinds is False and errors is False:  # the common call, without the checks
            return self._c.intersect(_curve(other, "other"))[0]
        want_kinds = _bool(kinds, "kinds", "intersect")
        want_errors = _bool(errors, "errors", "intersect")
        st, k, _, e = self._c.intersect(_curve(other, "other"), want_kinds, want_errors)
        return _hits(st, k, e, want_kinds, want_errors)

    def overlaps(self, other: "Curve") -> List[Tuple[Tuple[float, float], Tuple[float, float]]]:
        """The stretches where this curve and ``other`` coincide:
        ``((s0, s1), (t0, t1))`` each, ``t0`` meeting ``s0`` (so ``t0 > t1`` where the
        two run in opposite directions)."""
        return self._c.intersect(_curve(other, "other"))[2]

    def self_intersections(self, kinds: bool = False, errors: bool = False) -> Any:
        """Where the curve crosses or touches itself (2D): ``(K, 2)`` pairs ``s < t``, and
        with ``kinds`` / ``errors`` as :meth:`intersect`."""
        want_kinds = _bool(kinds, "kinds", "self_intersections")
        want_errors = _bool(errors, "errors", "self_intersections")
        st, k, _, e = self._c.self_intersections(want_kinds, want_errors)
        return _hits(st, k, e, want_kinds, want_errors)

    def nearest(self, p: ArrayLike) -> Tuple[Any, Any]:
        """The point of the curve nearest to ``p`` — the global minimum of the distance over
        the whole curve (every root of ``(C(t) − p)·C′(t)`` on every segment, and the
        ends), never a local one — as ``(t, distance)``; for ``(N, dim)`` points, ``(N,)``
        parameters and ``(N,)`` distances, computed on every core. Points equally near: the
        smaller ``t``. A 2-D curve and a 3-D point: the distance counts its ``z``.
        ``docs/math.md`` states the bound on the distance's error."""
        return self._c.nearest(p)

    def to_cubics(self, tolerance: float, with_error: bool = False) -> Any:
        """The curve as a :class:`Path` of cubic segments within ``tolerance`` of it in the
        Hausdorff sense — every point of each within ``tolerance`` of the other — shown by
        a computed bound, not by sampling (``docs/math.md`` §11); rational curves and high
        degrees included, segments already cubic (or lower, raised exactly) kept. With
        ``with_error=True``, ``(path, bound)``."""
        path, bound = self._c.to_cubics(_float(tolerance, "tolerance", "to_cubics"))
        path = Curve._wrap(path)
        return (path, bound) if with_error else path

    def to_quadratics(self, tolerance: float, with_error: bool = False) -> Any:
        """The curve as a :class:`Path` of quadratic segments within ``tolerance`` (what a
        TrueType font stores), the bound proven as for :meth:`to_cubics`."""
        path, bound = self._c.to_quadratics(_float(tolerance, "tolerance", "to_quadratics"))
        path = Curve._wrap(path)
        return (path, bound) if with_error else path

    def offset(
        self,
        d: float,
        tolerance: float,
        *,
        join: str = "round",
        miter_limit: float = 4.0,
        caps: Optional[str] = None,
        trim: bool = False,
        with_error: bool = False,
    ) -> Any:
        """The offset (parallel curve) at signed distance ``d`` — ``C(t) + d n(t)``, ``n``
        the left unit normal (``d > 0`` to the left of the direction of travel, y up) — as
        a :class:`Path` of cubic segments within ``tolerance`` of the true offset in the
        Hausdorff sense, shown by a computed bound (``docs/math.md`` §14), for every
        family (2D). Where ``|d|`` passes the radius of curvature the offset has cusps
        (kept; ``trim=True`` removes the loops they make, and the inner side of kinks,
        returning a list of the paths left). Kinks get ``join`` ("round", "miter" — past
        ``miter_limit`` times ``|d|`` a bevel — or "bevel") on their outer side.
        ``caps`` ("butt", "round", "square") gives the outline of a stroke of half width
        ``|d|`` instead: a list of one closed path (open curve) or two (closed curve).
        With ``with_error=True``, ``(result, bound)``."""
        paths, bound, _cusps = self._c.offset(
            _float(d, "d", "offset"),
            _float(tolerance, "tolerance", "offset"),
            str(join),
            _float(miter_limit, "miter_limit", "offset"),
            None if caps is None else str(caps),
            bool(trim),
        )
        wrapped = [Curve._wrap(p) for p in paths]
        result: Any = wrapped if (trim or caps is not None) else wrapped[0]
        return (result, bound) if with_error else result

    def split(self, t: float) -> Tuple["Curve", "Curve"]:
        """The curve split at ``t`` (inside the domain) into the curves before and after
        it, exactly: a Bézier or rational Bézier curve into two of its family (de
        Casteljau), a path into two paths, any other family into two :class:`Path` curves
        of its exact segments."""
        a, b = self._c.split(_float(t, "t", "split"))
        return Curve._wrap(a), Curve._wrap(b)

    def remove_knot(
        self, u: float, *, times: int = 1, tolerance: float = 0.0, with_error: bool = False
    ) -> Any:
        """The curve (:class:`BSpline`, :class:`Nurbs`, or a standard :class:`Nubmp` through
        its B-spline — refused while its shape parameters are set) with the knot ``u``
        removed ``times`` times (Tiller's algorithm) when it moves by at most ``tolerance`` — a
        proven bound: the knot inserted back, the control points compared on one basis —
        else a :class:`CurveError` naming the bound it would reach. ``tolerance=0`` removes
        only a knot whose removal does not move the curve (up to rounding). With
        ``with_error=True``, ``(curve, bound)``."""
        c, bound = self._c.remove_knot(
            _float(u, "u", "remove_knot"),
            _int(times, "times", 1, 2**31, "remove_knot"),
            _float(tolerance, "tolerance", "remove_knot"),
        )
        c = Curve._wrap(c)
        return (c, bound) if with_error else c

    def reduce_degree(self, tolerance: float, with_error: bool = False) -> Any:
        """The :class:`Bezier` curve at the lowest degree within ``tolerance`` of it
        (Hausdorff, a proven bound), its ends kept: for each lower degree in turn, the
        least-squares curve over the whole range with the same ends, until one is within
        the tolerance; else a :class:`CurveError` naming the best bound reached. With
        ``with_error=True``, ``(curve, bound)``."""
        c, bound = self._c.reduce_degree(_float(tolerance, "tolerance", "reduce_degree"))
        c = Curve._wrap(c)
        return (c, bound) if with_error else c

    def reverse(self) -> "Curve":
        """The curve traced the other way: the same points, ``reversed(a + b − t) ==
        C(t)`` for Bézier, rational Bézier, B-spline and NURBS curves (which keep their
        family, a spline's knots mirrored); others as the reversed :class:`Path` of their
        exact segments."""
        return Curve._wrap(self._c.reverse())

    def intersect_line(self, p: ArrayLike, q: ArrayLike) -> Tuple[np.ndarray, List[str]]:
        """Where the curve meets the line through ``p`` and ``q`` (2D): ``(K, 2)`` pairs
        ``(t, λ)`` (the point is ``p + λ (q − p)``) and their kinds."""
        st, k, _ = self._c.intersect_line(
            np.asarray(_point(p, "p"), dtype=np.float64),
            np.asarray(_point(q, "q"), dtype=np.float64),
        )
        return st, k

    def analyze(self, accuracy: float = 1e-12, intersections: bool = False) -> Dict[str, Any]:
        """``splinescope analyze``'s report of this curve (a dict)."""
        return json.loads(
            self._c.analyze_json(
                _float(accuracy, "accuracy", "analyze"),
                _bool(intersections, "intersections", "analyze"),
            )
        )

    # -- structure ------------------------------------------------------------------

    def insert_knot(self, t: float) -> "Curve":
        """The same curve with the knot ``t`` inserted (B-splines, standard NUBMP)."""
        return Curve._wrap(self._c.insert_knot(_number(t, "t")))

    def insert_point(self, at: ArrayLike) -> Tuple["Curve", int]:
        """A control point inserted on the control polygon's leg nearest ``at``."""
        c, i = self._c.insert_point(np.asarray(_point(at, "at"), dtype=np.float64))
        return Curve._wrap(c), i

    def move_point(self, index: int, to: ArrayLike) -> "Curve":
        """The curve with control point ``index`` moved to ``to``, every other property
        kept (a point where a path's segments meet moves in both), as the viewer's drag
        does."""
        index = _int(index, "index", 0, 2**63 - 1, "move_point")
        return Curve._wrap(self._c.move_point(index, np.asarray(_point(to, "to"), dtype=np.float64)))

    def remove_point(self, index: int) -> "Curve":
        """The curve without control point ``index``."""
        return Curve._wrap(self._c.remove_point(_int(index, "index", 0, 2**63 - 1, "remove_point")))

    def elevate(self, times: int = 1) -> "Curve":
        """The same curve with its degree raised ``times`` (Bézier, B-spline, rational
        Bézier, NURBS), refused before any work when the result would pass the degree
        or order limit."""
        return Curve._wrap(self._c.elevate(_int(times, "times", 0, 2**63 - 1, "elevate")))

    # -- least-squares shape modification (paper 000) ------------------------------

    def solve(self, method: str, **fields: Any) -> Tuple["Curve", Report]:
        """Applies one solve method (``docs/solve-format.md``) to this curve alone: the
        modified curve and the method's report. Points in ``fields`` may be numpy arrays.
        """
        request: Dict[str, Any] = {"curve": 0, "method": _str(method, "method", "solve")}
        for k, v in fields.items():
            if v is None:
                continue
            request[k] = v
        scene = _native._Scene.from_curves([self._c])
        new, reports = scene.solve(_dumps(request))
        return Curve._wrap(new.curves[0], self.dim), json.loads(reports)[0]

    def pass_through(
        self,
        target: ArrayLike,
        t: Optional[float] = None,
        first: Optional[int] = None,
        count: Optional[int] = None,
    ) -> Tuple["Curve", Report]:
        """Moves control points minimally (least squares) so that the curve passes
        through ``target`` at ``t`` (default: the parameter nearest the target), moving
        ``count`` points from ``first`` (default all): paper 000, single target.
        Bézier, rational Bézier and NURBS curves (weights held fixed)."""
        return self.solve(
            "single_target",
            target=_point(target, "target"),
            t=None if t is None else _number(t, "t"),
            first=None if first is None else _int(first, "first", 0, 2**63 - 1, "pass_through"),
            count=None if count is None else _int(count, "count", 0, 2**63 - 1, "pass_through"),
        )

    def pass_through_keeping_tangents(
        self, target: ArrayLike, t: Optional[float] = None
    ) -> Tuple["Curve", Report]:
        """As :meth:`pass_through`, keeping both end tangent directions (paper 000)."""
        return self.solve(
            "tangent_kept",
            target=_point(target, "target"),
            t=None if t is None else _number(t, "t"),
        )

    def pass_through_all(
        self, targets: ArrayLike, params: Optional[Sequence[float]] = None
    ) -> Tuple["Curve", Report]:
        """Moves control points minimally so that the curve passes through every
        target (at ``params``, default the nearest parameters): paper 000, several
        targets."""
        pts, _ = _points(targets, "targets")
        return self.solve(
            "multi_target",
            targets=pts,
            params=None if params is None else _numbers(params, "params"),
        )


class Bezier(Curve):
    """A Bézier curve of any degree ``n`` (paper 002):
    ``P(t) = Σ_{i=0}^{n} B_{i,n}(t) P_i`` on ``[0, 1]``, ``B_{i,n}(t) = C(n,i) tᶦ (1−t)ⁿ⁻ᶦ``,
    evaluated by de Casteljau in float64.

    ``points``: ``(n + 1, 2)`` or ``(n + 1, 3)``, ``n + 1 ≥ 2``.
    """

    __slots__ = ()

    def __init__(self, points: ArrayLike) -> None:
        pts, dim = _points(points, "points")
        self._set({"type": "bezier", "points": pts}, dim)

    @property
    def degree(self) -> int:
        return len(self.control_points) - 1


class ModifiedBezier(Curve):
    """The modified Bézier curve of paper 002, §4: ``R(t) = Q(t) + S(t) v`` where ``Q``
    is the Bézier curve of ``points`` and ``S`` the C¹ bump
    ``S(t) = (2 t t* − t²)/t*²`` on ``[0, t*]``, ``(2 t t* − t² − 2t* + 1)/(t* − 1)²`` on
    ``[t*, 1]`` (``S(0) = S(1) = 0``, ``S(t*) = 1``).

    ``t_star`` in the open interval (0, 1); ``v`` a vector of 2 or 3 numbers.
    """

    __slots__ = ()

    def __init__(self, points: ArrayLike, t_star: float, v: ArrayLike) -> None:
        pts, dim = _points(points, "points")
        self._set(
            {
                "type": "modified_bezier",
                "points": pts,
                "t_star": _number(t_star, "t_star"),
                "v": _point(v, "v"),
            },
            dim,
        )

    @property
    def t_star(self) -> float:
        """Where the bump peaks; setting it is checked as in a scene file."""
        return float(self.to_dict()["t_star"])

    @t_star.setter
    def t_star(self, value: float) -> None:
        self._c = self._with(t_star=_number(value, "t_star"))._c

    @property
    def v(self) -> np.ndarray:
        """The vector ``v``."""
        return np.asarray(self.to_dict()["v"], dtype=np.float64)[: self.dim]

    @v.setter
    def v(self, value: ArrayLike) -> None:
        self._c = self._with(v=_point(value, "v"))._c


class Interpolation(Curve):
    """Cubic Bézier interpolation of paper 002, §5: the curve passes through ``points``
    at ``params`` (default ``0, 1, 2, …``); piece ``i`` is the cubic from ``P_{i−1}`` to
    ``P_i`` with inner points ``P_{i−1} + (h/3) s_{i−1}`` and ``P_i − (h/3) s_i``, the
    tangents ``s_i`` those of the parabola through three neighbours.

    ``modification``: ``None`` or ``{"t_star": t, "v": [x, y], "reading": "paper" |
    "bump_added"}`` (the modified interpolation of the paper's Example 2).
    """

    __slots__ = ()

    def __init__(
        self,
        points: ArrayLike,
        params: Optional[ArrayLike] = None,
        modification: Optional[Dict[str, Any]] = None,
    ) -> None:
        pts, dim = _points(points, "points")
        obj: Dict[str, Any] = {"type": "interpolation", "points": pts}
        if params is not None:
            obj["params"] = _numbers(params, "params")
        if modification is not None:
            obj["modification"] = _modification(modification)
        self._set(obj, dim)

    @property
    def params(self) -> np.ndarray:
        """The parameters of the points."""
        d = self.to_dict()
        if "params" in d:
            return np.asarray(d["params"], dtype=np.float64)
        return np.arange(len(d["points"]), dtype=np.float64)

    @property
    def modification(self) -> Optional[Dict[str, Any]]:
        return self.to_dict().get("modification")

    @modification.setter
    def modification(self, value: Optional[Dict[str, Any]]) -> None:
        obj = self.to_dict()
        if value is None:
            obj.pop("modification", None)
        else:
            obj["modification"] = _modification(value)
        self._c = Curve.from_dict(obj, self.dim)._c


def _modification(m: Dict[str, Any]) -> Dict[str, Any]:
    if not isinstance(m, dict):
        raise TypeError(
            f"modification must be a dict ({{'t_star': …, 'v': …}}) or None, not {type(m).__name__}"
        )
    out = dict(m)
    if "v" in out:
        out["v"] = _point(out["v"], "modification.v")
    return out


class BSpline(Curve):
    """A non-uniform B-spline of order ``k`` (degree ``k − 1``), paper 001, §2:
    ``P(t) = Σ_i N_{i,k}(t) P_i`` on ``[t_{k−1}, t_n]`` (Cox–de Boor basis).

    ``knots``: ``n + k`` non-decreasing numbers, or ``"clamped_uniform"``; ``points``:
    ``(n, 2)`` or ``(n, 3)``; ``order`` = ``k ≥ 2``. The argument order follows
    ``scipy.interpolate.BSpline(t, c, k)`` (but with the order, not the degree).
    """

    __slots__ = ()

    def __init__(self, knots: Union[ArrayLike, str], points: ArrayLike, order: int) -> None:
        pts, dim = _points(points, "points")
        self._set(
            {
                "type": "bspline",
                "points": pts,
                "knots": knots if isinstance(knots, str) else _numbers(knots, "knots"),
                "order": order,
            },
            dim,
        )

    @property
    def knots(self) -> np.ndarray:
        return np.asarray(self.inspect()["knots"], dtype=np.float64)

    @property
    def order(self) -> int:
        return int(self.to_dict()["order"])

    @classmethod
    def from_scipy(cls, spl: Any) -> "BSpline":
        """From ``scipy.interpolate.BSpline`` (coefficients ``(n, 2)`` or ``(n, 3)``)."""
        t = np.asarray(spl.t, dtype=np.float64)
        k = int(spl.k)
        n = len(t) - k - 1
        c = np.asarray(spl.c, dtype=np.float64)
        if c.ndim != 2:
            raise _error(
                SceneError,
                f"the spline's coefficients must have shape (n, 2) or (n, 3); got {c.shape}",
                "c",
            )
        return cls(t, c[:n], k + 1)

    def to_scipy(self) -> Any:
        """As ``scipy.interpolate.BSpline`` (same knots, coefficients and degree)."""
        from scipy.interpolate import BSpline as ScipyBSpline

        return ScipyBSpline(self.knots, self.control_points, self.order - 1)


class Nubmp(Curve):
    """A B-spline with multiple shape parameters (NUBMP), paper 001, §3–5:
    ``P(t) = Σ_i Ñ_{i,k}(t) P_i`` with ``Ñ_{i,k} = Σ_j a^i_j N*_{j,k+1}`` over the refined
    knots ``T*`` (each distinct knot once more). With every ``a^i_j`` at its standard
    value ``c^i_j`` it is the ordinary B-spline.

    ``shape``: the scene format's settings, applied in order —
    ``{"group": j, "values": [...]}`` or
    ``{"group": j, "member": i, "value": x, "absorber": l}``.
    """

    __slots__ = ()

    def __init__(
        self,
        points: ArrayLike,
        knots: Union[ArrayLike, str],
        order: int,
        shape: Optional[List[Dict[str, Any]]] = None,
    ) -> None:
        pts, dim = _points(points, "points")
        obj: Dict[str, Any] = {
            "type": "nubmp",
            "points": pts,
            "knots": knots if isinstance(knots, str) else _numbers(knots, "knots"),
            "order": order,
        }
        if shape is not None:
            obj["shape"] = shape
        self._set(obj, dim)

    @property
    def shape(self) -> List[Dict[str, Any]]:
        """Every group's parameters, as ``{"group": j, "values": [...]}`` settings."""
        return self.to_dict().get("shape", [])

    @shape.setter
    def shape(self, settings: List[Dict[str, Any]]) -> None:
        self._c = self._with(shape=settings)._c

    def set_group(self, group: int, values: ArrayLike) -> None:
        """Sets every parameter of group ``group`` (≥ 0, summing to 1)."""
        group = _int(group, "group", 0, 2**63 - 1, "set_group")
        self.shape = self.shape + [{"group": group, "values": _numbers(values, "values")}]

    def constrained(
        self, target: ArrayLike, tau: float, group: int, respect_vd: bool = False
    ) -> Tuple["Curve", Report]:
        """Paper 001's constrained modification: changes group ``group``'s shape
        parameters so that ``P(tau)`` moves to ``target`` (within the
        variation-diminishing ranges when ``respect_vd``)."""
        return self.solve(
            "nubmp_constrained",
            target=_point(target, "target"),
            tau=_number(tau, "tau"),
            group=_int(group, "group", 0, 2**63 - 1, "constrained"),
            respect_vd=_bool(respect_vd, "respect_vd", "constrained"),
        )


class _Weighted(Curve):
    """The weights of a rational curve, read and set as in a scene file."""

    __slots__ = ()

    @property
    def weights(self) -> np.ndarray:
        """The weights ``w_i > 0``, one per control point; setting them is checked (a
        weight ≤ 0 is refused naming ``weights[i]``)."""
        return np.asarray(self.to_dict()["weights"], dtype=np.float64)

    @weights.setter
    def weights(self, value: ArrayLike) -> None:
        self._c = self._with(weights=_numbers(value, "weights"))._c


class RationalBezier(_Weighted):
    """A rational Bézier curve of degree ``n``:
    ``C(t) = Σ w_i P_i B_{i,n}(t) / Σ w_i B_{i,n}(t)`` on ``[0, 1]``, evaluated in
    homogeneous coordinates (de Casteljau on ``(w_i P_i, w_i)``, then divided); with every
    weight 1 it is the :class:`Bezier` curve. Conics are exact: the quarter circle is
    ``(1, 0), (1, 1), (0, 1)`` with weights ``1, √2/2, 1``. The least-squares
    modification of paper 000 applies with the weights held fixed.

    ``points``: ``(n + 1, 2)`` or ``(n + 1, 3)``; ``weights``: ``n + 1`` numbers > 0.
    """

    __slots__ = ()

    def __init__(self, points: ArrayLike, weights: ArrayLike) -> None:
        pts, dim = _points(points, "points")
        self._set(
            {"type": "rational_bezier", "points": pts, "weights": _numbers(weights, "weights")},
            dim,
        )

    @property
    def degree(self) -> int:
        return len(self.control_points) - 1


class Nurbs(_Weighted):
    """A NURBS curve of order ``k``:
    ``C(t) = Σ w_i P_i N_{i,k}(t) / Σ w_i N_{i,k}(t)`` on ``[t_{k−1}, t_n]``; with every
    weight 1 it is the :class:`BSpline`. Knot insertion, degree elevation and Bézier
    extraction work in homogeneous coordinates (the curve does not move).

    Arguments in :class:`BSpline`'s order, then the weights: ``knots`` (``n + k``
    numbers or ``"clamped_uniform"``), ``points`` ``(n, 2)`` or ``(n, 3)``, ``order``,
    ``weights`` (``n`` numbers > 0).
    """

    __slots__ = ()

    def __init__(
        self,
        knots: Union[ArrayLike, str],
        points: ArrayLike,
        order: int,
        weights: ArrayLike,
    ) -> None:
        pts, dim = _points(points, "points")
        self._set(
            {
                "type": "nurbs",
                "points": pts,
                "weights": _numbers(weights, "weights"),
                "knots": knots if isinstance(knots, str) else _numbers(knots, "knots"),
                "order": order,
            },
            dim,
        )

    @classmethod
    def circle(cls, center: ArrayLike = (0.0, 0.0), radius: float = 1.0) -> "Nurbs":
        """The exact circle: the nine-point quadratic NURBS curve on the knots
        ``0,0,0,¼,¼,½,½,¾,¾,1,1,1``, corner weights ``√2/2`` (2-D when ``center`` has two
        coordinates)."""
        c = np.asarray(_point(center, "center"), dtype=np.float64)
        r = _number(radius, "radius")
        corners = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (1, 0)]
        pts = np.array([[c[0] + x * r, c[1] + y * r] + list(c[2:]) for x, y in corners])
        h = float(np.sqrt(0.5))
        weights = [1.0, h, 1.0, h, 1.0, h, 1.0, h, 1.0]
        knots = [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1]
        return cls(knots, pts, 3, weights)

    @property
    def knots(self) -> np.ndarray:
        return np.asarray(self.inspect()["knots"], dtype=np.float64)

    @property
    def order(self) -> int:
        return int(self.to_dict()["order"])


class Path(Curve):
    """Bézier segments of any degree, each polynomial or rational, joined end to end:
    segment ``k`` covers ``t ∈ [k, k + 1]``,
    ``C(t) = S_k(t − k)``, ``S_k(u) = Σ w_i P_i B_{i,n}(u) / Σ w_i B_{i,n}(u)`` (``w_i = 1``
    for a polynomial segment) — what an SVG subpath, a glyph contour, a DXF polyline and a
    STEP composite curve are. Consecutive segments must share their end point (a gap
    beyond rounding is refused naming the joint); ``closed``: the last ends where the
    first starts. :meth:`Curve.segments` returns them exactly as given.

    ``segments``: a sequence whose items are each an ``(n + 1, dim)`` array of control
    points or a ``(points, weights)`` pair for a rational segment; every segment in the
    same dimension (2 or 3).
    """

    __slots__ = ()

    def __init__(self, segments: Sequence[Any], closed: bool = False) -> None:
        try:
            items = list(segments)
        except TypeError:
            raise TypeError(
                f"Path: segments must be a sequence of arrays or (points, weights) pairs, "
                f"not {type(segments).__name__}"
            ) from None
        docs: List[Dict[str, Any]] = []
        dim = None
        for k, item in enumerate(items):
            what = f"segments[{k}]"
            if isinstance(item, tuple) and len(item) == 2:
                pts, d = _points(item[0], f"{what}.points")
                doc: Dict[str, Any] = {"points": pts, "weights": _numbers(item[1], f"{what}.weights")}
            else:
                pts, d = _points(item, f"{what}.points")
                doc = {"points": pts}
            if dim is None:
                dim = d
            elif d != dim:
                raise _error(
                    SceneError,
                    f"{what}: points of dimension {d} after segments of dimension {dim}: "
                    "every segment has the same dimension",
                    f"{what}.points",
                )
            docs.append(doc)
        self._set(
            {"type": "path", "segments": docs, "closed": _bool(closed, "closed", "Path")},
            dim or 2,
        )

    @property
    def closed(self) -> bool:
        """Whether the last segment ends where the first starts."""
        return bool(self.to_dict().get("closed", False))


_CLASSES = {
    "bezier": Bezier,
    "modified_bezier": ModifiedBezier,
    "interpolation": Interpolation,
    "bspline": BSpline,
    "nubmp": Nubmp,
    "rational_bezier": RationalBezier,
    "nurbs": Nurbs,
    "path": Path,
}


def _scene_from_state(text: str) -> "Scene":
    """A pickled scene back from its JSON text."""
    return Scene._wrap(_native._Scene.from_json(text))


class Scene:
    """A scene: curves, view, annotations (``docs/scene-format.md``)."""

    __slots__ = ("_s",)

    def __init__(self, curves: Sequence[Curve] = (), name: Optional[str] = None) -> None:
        if name is not None:
            name = _str(name, "name", "Scene")
        try:
            items = list(curves)
        except TypeError:
            raise TypeError(
                f"Scene: curves must be a sequence of Curve, not {type(curves).__name__}"
            ) from None
        self._s = _native._Scene.from_curves(
            [_curve(c, f"curves[{i}]") for i, c in enumerate(items)], name
        )

    @staticmethod
    def _wrap(native: Any) -> "Scene":
        s = Scene.__new__(Scene)
        s._s = native
        return s

    @staticmethod
    def from_json(text: str) -> "Scene":
        """Reads and checks a scene from JSON text (:class:`SceneError` naming the path)."""
        return Scene._wrap(_native._Scene.from_json(text))

    @staticmethod
    def load(path: Any) -> "Scene":
        """Reads and checks a scene file."""
        return Scene._wrap(_native._Scene.load(str(path)))

    @property
    def name(self) -> Optional[str]:
        return self._s.name

    @property
    def unit(self) -> Optional[str]:
        """The unit of length of the coordinates when the file named one (a STEP file's
        ``"millimetre"`` or ``"inch"``); ``None``: unitless."""
        return self._s.unit

    @property
    def curves(self) -> List[Curve]:
        """The curves, in order (2-D results for a planar scene, 3-D otherwise)."""
        return [Curve._wrap(c) for c in self._s.curves]

    def to_json(self) -> str:
        """The scene as JSON text, in the form it was read in."""
        return self._s.to_json()

    # -- a value: pickling, copies, equality ---------------------------------------

    def __reduce__(self) -> Tuple[Any, Tuple[str]]:
        """Pickles (protocols 2–5) as its JSON text in the form it was read in: unpickled,
        every number is the same double and a save writes the same bytes."""
        return (_scene_from_state, (self._s.to_json(),))

    def __copy__(self) -> "Scene":
        # Scenes are immutable (a solve returns a new one): a copy may share the value.
        return Scene._wrap(self._s)

    def __deepcopy__(self, memo: Dict[int, Any]) -> "Scene":
        return _scene_from_state(self._s.to_json())

    def __eq__(self, other: object) -> bool:
        """Equal: the same curves (as :class:`Curve` compares them), view, annotations,
        name and background — whatever form their files were written in."""
        if not isinstance(other, Scene):
            return NotImplemented
        return self._s.canonical_json() == other._s.canonical_json()

    def __hash__(self) -> int:
        return hash(self._s.canonical_json())

    def save(self, path: Any) -> None:
        """Writes the scene atomically: a ``.dxf`` path as binary DXF (every curve an
        exact ``SPLINE``, ``docs/formats.md``), any other as the scene's JSON (an unedited
        scene keeps the file's bytes)."""
        self._s.save(str(path))

    def solve(self, request: Union[Dict[str, Any], List[Dict[str, Any]], str]) -> Tuple["Scene", Any]:
        """As :func:`solve`."""
        return solve(self, request)

    def render(
        self,
        width: int = 800,
        height: int = 500,
        tolerance_px: float = 0.25,
        backend: str = "auto",
        comb: Union[None, bool, str, float] = None,
        comb_cap: Optional[float] = 0.05,
        inflections: bool = False,
        curvature_extrema: bool = False,
        intersections: bool = False,
        joints: bool = False,
    ) -> np.ndarray:
        """The scene drawn on the GPU (a software adapter works), as an
        ``(height, width, 4)`` uint8 RGBA array: the image ``splinescope render``
        makes. ``backend``: ``auto``, ``vulkan``, ``gl``, ``metal`` or ``dx12``.

        ``comb``: each curve's curvature comb — ``True`` or ``"auto"`` for a scale chosen
        for the view, a number for the world length of a hair per unit of curvature;
        ``comb_cap``: the longest hair, a fraction of the view's height (``None``: no cap)
        — a longer one is cut to it, drawn in the envelope's stroke, the envelope broken
        there;
        ``inflections``, ``curvature_extrema``, ``intersections``, ``joints`` (kinks and
        curvature jumps where segments meet): the markers
        (``render --comb --inflections …``)."""
        w, h = _size(width, height, "render")
        shape = _shape(comb, comb_cap, inflections, curvature_extrema, intersections, joints, "render")
        return self._s.render(
            w, h, _number(tolerance_px, "tolerance_px"), _str(backend, "backend", "render"), shape
        )

    def png(
        self,
        width: int = 800,
        height: int = 500,
        backend: str = "auto",
        comb: Union[None, bool, str, float] = None,
        comb_cap: Optional[float] = 0.05,
        inflections: bool = False,
        curvature_extrema: bool = False,
        intersections: bool = False,
        joints: bool = False,
    ) -> bytes:
        """The rendered scene as PNG file bytes (the shape overlays as for ``render``)."""
        w, h = _size(width, height, "png")
        shape = _shape(comb, comb_cap, inflections, curvature_extrema, intersections, joints, "png")
        return bytes(self._s.png(w, h, 0.25, _str(backend, "backend", "png"), shape))

    def export(
        self,
        path: Any,
        width: int = 800,
        height: int = 500,
        tolerance: float = 0.01,
        labels: bool = False,
        legend: bool = False,
        axes: bool = False,
        grid: bool = False,
        backend: str = "auto",
        comb: Union[None, bool, str, float] = None,
        comb_cap: Optional[float] = 0.05,
        inflections: bool = False,
        curvature_extrema: bool = False,
        intersections: bool = False,
        joints: bool = False,
    ) -> None:
        """Writes the scene as a figure, by the extension: ``.svg`` or ``.pdf`` (curves
        of degree ≤ 3 in a 2D view exact, other pieces within ``tolerance`` points) or
        ``.png`` (the GPU picture), with labels, legend, axes and grid as asked
        (``splinescope export``'s options), and the curvature comb and markers as for
        ``render`` (in SVG and PDF the comb's hairs are exact line segments and the
        markers circles at exact positions); atomically."""
        w, h = _size(width, height, "export")
        shape = _shape(comb, comb_cap, inflections, curvature_extrema, intersections, joints, "export")
        self._s.export(
            str(path),
            w,
            h,
            _number(tolerance, "tolerance"),
            _bool(labels, "labels", "export"),
            _bool(legend, "legend", "export"),
            _bool(axes, "axes", "export"),
            _bool(grid, "grid", "export"),
            _str(backend, "backend", "export"),
            shape,
        )

    def svg(self, width: int = 640, height: int = 400, labels: bool = True) -> str:
        """The scene as an SVG figure (``splinescope export``'s: exact curves in the
        scene's view), its curves labelled unless ``labels=False``."""
        w, h = _size(width, height, "svg")
        return self._s.svg(w, h, _bool(labels, "labels", "svg"))

    def _repr_png_(self) -> bytes:
        return self.png()

    def _repr_svg_(self) -> str:
        # A notebook's vector picture of the scene, labelled; no GPU needed.
        return self.svg()

    def __repr__(self) -> str:
        curves = self.curves
        families: Dict[str, int] = {}
        for c in curves:
            families[c.family] = families.get(c.family, 0) + 1
        kinds = ", ".join(
            f"{f} ×{n}" if n > 1 else f for f, n in list(families.items())[:6]
        ) + (", …" if len(families) > 6 else "")
        name = f"{self.name!r}, " if self.name else ""
        count = f"{len(curves)} curve" + ("" if len(curves) == 1 else "s")
        return f"Scene({name}{count}" + (f": {kinds})" if curves else ")")

    # -- a sequence of curves ---------------------------------------------------------

    def __len__(self) -> int:
        return len(self._s)

    def __getitem__(self, index: Any) -> Any:
        """``scene[i]`` the ``i``-th curve (negative from the end), ``scene[a:b]`` a list of
        curves; an index out of range is an :class:`IndexError` naming it."""
        if isinstance(index, slice):
            return [Curve._wrap(c) for c in self._s.curves[index]]
        if isinstance(index, (bool, np.bool_)) or not isinstance(index, (int, np.integer)):
            raise TypeError(
                f"scene indices must be integers or slices, not {type(index).__name__} {index!r}"
            )
        n = len(self._s)
        if not -n <= int(index) < n:
            raise IndexError(
                f"curve index {int(index)} is out of range: the scene has {n} curve"
                + ("" if n == 1 else "s")
            )
        return Curve._wrap(self._s.curve_at(int(index) % n))

    def __iter__(self) -> Iterator[Curve]:
        return iter(self.curves)

    def __contains__(self, curve: object) -> bool:
        """Whether a curve equal to ``curve`` (as :class:`Curve` compares them) is in
        the scene."""
        return isinstance(curve, Curve) and any(c == curve for c in self.curves)


def stress_scene(curves: int, family: str = "bezier", degree: int = 3, seed: int = 1) -> Scene:
    """The stress generator's scene (``view --stress``, ``bench --families``): ``curves``
    random curves of ``family`` (a name of :data:`FAMILY_NAMES`) and ``degree`` (1–31),
    each in a unit cell of a square grid, the same for the same ``seed``."""
    return Scene._wrap(
        _native.stress_scene(
            _int(curves, "curves", 0, 2**63 - 1, "stress_scene"),
            _str(family, "family", "stress_scene"),
            _int(degree, "degree", 1, 31, "stress_scene"),
            _int(seed, "seed", 0, 2**64 - 1, "stress_scene"),
        )
    )


_IMPORTED = (".svg", ".dxf", ".step", ".stp", ".ttf", ".otf", ".ttc", ".otc")


def load(
    path: Any,
    glyphs: Optional[Sequence[Union[str, int]]] = None,
    text: Optional[str] = None,
    variations: Optional[Dict[str, float]] = None,
    index: int = 0,
) -> Scene:
    """Reads a scene file (``.json``, checked: :class:`SceneError` naming the offending
    value), or a file of another format as a scene of :class:`Path` curves (what is
    left out is said with ``warnings.warn``; a bad file is a :class:`SceneError` naming
    the file and the place):

    * SVG (``.svg``): every subpath one path, arcs exact (``docs/formats.md``);
    * DXF (``.dxf``, ASCII or binary): splines as B-spline or NURBS curves with their
      own knots and weights, lines, arcs, circles, ellipses and polylines as paths
      (arcs exact), blocks inserted;
    * STEP (``.step``, ``.stp``): B-spline, Bézier, line, circle, ellipse, trimmed and
      composite curves and B-rep edges as 3D curves in the file's length unit;
    * fonts (``.ttf``, ``.otf``, ``.ttc``/``.otc`` with ``index``): every contour one
      closed path in font units, TrueType quadratics and CFF cubics as they are; every
      glyph on a grid, or ``glyphs`` (names or ids; one glyph at its own origin), or
      ``text`` laid out by the advances (no shaping or kerning), at the ``variations``
      location of a variable font (``{"wght": 700}``).
    """
    p = str(path)
    if not p.lower().endswith(_IMPORTED):
        return Scene.load(path)
    native, left_out = _native._Scene.import_file(
        p,
        glyphs=None if glyphs is None else [str(g) for g in glyphs],
        text=text,
        variations=None if variations is None else [(str(k), float(v)) for k, v in variations.items()],
        index=_int(index, "index", 0, 2**32 - 1, "load"),
    )
    for w in left_out:
        warnings.warn(w, stacklevel=2)
    return Scene._wrap(native)


def solve(
    scene: Scene, request: Union[Dict[str, Any], List[Dict[str, Any]], str]
) -> Tuple[Scene, Any]:
    """Applies a solve request (a dict, a list of them, or JSON text) as ``splinescope
    solve`` does: the new scene and the report (a list of reports for a list).
    Nothing changes unless every request succeeds (:class:`SolveError` naming the
    offending value)."""
    if not isinstance(scene, Scene):
        raise TypeError(f"solve: scene must be a Scene, not {type(scene).__name__}")
    text = request if isinstance(request, str) else _dumps(request)
    new, reports = scene._s.solve(text)
    parsed = json.loads(reports)
    single = not isinstance(request, list) and not (
        isinstance(request, str) and request.lstrip().startswith("[")
    )
    return Scene._wrap(new), parsed[0] if single else parsed


def _shape(
    comb: Any,
    comb_cap: Any,
    inflections: Any,
    curvature_extrema: Any,
    intersections: Any,
    joints: Any,
    method: str,
) -> Tuple[bool, Optional[float], Optional[float], bool, bool, bool, bool]:
    """The shape overlays' arguments: ``comb`` ``None``/``False`` (off), ``True`` or
    ``"auto"`` (a scale chosen for the view), or a number (the scale: finite, above 0 —
    else a :class:`SceneError` naming ``comb``); ``comb_cap`` ``None`` (no cap) or a
    fraction of the view's height (finite, above 0 — else a :class:`SceneError` naming
    ``comb_cap``)."""
    cap = None
    if comb_cap is not None:
        cap = _float(comb_cap, "comb_cap", method)
        if not (np.isfinite(cap) and cap > 0):
            raise _error(
                SceneError,
                f"{method}: comb cap {cap}: must be a finite number above 0 (a fraction of the view's height), or None",
                "comb_cap",
            )
    flags = (
        _bool(inflections, "inflections", method),
        _bool(curvature_extrema, "curvature_extrema", method),
        _bool(intersections, "intersections", method),
        _bool(joints, "joints", method),
    )
    if comb is None or comb is False:
        return (False, None, cap) + flags
    if comb is True or (isinstance(comb, str) and comb == "auto"):
        return (True, None, cap) + flags
    scale = _float(comb, "comb", method)
    if not (np.isfinite(scale) and scale > 0):
        raise _error(SceneError, f"{method}: comb scale {scale}: must be a finite number above 0", "comb")
    return (True, scale, cap) + flags


def _size(width: Any, height: Any, method: str) -> Tuple[int, int]:
    """A picture's size: whole numbers from 1 to 16384, as the command line takes."""
    return (
        _int(width, "width", 1, 16384, method),
        _int(height, "height", 1, 16384, method),
    )


def eval_many(curves: Sequence[Curve], n: int) -> np.ndarray:
    """``n`` uniform samples of every curve over its domain, ``(C, n, dim)``, on every
    core (all curves of one dimension; ``n`` at least 2, ``len(curves) × n`` within the
    sample limit)."""
    natives = [_curve(c, f"curves[{i}]") for i, c in enumerate(curves)]
    return _native.eval_many(natives, _int(n, "n", 2, 2**64 - 1, "eval_many"))


def join(curves: Sequence[Curve], closed: bool = False) -> Curve:
    """``curves`` joined end to end into one :class:`Path` of their exact segments, in
    order; each must start where the one before ends (else a :class:`CurveError` naming
    the joint); ``closed=True`` for a closed path (the last must end where the first
    starts)."""
    natives = [_curve(c, f"curves[{i}]") for i, c in enumerate(curves)]
    return Curve._wrap(_native.join(natives, _bool(closed, "closed", "join")))


def _params_arg(params: Any) -> Any:
    if isinstance(params, str):
        return params
    return np.asarray(_numbers(params, "params"), dtype=np.float64)


def fit_bezier(
    points: ArrayLike, degree: int, params: Any = "chord", weights: Optional[ArrayLike] = None
) -> Tuple[Curve, np.ndarray]:
    """The :class:`Bezier` curve of ``degree`` nearest to ``points`` (``(N, dim)``) in the
    weighted least-squares sense, ``min Σ w_i² |C(t_i) − p_i|²``, at parameters
    ``"chord"`` (by the distances between points), ``"centripetal"`` (by their square
    roots) or given (one per point, non-decreasing) — the machinery of paper 000's
    solver, its normal equations solved exactly; and the residuals ``|C(t_i) − p_i|``."""
    c, r = _native.fit_bezier(
        np.asarray(points, dtype=np.float64),
        _int(degree, "degree", 1, 64, "fit_bezier"),
        _params_arg(params),
        None if weights is None else _numbers(weights, "weights"),
    )
    return Curve._wrap(c), r


def fit_bspline(
    points: ArrayLike,
    degree: int = 3,
    smoothing: Optional[float] = None,
    knots: Optional[ArrayLike] = None,
    params: Any = "chord",
    weights: Optional[ArrayLike] = None,
) -> Tuple[Curve, np.ndarray]:
    """A clamped :class:`BSpline` of ``degree`` fitted to ``points`` (``(N, dim)``,
    parametric, any dimension), and the residuals ``|C(t_i) − p_i|``: with ``knots``
    (interior, in ``(0, 1)`` of the normalised parameters) the weighted least-squares
    spline on them; with ``smoothing=s`` one whose weighted sum of squared residuals
    ``Σ (w_i r_i)²`` is at most ``s`` (scipy's ``make_splprep``/``splprep`` meaning),
    knots added where the residuals are largest until it is (``s = 0``: through every
    point). Exactly one of ``knots`` and ``smoothing``; with neither, ``smoothing=0``."""
    if knots is None and smoothing is None:
        smoothing = 0.0
    c, r = _native.fit_bspline(
        np.asarray(points, dtype=np.float64),
        _int(degree, "degree", 1, 64, "fit_bspline"),
        None if knots is None else _numbers(knots, "knots"),
        None if smoothing is None else _float(smoothing, "smoothing", "fit_bspline"),
        _params_arg(params),
        None if weights is None else _numbers(weights, "weights"),
    )
    return Curve._wrap(c), r


def fit_path(
    points: ArrayLike, tolerance: float, corner_angle: float = 30.0
) -> Tuple[Curve, np.ndarray]:
    """A :class:`Path` of cubic segments through ``points`` (a noise-free polyline from a
    pen or a scan, ``(N, dim)``) with every point within ``tolerance`` of it, corners —
    turns sharper than ``corner_angle`` degrees — kept as corners and the rest smooth
    (Schneider's algorithm: end tangents fixed, tangent lengths by least squares,
    parameters refined by Newton, cut at the worst point); a polyline that ends where it
    starts gives a closed path. With the residuals (each point's distance to its point on
    the path)."""
    c, r = _native.fit_path(
        np.asarray(points, dtype=np.float64),
        _float(tolerance, "tolerance", "fit_path"),
        _float(corner_angle, "corner_angle", "fit_path"),
    )
    return Curve._wrap(c), r


def intersections(curves: Sequence[Curve], errors: bool = False) -> List[Dict[str, Any]]:
    """Every intersecting pair among ``curves`` (2D), on every core: a list of dicts
    ``{"i", "j", "params": (K, 2) array of (s, t), "kinds", "overlaps"}`` with ``i < j``
    (a grid over the segments' boxes finds the candidate pairs; with ``errors=True`` each
    dict also has ``"errors"``, the ``(K, 2)`` bounds on the parameters' errors), then,
    for each group of curves that coincide entirely (copies: the same segments over the
    same domain), one dict ``{"copies": [indices], "interval": (t0, t1)}`` in place of
    their pairs."""
    want_errors = _bool(errors, "errors", "intersections")
    natives = [_curve(c, f"curves[{i}]") for i, c in enumerate(curves)]
    return _native.intersections(natives, want_errors)


def compare_images(
    actual: np.ndarray, reference: np.ndarray, tolerance: str = "channel=24,pixels=0.1%"
) -> Dict[str, Any]:
    """Compares two ``(H, W, 4)`` or ``(H, W, 3)`` uint8 images as ``splinescope diff``
    does: ``matches``, ``max_channel_diff``, ``differing_pixels``,
    ``differing_fraction``, ``flip_mean``, ``flip_max``, ``width``, ``height``."""
    tolerance = _str(tolerance, "tolerance", "compare_images")
    return json.loads(_native.compare_images(actual, reference, tolerance))


def __getattr__(name: str) -> Any:
    # The notebook widget loads (and needs jupyter_rfb, the `notebook` extra) only when
    # asked for: `import splinescope` stays free of Jupyter.
    if name == "Widget":
        from .widget import Widget

        return Widget
    raise AttributeError(f"module 'splinescope' has no attribute {name!r}")

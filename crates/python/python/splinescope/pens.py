"""The fontTools pen protocol, both ways: :meth:`splinescope.Curve.draw` draws a curve into
any pen (``moveTo``, ``lineTo``, ``qCurveTo``, ``curveTo``, ``closePath``/``endPath``), and
:class:`ScenePen` is a pen whose contours become :class:`splinescope.Path` curves — what
a fontTools or ufoLib2 glyph draws into it (``glyph.draw(pen)``), TrueType quadratic
splines with their implied on-curve points as exact midpoints.

No fontTools import is needed: a pen is any object with those methods."""

from typing import Any, List, Optional, Sequence, Tuple

import numpy as np

Point = Tuple[float, float]


class PenError(ValueError):
    """A pen call out of order (a segment before ``moveTo``), or a segment the protocol
    cannot say (a curve of degree above 3 or a rational one, for :meth:`Curve.draw`)."""


class ScenePen:
    """A pen that collects what is drawn into it as path curves, one per contour.

    ``glyph_set``: where ``addComponent`` finds a component (a mapping of glyph names to
    objects with ``draw(pen)``, as a fontTools glyph set); without one a component is an
    error naming it. ``name``: the curves' name prefix (``"<name> contour <k>"``).
    """

    def __init__(self, glyph_set: Optional[Any] = None, name: str = "glyph") -> None:
        self.glyph_set = glyph_set
        self.name = name
        self.curves: List[Any] = []
        self._segments: List[Any] = []
        self._start: Optional[Point] = None
        self._at: Optional[Point] = None
        self._transform = (1.0, 0.0, 0.0, 1.0, 0.0, 0.0)
        self._depth = 0

    # -- the protocol ------------------------------------------------------------------

    def _p(self, pt: Sequence[float]) -> Point:
        a, b, c, d, e, f = self._transform
        x, y = float(pt[0]), float(pt[1])
        return (a * x + c * y + e, b * x + d * y + f)

    def _need(self, what: str) -> Point:
        if self._at is None:
            raise PenError(f"ScenePen.{what}: no current point (moveTo first)")
        return self._at

    def moveTo(self, pt: Sequence[float]) -> None:  # noqa: N802 - fontTools' names
        if self._segments:
            self._finish(False)
        self._start = self._at = self._p(pt)

    def lineTo(self, pt: Sequence[float]) -> None:  # noqa: N802
        a = self._need("lineTo")
        p = self._p(pt)
        self._segments.append([a, p])
        self._at = p

    def curveTo(self, *points: Sequence[float]) -> None:  # noqa: N802
        a = self._need("curveTo")
        pts = [self._p(p) for p in points]
        if len(pts) == 1:
            self.lineTo(points[0])
        elif len(pts) == 2:
            self._segments.append([a, pts[0], pts[1]])
            self._at = pts[1]
        elif len(pts) == 3:
            self._segments.append([a, *pts])
            self._at = pts[2]
        else:
            raise PenError(
                f"ScenePen.curveTo: {len(pts) - 1} off-curve points (a super-Bézier); "
                "decompose it first (fontTools' decomposeSuperBezierSegment)"
            )

    def qCurveTo(self, *points: Optional[Sequence[float]]) -> None:  # noqa: N802
        """A TrueType quadratic spline: off-curve points with implied on-curve points
        between them (exact midpoints); a last point of ``None`` closes a contour of
        off-curve points only (it then starts at the midpoint of the last and first)."""
        pts = list(points)
        if pts and pts[-1] is None:
            off = [self._p(p) for p in pts[:-1] if p is not None]
            if not off:
                raise PenError("ScenePen.qCurveTo: no points")
            first = ((off[-1][0] + off[0][0]) / 2, (off[-1][1] + off[0][1]) / 2)
            if self._segments:
                self._finish(False)
            self._start = self._at = first
            on = off + [first]
        else:
            self._need("qCurveTo")
            on = [self._p(p) for p in pts]
        if len(on) < 1:
            raise PenError("ScenePen.qCurveTo: no points")
        if len(on) == 1:
            a = self._at
            self._segments.append([a, on[0]])
            self._at = on[0]
            return
        off, end = on[:-1], on[-1]
        for k, c in enumerate(off):
            a = self._at
            if k + 1 < len(off):
                n = off[k + 1]
                p = ((c[0] + n[0]) / 2, (c[1] + n[1]) / 2)
            else:
                p = end
            self._segments.append([a, c, p])
            self._at = p

    def closePath(self) -> None:  # noqa: N802
        self._finish(True)

    def endPath(self) -> None:  # noqa: N802
        self._finish(False)

    def addComponent(self, glyph_name: str, transformation: Sequence[float]) -> None:  # noqa: N802
        if self.glyph_set is None or glyph_name not in self.glyph_set:
            raise PenError(
                f"ScenePen.addComponent: no glyph set holds the component {glyph_name!r} "
                "(give ScenePen(glyph_set=...))"
            )
        if self._depth > 64:
            raise PenError(f"ScenePen.addComponent: components nested deeper than 64 at {glyph_name!r}")
        a, b, c, d, e, f = (float(v) for v in transformation)
        outer = self._transform
        A, B, C, D, E, F = outer
        # outer ∘ component
        self._transform = (
            A * a + C * b, B * a + D * b,
            A * c + C * d, B * c + D * d,
            A * e + C * f + E, B * e + D * f + F,
        )
        self._depth += 1
        try:
            self.glyph_set[glyph_name].draw(self)
        finally:
            self._depth -= 1
            self._transform = outer

    # -- the result --------------------------------------------------------------------

    def _finish(self, closed: bool) -> None:
        from . import Path

        segs = self._segments
        self._segments = []
        if not segs:
            self._at = None
            return
        if closed and self._at != self._start:
            segs.append([self._at, self._start])
        k = len(self.curves)
        curve = Path([np.asarray(s, dtype=np.float64) for s in segs], closed=closed)
        self.curves.append(curve._with(name=f"{self.name} contour {k}"))
        self._at = None

    @property
    def scene(self) -> Any:
        """The curves drawn so far, as a :class:`splinescope.Scene`."""
        from . import Scene

        if self._segments:
            self._finish(False)
        return Scene(self.curves)


def draw(curve: Any, pen: Any, tolerance: Any = None) -> None:
    """Draws `curve`'s segments into `pen` (see :meth:`splinescope.Curve.draw`)."""
    segs = curve.segments()
    if not segs:
        return
    if any(len(s) > 3 or len(s[2]) - 1 > 3 for s in segs):
        from . import Bezier, RationalBezier

        if tolerance is None:
            box = np.asarray(curve.bbox(), dtype=float)
            tolerance = 1e-6 * max(float(np.linalg.norm(box[1] - box[0])), 1e-300)
        drawn = []
        for s in segs:
            if len(s) <= 3 and len(s[2]) - 1 <= 3:
                drawn.append(s)
                continue
            piece = RationalBezier(s[2], s[3]) if len(s) > 3 else Bezier(s[2])
            drawn.extend(piece.to_cubics(tolerance).segments())
        segs = drawn
    closed = bool(getattr(curve, "closed", False))
    pts = lambda s: [tuple(float(v) for v in p[:2]) for p in s[2]]  # noqa: E731
    first = pts(segs[0])
    pen.moveTo(first[0])
    for k, s in enumerate(segs):
        p = pts(s)
        last = closed and k == len(segs) - 1
        if len(p) == 2:
            if not last:
                pen.lineTo(p[1])
        elif len(p) == 3:
            pen.qCurveTo(p[1], p[2])
        else:
            pen.curveTo(p[1], p[2], p[3])
    if closed:
        pen.closePath()
    else:
        pen.endPath()

"""DXF against ezdxf (an independent reader and writer): files ezdxf writes (ASCII and
binary) read as the curves ezdxf evaluates — splines point for point through ezdxf's own
B-spline evaluator, arcs, circles, ellipses and bulges on the geometry ezdxf's construction
tools give, blocks where ezdxf's own decomposition puts them — and every family written
by splinescope read by ezdxf, its SPLINE entities evaluating to the curves' points."""

import math
import os
import warnings

import numpy as np
import pytest

import splinescope as ss

try:
    import ezdxf
except ImportError:  # pragma: no cover - scripts/python-dev installs it
    pytest.fail("ezdxf is missing: it is a test extra, scripts/python-dev installs it", pytrace=False)
from ezdxf import disassemble  # noqa: E402
from ezdxf.math import BSpline as EzBSpline  # noqa: E402
from ezdxf.math import bulge_to_arc  # noqa: E402
from scipy.interpolate import BSpline  # noqa: E402


def _rng():
    return np.random.default_rng(47)


def _doc():
    doc = ezdxf.new("R2018")
    return doc, doc.modelspace()


def _save(doc, tmp_path, name, binary):
    p = os.path.join(tmp_path, name)
    doc.saveas(p, fmt="bin" if binary else "asc")
    return p


def _load(path):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return ss.load(path)


def _ezdxf_point(e, t):
    """The point of SPLINE `e` at the file's parameter `t`, by ezdxf's B-spline evaluator
    on the entity's own control points, knots and weights."""
    w = list(e.weights)
    b = EzBSpline(list(e.control_points), order=e.dxf.degree + 1, knots=list(e.knots), weights=w or None)
    return tuple(b.point(float(t)))


def _span(c, n=101):
    a, b = c.domain()
    return np.linspace(a, b, n)


@pytest.mark.parametrize("binary", [False, True])
def test_splines_ezdxf_writes_evaluate_where_ezdxf_evaluates_them(tmp_path, binary):
    rng = _rng()
    doc, msp = _doc()
    made = []
    for k in range(60):
        degree = int(rng.integers(1, 8))
        n = degree + 1 + int(rng.integers(0, 12))
        pts = rng.normal(size=(n, 3)) * 10.0 ** rng.integers(-3, 4)
        if k % 3 == 0:
            pts[:, 2] = 0.0
        inner = np.sort(rng.uniform(0, 5, size=n - degree - 1))
        if k % 4 == 0 and len(inner) > 1:
            inner[1] = inner[0]  # a double knot
        clamped = k % 5 != 0
        if clamped:
            knots = np.concatenate([[0.0] * (degree + 1), inner, [5.0] * (degree + 1)])
        else:
            knots = np.sort(rng.uniform(-1, 6, size=n + degree + 1))
        weights = rng.uniform(0.2, 5.0, size=n) if k % 2 else None
        e = msp.add_open_spline(pts.tolist(), degree=degree, knots=knots.tolist())
        if weights is not None:
            e.dxf.flags = e.dxf.flags | 4
            e.weights = weights.tolist()
        made.append(e)
    path = _save(doc, tmp_path, "splines.dxf", binary)
    scene = _load(path)
    assert len(scene) == len(made)
    for e, c in zip(made, scene.curves):
        a, b = c.domain()
        # The same parameter range: the knots ezdxf wrote, from the degree's knot on.
        assert (a, b) == (e.knots[e.dxf.degree], e.knots[-e.dxf.degree - 1])
        ts = np.linspace(a, b, 41)
        ours = c.eval(ts)
        scale = 1.0 + np.abs(np.asarray(e.control_points)).max()
        # scipy on the homogeneous points (w·P, w), on the file's own knots.
        pts = np.asarray(e.control_points)[:, : ours.shape[1]]
        w = np.asarray(e.weights) if len(e.weights) else np.ones(len(pts))
        knots = np.asarray(e.knots)
        num = BSpline(knots, pts * w[:, None], e.dxf.degree, extrapolate=False)(ts)
        den = BSpline(knots, w, e.dxf.degree, extrapolate=False)(ts)
        sp = num / den[:, None]
        assert np.abs(ours - sp).max() <= 1e-12 * scale, (e.dxf.handle, np.abs(ours - sp).max())
        # ezdxf's evaluator takes clamped knots (it divides by zero on others).
        if clamped_knots(knots, e.dxf.degree):
            theirs = np.array([_ezdxf_point(e, t) for t in ts])[:, : ours.shape[1]]
            assert np.abs(ours - theirs).max() <= 1e-10 * scale, (e.dxf.handle, np.abs(ours - theirs).max())


def clamped_knots(knots, degree):
    return len(set(knots[: degree + 1])) == 1 and len(set(knots[-degree - 1 :])) == 1


@pytest.mark.parametrize("binary", [False, True])
def test_arcs_circles_ellipses_and_bulges_lie_on_ezdxfs_geometry(tmp_path, binary):
    rng = _rng()
    doc, msp = _doc()
    arcs, circles, ellipses, polys = [], [], [], []
    for k in range(20):
        normal = (0, 0, 1) if k % 2 else tuple(rng.normal(size=3))
        arcs.append(
            msp.add_arc(
                tuple(rng.normal(size=3)), float(rng.uniform(0.1, 9)), float(rng.uniform(-400, 400)),
                float(rng.uniform(-400, 400)), dxfattribs={"extrusion": normal},
            )
        )
        circles.append(msp.add_circle(tuple(rng.normal(size=3)), float(rng.uniform(0.1, 9)), dxfattribs={"extrusion": normal}))
        major = rng.normal(size=3)
        n = np.cross(major, rng.normal(size=3))
        ellipses.append(
            msp.add_ellipse(
                tuple(rng.normal(size=3)), tuple(major), float(rng.uniform(0.05, 1.0)),
                float(rng.uniform(0, 7)), float(rng.uniform(0, 7)), dxfattribs={"extrusion": tuple(n / np.linalg.norm(n))},
            )
        )
        pts = [(float(x), float(y), 0, 0, float(b)) for x, y, b in zip(rng.normal(size=6), rng.normal(size=6), rng.uniform(-3, 3, size=6))]
        polys.append(msp.add_lwpolyline(pts, format="xyseb", close=bool(k % 2), dxfattribs={"extrusion": normal, "elevation": 0.5}))
    path = _save(doc, tmp_path, "conics.dxf", binary)
    scene = _load(path)
    curves = scene.curves
    by_handle = {c.name.split(" ")[-1]: c for c in curves}
    for e in arcs + circles:
        c = by_handle[e.dxf.handle]
        ocs = e.ocs()
        centre = np.array(ocs.to_wcs(e.dxf.center))
        q = c.eval(_span(c))
        r = np.linalg.norm(q - centre, axis=1)
        assert np.abs(r - e.dxf.radius).max() <= 1e-12 * (1 + np.abs(centre).max() + e.dxf.radius)
        normal = np.array(ocs.uz)
        assert np.abs((q - centre) @ normal).max() <= 1e-12 * (1 + e.dxf.radius)
        if e.dxftype() == "ARC":
            # ezdxf's vertices are in the WCS.
            s, t = (np.array(v) for v in e.vertices([e.dxf.start_angle, e.dxf.end_angle]))
            assert np.abs(q[0] - s).max() <= 1e-12 * (1 + np.abs(s).max())
            assert np.abs(q[-1] - t).max() <= 1e-12 * (1 + np.abs(t).max())
            # The length: r times the counter-clockwise sweep.
            sweep = (e.dxf.end_angle - e.dxf.start_angle) % 360 or 360
            assert math.isclose(c.length(), e.dxf.radius * math.radians(sweep), rel_tol=1e-12)
        else:
            assert math.isclose(c.length(), 2 * math.pi * e.dxf.radius, rel_tol=1e-12)
    for e in ellipses:
        c = by_handle[e.dxf.handle]
        tool = e.construction_tool()
        ends = np.array([tuple(v) for v in tool.vertices([tool.start_param, tool.end_param])])
        q = c.eval(_span(c))
        assert np.abs(q[0] - ends[0]).max() <= 1e-12 * (1 + np.abs(ends).max())
        assert np.abs(q[-1] - ends[1]).max() <= 1e-12 * (1 + np.abs(ends).max())
        major, minor = np.array(tool.major_axis), np.array(tool.minor_axis)
        d = q - np.array(tool.center)
        u = d @ major / (major @ major)
        v = d @ minor / (minor @ minor)
        assert np.abs(u * u + v * v - 1).max() <= 1e-11
    for e in polys:
        c = by_handle[e.dxf.handle]
        # Each leg: ezdxf's bulge_to_arc gives the circle; our leg's points are on it.
        ocs = e.ocs()
        z = e.dxf.elevation
        verts = list(e.get_points("xyb"))
        legs = len(verts) if e.closed else len(verts) - 1
        q = c.eval(np.linspace(*c.domain(), 40 * legs + 1))
        for k in range(legs):
            (x0, y0, b), (x1, y1, _) = verts[k], verts[(k + 1) % len(verts)]
            piece = q[40 * k : 40 * k + 41] if len(c.segments()) == legs else None
            start = np.array(ocs.to_wcs((x0, y0, z)))
            assert np.abs(q[40 * k] - start).max() <= 1e-9 or piece is None
            if b == 0 or piece is None:
                continue
            centre, _, _, r = bulge_to_arc((x0, y0), (x1, y1), b)
            centre = np.array(ocs.to_wcs((centre[0], centre[1], z)))
            assert np.abs(np.linalg.norm(piece - centre, axis=1) - r).max() <= 1e-10 * (1 + r)


def test_blocks_land_where_ezdxfs_decomposition_puts_them(tmp_path):
    rng = _rng()
    doc, msp = _doc()
    inner = doc.blocks.new("inner", base_point=(1, 2))
    inner.add_line((1, 2), (4, 3))
    inner.add_circle((3, 3), 0.5)
    outer = doc.blocks.new("outer")
    outer.add_blockref("inner", (5, 0), dxfattribs={"rotation": 30, "xscale": 2, "yscale": 0.5})
    # The outer references scale evenly: ezdxf's decomposition turns a nested insert into
    # one insert with a scale and a rotation, which cannot hold the shear an uneven scale
    # of a rotated inner block makes (splinescope maps by the whole affine map; the Rust
    # tests check that case against the composition by hand).
    for k in range(5):
        s = float(rng.uniform(0.5, 2))
        msp.add_blockref(
            "outer", tuple(rng.normal(size=2) * 10),
            dxfattribs={"rotation": float(rng.uniform(0, 360)), "xscale": s, "yscale": s},
        )
    path = _save(doc, tmp_path, "blocks.dxf", False)
    scene = _load(path)
    ours = [c for c in scene.curves]
    theirs = [e for e in disassemble.recursive_decompose(msp) if e.dxftype() in ("LINE", "ELLIPSE", "CIRCLE")]
    assert len(ours) == len(theirs) == 10
    for c, e in zip(ours, theirs):
        q = c.eval(np.array(c.domain()))
        if e.dxftype() == "LINE":
            want = np.array([tuple(e.dxf.start), tuple(e.dxf.end)])[:, : q.shape[1]]
            assert np.abs(q - want).max() <= 1e-12 * (1 + np.abs(want).max())
        else:
            # A circle scaled unevenly is an ellipse: every point of ours on it.
            tool = e.construction_tool() if e.dxftype() == "ELLIPSE" else None
            pts = c.eval(_span(c))
            if tool is None:
                centre = np.array(e.dxf.center)[: pts.shape[1]]
                assert np.abs(np.linalg.norm(pts - centre, axis=1) - e.dxf.radius).max() <= 1e-12
            else:
                major, minor = np.array(tool.major_axis), np.array(tool.minor_axis)
                d = np.pad(pts, ((0, 0), (0, 3 - pts.shape[1]))) - np.array(tool.center)
                u, v = d @ major / (major @ major), d @ minor / (minor @ minor)
                assert np.abs(u * u + v * v - 1).max() <= 1e-11


def test_every_family_splinescope_writes_ezdxf_reads_and_evaluates(tmp_path):
    rng = _rng()
    curves = [
        ss.Bezier(rng.normal(size=(6, 2))),
        ss.ModifiedBezier(rng.normal(size=(5, 2)), t_star=0.4, v=(0.5, -0.2)),
        ss.BSpline(np.concatenate([[0.0] * 4, [0.3, 0.3, 0.8], [1.0] * 4]), rng.normal(size=(7, 2)), order=4),
        ss.RationalBezier(rng.normal(size=(4, 2)), rng.uniform(0.3, 3, size=4)),
        ss.Nurbs(np.array([0, 0, 0, 0.5, 0.5, 0.7, 1, 1, 1.0]), rng.normal(size=(6, 2)), order=3, weights=rng.uniform(0.3, 3, size=6)),
        ss.Path([np.array([[0, 0], [1, 2], [3, 2], [4, 0.0]]), np.array([[4, 0], [5, -1.0]]), (np.array([[5, -1], [6, 0], [7, -1.0]]), np.array([1, 0.5, 2.0]))]),
    ]
    for name in ("gallery.json", "paths.json"):
        p = os.path.join(os.path.dirname(__file__), "..", "..", "..", "scenes", name)
        if os.path.exists(p):
            curves += ss.load(p).curves
    scene = ss.Scene(curves)
    out = os.path.join(tmp_path, "ours.dxf")
    scene.save(out)
    doc = ezdxf.readfile(out)
    auditor = doc.audit()
    assert not auditor.has_errors, [str(e) for e in auditor.errors]
    splines = doc.modelspace().query("SPLINE")
    assert len(splines) == len(curves)
    families, checked = set(), set()
    for c, e in zip(curves, splines):
        families.add(c.family)
        ts = np.linspace(*c.domain(), 33)
        ours = c.eval(ts)
        scale = 1.0 + np.abs(ours).max()
        # What ezdxf read, evaluated by scipy on the homogeneous points: every curve.
        pts = np.asarray(e.control_points)[:, : ours.shape[1]]
        w = np.asarray(e.weights) if len(e.weights) else np.ones(len(pts))
        knots = np.asarray(e.knots)
        num = BSpline(knots, pts * w[:, None], e.dxf.degree, extrapolate=False)(ts)
        den = BSpline(knots, w, e.dxf.degree, extrapolate=False)(ts)
        assert np.abs(ours - num / den[:, None]).max() <= 1e-9 * scale, c.family
        # ezdxf's evaluator stops at order 11 (the gallery's degree-31 spiral is past it).
        if e.dxf.degree + 1 <= 11:
            theirs = np.array([_ezdxf_point(e, t) for t in ts])[:, : ours.shape[1]]
            assert np.abs(ours - theirs).max() <= 1e-9 * scale, (c.family, np.abs(ours - theirs).max())
            checked.add(c.family)
    assert families == checked == {
        "bezier", "modified_bezier", "interpolation", "bspline", "nubmp", "rational_bezier", "nurbs", "path"
    }, (families, checked)

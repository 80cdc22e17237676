"""STEP against OCCT (an independent CAD kernel, from the cadquery-ocp wheel): files OCCT
writes — solids' B-rep edges (lines, circles, seams), free edges on an ellipse and a
rational B-spline, in millimetres and in inches — read as 3D curves that lie on OCCT's
own evaluation of each edge (its points projected by OCCT onto ours' edge, its ends at the
edge's vertices, its length OCCT's), one curve per edge, in the file's length unit."""

import math
import os
import warnings

import numpy as np
import pytest

import splinescope as ss

try:
    from OCP.BRep import BRep_Builder, BRep_Tool
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCone, BRepPrimAPI_MakeCylinder
    from OCP.GCPnts import GCPnts_AbscissaPoint
    from OCP.Geom import Geom_BSplineCurve
    from OCP.GeomAPI import GeomAPI_ProjectPointOnCurve
    from OCP.gp import gp_Ax2, gp_Circ, gp_Dir, gp_Elips, gp_Pnt
    from OCP.OCP.collections import Array1_double, Array1_gp_Pnt, Array1_int
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Reader, STEPControl_Writer
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp
    from OCP.TopoDS import TopoDS, TopoDS_Compound
    from OCP.OCP.collections import IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as TopTools_IndexedMapOfShape
except ImportError:  # pragma: no cover - scripts/python-dev installs it
    pytest.fail("cadquery-ocp is missing: it is a test extra, scripts/python-dev installs it", pytrace=False)


def _shapes():
    b = BRep_Builder()
    comp = TopoDS_Compound()
    b.MakeCompound(comp)
    b.Add(comp, BRepPrimAPI_MakeBox(10, 20, 30).Shape())
    b.Add(comp, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(40, 0, 0), gp_Dir(0, 0, 1)), 5, 12).Shape())
    b.Add(comp, BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(-40, 5, 3), gp_Dir(1, 1, 0)), 6, 2, 9).Shape())
    b.Add(comp, BRepBuilderAPI_MakeEdge(gp_Elips(gp_Ax2(gp_Pnt(0, 50, 0), gp_Dir(0, 1, 1)), 8, 3), 0.3, 2.5).Edge())
    b.Add(comp, BRepBuilderAPI_MakeEdge(gp_Circ(gp_Ax2(gp_Pnt(3, -20, 1), gp_Dir(1, 0, 0)), 4), 5.0, 1.0).Edge())
    pts = Array1_gp_Pnt(1, 6)
    for i, p in enumerate([(0, 0, 0), (1, 2, 0), (3, 3, 1), (5, 1, 2), (6, 0, 0), (8, -1, 1)]):
        pts.SetValue(i + 1, gp_Pnt(*p))
    w = Array1_double(1, 6)
    for i, x in enumerate([1, 0.5, 2, 0.8, 1.5, 1]):
        w.SetValue(i + 1, x)
    k, m = Array1_double(1, 4), Array1_int(1, 4)
    for i, (kv, mv) in enumerate([(0, 4), (0.4, 1), (0.7, 1), (1, 4)]):
        k.SetValue(i + 1, kv)
        m.SetValue(i + 1, mv)
    b.Add(comp, BRepBuilderAPI_MakeEdge(Geom_BSplineCurve(pts, w, k, m, 3)).Edge())
    return comp


def _write(shape, path, unit):
    """OCCT writes the file in millimetres; for inches its length units are then declared
    inches (a CONVERSION_BASED_UNIT of 25.4 mm), the numbers unchanged: OCCT reads such a
    file scaled to millimetres, splinescope in the file's unit."""
    w = STEPControl_Writer()
    w.Transfer(shape, STEPControl_AsIs)
    assert int(w.Write(path)) == 1
    if unit == "IN":
        text = open(path).read()
        mm = "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )"
        assert mm in text
        text = text.replace(mm, "( CONVERSION_BASED_UNIT('INCH',#990001) LENGTH_UNIT() NAMED_UNIT(*) )")
        text = text.replace(
            "ENDSEC;\nEND-ISO-10303-21;",
            "#990001 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#990002);\n"
            f"#990002 = {mm};\nENDSEC;\nEND-ISO-10303-21;",
        )
        open(path, "w").write(text)


def _occt_edges(path):
    """The file's edges as OCCT reads and evaluates them: (curve adaptor, first and last
    point, length), degenerate edges left out."""
    r = STEPControl_Reader()
    r.ReadFile(path)
    r.TransferRoots()
    shape = r.OneShape()
    edges = TopTools_IndexedMapOfShape()
    TopExp.MapShapes_s(shape, TopAbs_EDGE, edges)
    out = []
    for i in range(1, edges.Size() + 1):
        e = TopoDS.Edge(edges.FindKey(i))
        if BRep_Tool.Degenerated_s(e):
            continue
        a = BRepAdaptor_Curve(e)
        p0, p1 = a.Value(a.FirstParameter()), a.Value(a.LastParameter())
        curve = BRep_Tool.Curve_s(e, 0.0, 0.0)
        out.append(
            {
                "ends": np.array([[p0.X(), p0.Y(), p0.Z()], [p1.X(), p1.Y(), p1.Z()]]),
                "length": GCPnts_AbscissaPoint.Length_s(a, 1e-13),
                "curve": curve,
                "mid": a.Value(0.5 * (a.FirstParameter() + a.LastParameter())),
            }
        )
    return out


@pytest.mark.parametrize("unit,name,scale", [("MM", "millimetre", 1.0), ("IN", "inch", 25.4)])
def test_every_edge_lies_on_occts_curve_with_its_ends_and_length(tmp_path, unit, name, scale):
    path = os.path.join(tmp_path, f"parts-{unit}.step")
    _write(_shapes(), path, unit)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        scene = ss.load(path)
    assert scene.unit == name
    occt = _occt_edges(path)
    ours = scene.curves
    assert len(ours) == len(occt), (len(ours), len(occt))
    # OCCT's numbers in the file's unit.
    for e in occt:
        e["ends"] = e["ends"] / scale
        e["length"] /= scale
    used = set()
    for c in ours:
        a, b = c.domain()
        ends = c.eval(np.array([a, b]))
        length = c.length()
        match = [
            k
            for k, e in enumerate(occt)
            if k not in used
            and (
                np.abs(ends - e["ends"]).max() <= 1e-9 * (1 + np.abs(e["ends"]).max())
                or np.abs(ends[::-1] - e["ends"]).max() <= 1e-9 * (1 + np.abs(e["ends"]).max())
            )
            and math.isclose(length, e["length"], rel_tol=1e-9)
        ]
        assert match, (c.name, ends, length)
        k = match[0]
        used.add(k)
        # Every point of ours on OCCT's curve, by OCCT's projection.
        for t in np.linspace(a, b, 33):
            q = c.eval(np.array([t]))[0]
            proj = GeomAPI_ProjectPointOnCurve(gp_Pnt(*(q * scale)), occt[k]["curve"])
            assert proj.NbPoints() > 0 and proj.LowerDistance() <= 1e-9 * scale * (1 + np.abs(q).max()), (c.name, t)
    assert len(used) == len(occt)
    # The families: circles and ellipses as exact rational arcs, the B-spline as itself.
    kinds = {c.family for c in ours}
    assert kinds == {"path"}, kinds


def test_the_box_edges_are_its_twelve_lines_in_the_files_unit(tmp_path):
    path = os.path.join(tmp_path, "box.step")
    b = BRep_Builder()
    _write(BRepPrimAPI_MakeBox(10, 20, 30).Shape(), path, "MM")
    scene = ss.load(path)
    assert len(scene) == 12
    lengths = sorted(round(c.length(), 12) for c in scene.curves)
    assert lengths == [10.0] * 4 + [20.0] * 4 + [30.0] * 4
    del b

//! STEP in, against closed forms: conics trimmed by parameter (radians and degrees) and by
//! point, in either sense; composite curves; Bézier and rational B-spline curves with the
//! file's knots; units; and hostile files refused naming the entity and its line.

use std::f64::consts::PI;

use glam::DVec3;
use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::geom::{Curve, ParamCurve};
use splinescope_import::{ImportError, Imported, step};

const HEAD: &str = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('test'),'2;1');\nFILE_NAME('t.step','2026-12-05',(''),(''),'','','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n";
const MM: &str = "#900 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\n";
const DEG: &str = "#901 = ( CONVERSION_BASED_UNIT('DEGREE',#902) NAMED_UNIT(*) PLANE_ANGLE_UNIT() );\n#902 = PLANE_ANGLE_MEASURE_WITH_UNIT(PLANE_ANGLE_MEASURE(0.0174532925199433),#903);\n#903 = ( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );\n";

fn file(data: &str) -> String {
    format!("{HEAD}{data}ENDSEC;\nEND-ISO-10303-21;\n")
}

fn read(data: &str) -> Imported {
    step::read(&file(data), "t.step").unwrap_or_else(|e| panic!("{e}"))
}

fn refused(data: &str) -> String {
    match step::read(&file(data), "t.step") {
        Ok(i) => panic!("read {} curves from {data}", i.scene.curves.len()),
        Err(e) => {
            let m = e.to_string();
            assert!(m.starts_with("t.step"), "{m}");
            m
        }
    }
}

fn length(c: &Curve) -> f64 {
    let (a, b) = c.domain();
    CurveAnalysis::new(c)
        .length(a, b, 1e-13)
        .expect("length")
        .value
}

/// A circle of radius 2 about (1, 2, 3) in the plane x + z = const: axis (1, 0, 1)/√2,
/// reference direction y.
const CIRCLE: &str = "#1 = CARTESIAN_POINT('',(1.,2.,3.));\n#2 = DIRECTION('',(1.,0.,1.));\n#3 = DIRECTION('',(0.,1.,0.));\n#4 = AXIS2_PLACEMENT_3D('',#1,#2,#3);\n#5 = CIRCLE('c',#4,2.);\n";

#[test]
fn a_free_circle_is_closed_exact_and_in_the_files_unit() {
    let i = read(&format!("{CIRCLE}{MM}"));
    assert_eq!(i.scene.unit.as_deref(), Some("millimetre"));
    assert_eq!(i.scene.curves.len(), 1);
    let c = &i.scene.curves[0].curve;
    assert!((length(c) - 4.0 * PI).abs() <= 1e-12, "{}", length(c));
    let (a, b) = c.domain();
    let axis = DVec3::new(1.0, 0.0, 1.0).normalize();
    for k in 0..=100 {
        let q = c.eval(a + (b - a) * f64::from(k) / 100.0) - DVec3::new(1.0, 2.0, 3.0);
        assert!((q.length() - 2.0).abs() <= 1e-13);
        assert!(q.dot(axis).abs() <= 1e-13);
    }
    // It starts on the reference direction.
    assert!((c.eval(a) - DVec3::new(1.0, 4.0, 3.0)).length() <= 1e-13);
    assert!(
        i.scene.curves[0]
            .name
            .as_deref()
            .unwrap()
            .contains("#5 CIRCLE c")
    );
}

#[test]
fn trims_by_parameter_in_degrees_and_by_point_in_either_sense() {
    // 90° to 180° in degrees; the same arc by its points, against the sense (the long
    // way round, 270°).
    let data = format!(
        "{CIRCLE}{DEG}#10 = TRIMMED_CURVE('',#5,(PARAMETER_VALUE(90.)),(PARAMETER_VALUE(180.)),.T.,.PARAMETER.);\n#11 = CARTESIAN_POINT('',(-0.41421356237309515,2.,4.414213562373095));\n#12 = TRIMMED_CURVE('',#5,(#11),(#13),.F.,.CARTESIAN.);\n#13 = CARTESIAN_POINT('',(1.,0.,3.));\n"
    );
    let i = read(&data);
    assert_eq!(
        i.scene.curves.len(),
        2,
        "the basis circle is drawn only trimmed"
    );
    let quarter = &i.scene.curves[0].curve;
    assert!((length(quarter) - PI).abs() <= 1e-12, "{}", length(quarter));
    let long = &i.scene.curves[1].curve;
    assert!((length(long) - 3.0 * PI).abs() <= 1e-12, "{}", length(long));
    let (a, b) = long.domain();
    let top = DVec3::new(1.0, 2.0, 3.0) + 2.0 * DVec3::new(-1.0, 0.0, 1.0).normalize();
    assert!((long.eval(a) - top).length() <= 1e-12);
    assert!((long.eval(b) - DVec3::new(1.0, 0.0, 3.0)).length() <= 1e-12);
    // The circle's x axis (y) at 0, so 90° is along z × x: the quarter starts there.
    let x = DVec3::Y;
    let y = DVec3::new(1.0, 0.0, 1.0).normalize().cross(x);
    let (a, _) = quarter.domain();
    assert!((quarter.eval(a) - (DVec3::new(1.0, 2.0, 3.0) + 2.0 * y)).length() <= 1e-12);
}

#[test]
fn composite_curves_join_their_segments_each_in_its_sense() {
    // A line from (0,0,0) to (4,0,0), then an ellipse arc (a = 4, b = 2 about (0,0,0))
    // from 0 to 90° taken backwards... joined: the line, then the arc reversed from
    // (0,2,0) — no: the arc forward from (4,0,0) to (0,2,0).
    let data = "#1 = CARTESIAN_POINT('',(0.,0.,0.));\n#2 = DIRECTION('',(1.,0.,0.));\n#3 = VECTOR('',#2,1.);\n#4 = LINE('',#1,#3);\n#5 = TRIMMED_CURVE('',#4,(PARAMETER_VALUE(0.)),(PARAMETER_VALUE(4.)),.T.,.PARAMETER.);\n#6 = DIRECTION('',(0.,0.,1.));\n#7 = AXIS2_PLACEMENT_3D('',#1,#6,#2);\n#8 = ELLIPSE('',#7,4.,2.);\n#9 = TRIMMED_CURVE('',#8,(PARAMETER_VALUE(0.)),(PARAMETER_VALUE(1.5707963267948966)),.T.,.PARAMETER.);\n#10 = COMPOSITE_CURVE_SEGMENT(.CONTINUOUS.,.T.,#5);\n#11 = COMPOSITE_CURVE_SEGMENT(.CONTINUOUS.,.T.,#9);\n#12 = COMPOSITE_CURVE('',(#10,#11),.F.);\n#13 = COMPOSITE_CURVE_SEGMENT(.CONTINUOUS.,.F.,#9);\n#14 = COMPOSITE_CURVE('',(#13),.F.);\n";
    let i = read(data);
    assert_eq!(i.scene.curves.len(), 2);
    let c = &i.scene.curves[0].curve;
    let Curve::Path(p) = c else {
        panic!("{}", c.family())
    };
    assert_eq!(p.segments().len(), 2);
    let (a, b) = c.domain();
    assert!((c.eval(a) - DVec3::ZERO).length() <= 1e-15);
    assert!((c.eval(b) - DVec3::new(0.0, 2.0, 0.0)).length() <= 1e-15);
    for k in 0..=50 {
        let q = c.eval(1.0 + f64::from(k) / 50.0);
        assert!(((q.x / 4.0).powi(2) + (q.y / 2.0).powi(2) - 1.0).abs() <= 1e-14);
    }
    // The reversed one runs from (0,2,0) to (4,0,0).
    let r = &i.scene.curves[1].curve;
    let (a, b) = r.domain();
    assert!((r.eval(a) - DVec3::new(0.0, 2.0, 0.0)).length() <= 1e-15);
    assert!((r.eval(b) - DVec3::new(4.0, 0.0, 0.0)).length() <= 1e-15);
}

#[test]
fn b_splines_keep_the_files_knots_and_weights_and_bezier_curves_their_pieces() {
    let pts = "#1 = CARTESIAN_POINT('',(0.,0.,0.));\n#2 = CARTESIAN_POINT('',(1.,2.,0.));\n#3 = CARTESIAN_POINT('',(3.,2.,1.));\n#4 = CARTESIAN_POINT('',(4.,0.,0.));\n#5 = CARTESIAN_POINT('',(5.,-1.,2.));\n";
    let data = format!(
        "{pts}#10 = B_SPLINE_CURVE_WITH_KNOTS('plain',2,(#1,#2,#3,#4,#5),.UNSPECIFIED.,.F.,.F.,(3,1,1,3),(0.,0.25,0.5,2.),.UNSPECIFIED.);\n#11 = ( BOUNDED_CURVE() B_SPLINE_CURVE(2,(#1,#2,#3),.UNSPECIFIED.,.F.,.F.) B_SPLINE_CURVE_WITH_KNOTS((3,3),(0.,1.),.UNSPECIFIED.) CURVE() GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE((1.,0.5,2.)) REPRESENTATION_ITEM('rational') );\n#12 = BEZIER_CURVE('pieces',2,(#1,#2,#3,#4,#5),.UNSPECIFIED.,.F.,.F.);\n"
    );
    let i = read(&data);
    assert_eq!(i.scene.curves.len(), 3);
    let Curve::BSpline(b) = &i.scene.curves[0].curve else {
        panic!()
    };
    assert_eq!(
        b.knots().knots(),
        &[0.0, 0.0, 0.0, 0.25, 0.5, 2.0, 2.0, 2.0]
    );
    let Curve::Nurbs(n) = &i.scene.curves[1].curve else {
        panic!()
    };
    assert_eq!(n.weights(), &[1.0, 0.5, 2.0]);
    // The rational quadratic at t: Σ wᵢPᵢBᵢ / Σ wᵢBᵢ, by hand.
    let (p, w) = (
        [
            DVec3::ZERO,
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(3.0, 2.0, 1.0),
        ],
        [1.0, 0.5, 2.0],
    );
    for k in 0..=20 {
        let t = f64::from(k) / 20.0;
        let b = [(1.0 - t) * (1.0 - t), 2.0 * t * (1.0 - t), t * t];
        let num = (0..3)
            .map(|j| p[j] * w[j] * b[j])
            .fold(DVec3::ZERO, |a, x| a + x);
        let den: f64 = (0..3).map(|j| w[j] * b[j]).sum();
        assert!((n.eval(t) - num / den).length() <= 1e-14);
    }
    // The Bézier curve of degree 2 with five points: two pieces on [0, 1] and [1, 2].
    let c = &i.scene.curves[2].curve;
    assert_eq!(c.domain(), (0.0, 2.0));
    assert!((c.eval(1.0) - DVec3::new(3.0, 2.0, 1.0)).length() <= 1e-15);
    assert!((c.eval(0.5) - DVec3::new(1.25, 1.5, 0.25)).length() <= 1e-15);
}

#[test]
fn edges_are_trimmed_at_their_vertices() {
    let data = format!(
        "{CIRCLE}#20 = CARTESIAN_POINT('',(1.,4.,3.));\n#21 = VERTEX_POINT('',#20);\n#22 = CARTESIAN_POINT('',(1.,0.,3.));\n#23 = VERTEX_POINT('',#22);\n#24 = EDGE_CURVE('',#21,#23,#5,.T.);\n#25 = EDGE_CURVE('',#21,#21,#5,.F.);\n"
    );
    let i = read(&data);
    assert_eq!(
        i.scene.curves.len(),
        2,
        "the circle is the edges' geometry, not drawn alone"
    );
    assert!((length(&i.scene.curves[0].curve) - 2.0 * PI).abs() <= 1e-12);
    assert!((length(&i.scene.curves[1].curve) - 4.0 * PI).abs() <= 1e-12);
}

#[test]
fn hostile_files_are_refused_naming_the_entity_and_its_line() {
    // Missing and cyclic references.
    let m = refused("#5 = CIRCLE('',#4,2.);\n");
    assert!(
        m.contains("#5 CIRCLE (line 8)") && m.contains("#4, which is not in the file"),
        "{m}"
    );
    let m = refused(
        "#1 = TRIMMED_CURVE('',#2,(PARAMETER_VALUE(0.)),(PARAMETER_VALUE(1.)),.T.,.PARAMETER.);\n#2 = TRIMMED_CURVE('',#1,(PARAMETER_VALUE(0.)),(PARAMETER_VALUE(1.)),.T.,.PARAMETER.);\n#3 = COMPOSITE_CURVE_SEGMENT(.CONTINUOUS.,.T.,#1);\n#4 = COMPOSITE_CURVE('',(#3),.F.);\n",
    );
    assert!(m.contains("refers to itself"), "{m}");
    // Decreasing knots, zero weights, a degree past the limit, multiplicities that
    // claim a billion knots.
    let pts = "#1 = CARTESIAN_POINT('',(0.,0.,0.));\n#2 = CARTESIAN_POINT('',(1.,2.,0.));\n#3 = CARTESIAN_POINT('',(3.,2.,1.));\n";
    let m = refused(&format!(
        "{pts}#10 = B_SPLINE_CURVE_WITH_KNOTS('',2,(#1,#2,#3),.UNSPECIFIED.,.F.,.F.,(3,3),(1.,0.),.UNSPECIFIED.);\n"
    ));
    assert!(m.contains("#10 B_SPLINE_CURVE_WITH_KNOTS"), "{m}");
    let m = refused(&format!(
        "{pts}#11 = ( BOUNDED_CURVE() B_SPLINE_CURVE(2,(#1,#2,#3),.UNSPECIFIED.,.F.,.F.) B_SPLINE_CURVE_WITH_KNOTS((3,3),(0.,1.),.UNSPECIFIED.) CURVE() GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE((1.,0.,2.)) REPRESENTATION_ITEM('') );\n"
    ));
    assert!(m.contains("weight"), "{m}");
    let m = refused(&format!(
        "{pts}#10 = B_SPLINE_CURVE_WITH_KNOTS('',100000,(#1,#2,#3),.UNSPECIFIED.,.F.,.F.,(3,3),(0.,1.),.UNSPECIFIED.);\n"
    ));
    assert!(m.contains("SPLINESCOPE_MAX_ORDER"), "{m}");
    let m = refused(&format!(
        "{pts}#10 = B_SPLINE_CURVE_WITH_KNOTS('',2,(#1,#2,#3),.UNSPECIFIED.,.F.,.F.,(1000000000,3),(0.,1.),.UNSPECIFIED.);\n"
    ));
    assert!(m.contains("multiplicit"), "{m}");
    // A coordinate that overflows to infinity, and a point that is not a point.
    let m = refused(
        "#1 = CARTESIAN_POINT('',(1.E999,0.,0.));\n#2 = DIRECTION('',(0.,0.,1.));\n#3 = AXIS2_PLACEMENT_3D('',#1,#2,$);\n#4 = CIRCLE('',#3,1.);\n",
    );
    assert!(m.contains("#1 CARTESIAN_POINT") && m.contains("inf"), "{m}");
    // Syntax: truncated, wrong magic, a repeated id, lists nested past the limit.
    let text = file(CIRCLE);
    for cut in [10, 200, text.len() - 20] {
        match step::read(&text[..cut], "t.step") {
            Err(ImportError::Syntax { file, line, .. }) => {
                assert_eq!(file, "t.step");
                assert!(line >= 1);
            }
            other => panic!("{cut}: {other:?}"),
        }
    }
    assert!(matches!(
        step::read("hello", "t.step"),
        Err(ImportError::Syntax { .. })
    ));
    let m = refused("#1 = CARTESIAN_POINT('',(0.,0.,0.));\n#1 = CARTESIAN_POINT('',(0.,0.,0.));\n");
    assert!(
        m.contains("#1 is defined twice") && m.contains(":9:"),
        "{m}"
    );
    let deep = format!(
        "#1 = CARTESIAN_POINT('',{}0.{});\n",
        "(".repeat(100_000),
        ")".repeat(100_000)
    );
    let m = refused(&deep);
    assert!(m.contains("nested past the limit"), "{m}");
}

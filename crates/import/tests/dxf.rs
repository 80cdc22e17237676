//! DXF in and out: every family written and read back evaluates to the same points bit
//! for bit; entities built with the `dxf` crate read against closed forms (arc lengths,
//! points on circles and ellipses, bulges, inserted blocks, colours); hostile files
//! refused with the entity's handle.

use std::f64::consts::PI;

use dxf::entities::{Entity, EntityType};
use dxf::{Drawing, Point};
use glam::DVec3;
use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::geom::{BSpline, Curve, Nurbs, NurbsForm, ParamCurve, Path};
use splinescope_import::dxf as sdxf;
use splinescope_import::{ImportError, Imported};
use splinescope_scene::format::Scene;

fn bytes(d: &Drawing) -> Vec<u8> {
    let mut out = Vec::new();
    d.save(&mut out).expect("the dxf crate writes");
    out
}

fn read(d: &Drawing) -> Imported {
    sdxf::read(&bytes(d), "test.dxf").unwrap_or_else(|e| panic!("{e}"))
}

fn path(i: &Imported, k: usize) -> &Path {
    match &i.scene.curves[k].curve {
        Curve::Path(p) => p,
        other => panic!("curve {k} is a {}", other.family()),
    }
}

fn length(p: &Path) -> f64 {
    let (a, b) = p.domain();
    CurveAnalysis::new(p)
        .length(a, b, 1e-13)
        .expect("length")
        .value
}

fn new_drawing() -> Drawing {
    let mut d = Drawing::new();
    d.header.version = dxf::enums::AcadVersion::R2018;
    d
}

fn drawing_of(entities: Vec<Entity>) -> Drawing {
    let mut d = new_drawing();
    for e in entities {
        d.add_entity(e);
    }
    d
}

/// A small deterministic generator (xorshift).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The curve a form reads back as: a B-spline, or a NURBS curve when it has weights.
fn curve_of(f: &NurbsForm) -> Curve {
    match &f.weights {
        None => Curve::BSpline(
            BSpline::try_new(f.points.clone(), f.knots.clone(), f.degree + 1).unwrap(),
        ),
        Some(w) => Curve::Nurbs(
            Nurbs::try_new(f.points.clone(), w.clone(), f.knots.clone(), f.degree + 1).unwrap(),
        ),
    }
}

fn scenes() -> Vec<Scene> {
    let mut out = Vec::new();
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes");
    for entry in std::fs::read_dir(dir).expect("scenes/") {
        let p = entry.unwrap().path();
        if p.extension().is_some_and(|e| e == "json")
            && let Ok(s) = Scene::load(&p)
        {
            out.push(s);
        }
    }
    // Random curves of every family and degree, 2D and 3D, at scales from 1e-6 to 1e6.
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut curves = Vec::new();
    for family in Curve::FAMILY_NAMES {
        for degree in 1..=7 {
            for scale in [1e-6, 1.0, 1e6] {
                let flat = degree % 2 == 0;
                let mut point = || {
                    DVec3::new(
                        rng.next() * scale,
                        rng.next() * scale,
                        if flat { 0.0 } else { rng.next() * scale },
                    )
                };
                if let Some(Ok(c)) = Curve::generated(family, degree, &mut point) {
                    curves.push(c);
                }
            }
        }
    }
    out.push(Scene::of_curves(curves));
    out
}

#[test]
fn every_family_written_and_read_back_evaluates_to_the_same_points_bit_for_bit() {
    let mut checked = 0;
    let mut families = std::collections::BTreeSet::new();
    for scene in scenes() {
        let file = sdxf::write(&scene).expect("write");
        let back = sdxf::read(&file, "back.dxf").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(back.scene.curves.len(), scene.curves.len());
        for (c, b) in scene.curves.iter().zip(&back.scene.curves) {
            families.insert(c.curve.family());
            let form = NurbsForm::of(&c.curve);
            let expected = curve_of(&form);
            assert_eq!(expected.domain(), b.curve.domain(), "{}", c.curve.family());
            let (t0, t1) = expected.domain();
            for k in 0..=64 {
                let t = t0 + (t1 - t0) * f64::from(k) / 64.0;
                let (e, g) = (expected.eval(t), b.curve.eval(t));
                assert_eq!(
                    e.to_array().map(f64::to_bits),
                    g.to_array().map(f64::to_bits),
                    "{} at {t}",
                    c.curve.family()
                );
                // The form is the curve (an independent evaluation: the family's own).
                let o = c.curve.eval(t);
                let scale = 1.0
                    + c.curve
                        .control_points()
                        .iter()
                        .map(|p| p.abs().max_element())
                        .fold(0.0, f64::max);
                assert!(
                    (o - e).length() <= 1e-11 * scale,
                    "{}: {o} vs the form's {e} at {t}",
                    c.curve.family()
                );
                checked += 1;
            }
            // Its colour rides along as the entity's true colour.
            assert_eq!(b.style.color.to_rgba8()[..3], c.style.color.to_rgba8()[..3]);
        }
    }
    assert_eq!(families.len(), Curve::FAMILY_NAMES.len(), "{families:?}");
    assert!(checked > 10_000, "{checked}");
}

#[test]
fn the_ascii_writer_keeps_twelve_decimals() {
    let scene = Scene::of_curves([Curve::BSpline(
        BSpline::try_new(
            vec![
                DVec3::new(0.1, 1.0 / 3.0, 0.0),
                DVec3::new(2.0, 0.7, 0.0),
                DVec3::new(3.0, -1.0, 0.0),
            ],
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            3,
        )
        .unwrap(),
    )]);
    let text = sdxf::write_ascii(&scene).unwrap();
    let back = sdxf::read(&text, "a.dxf").unwrap();
    let (a, b) = (&scene.curves[0].curve, &back.scene.curves[0].curve);
    for k in 0..=10 {
        let t = f64::from(k) / 10.0;
        assert!((a.eval(t) - b.eval(t)).length() <= 1e-12);
    }
}

#[test]
fn arcs_circles_and_ellipses_are_exact() {
    let mut arc = dxf::entities::Arc::new(Point::new(1.0, 2.0, 0.0), 3.0, 30.0, 300.0);
    arc.normal = dxf::Vector::new(0.0, 0.0, 1.0);
    let circle = dxf::entities::Circle::new(Point::new(-5.0, 0.0, 0.0), 10.0);
    let ellipse = dxf::entities::Ellipse {
        center: Point::new(0.0, 0.0, 1.0),
        major_axis: dxf::Vector::new(4.0, 3.0, 0.0),
        normal: dxf::Vector::new(0.0, 0.0, 1.0),
        minor_axis_ratio: 0.5,
        start_parameter: 0.25,
        end_parameter: 4.0,
    };
    let i = read(&drawing_of(vec![
        Entity::new(EntityType::Arc(arc)),
        Entity::new(EntityType::Circle(circle)),
        Entity::new(EntityType::Ellipse(ellipse)),
    ]));
    // The arc: 270° of radius 3.
    let a = path(&i, 0);
    assert!((length(a) - 3.0 * 1.5 * PI).abs() <= 1e-12, "{}", length(a));
    let (s, e) = a.domain();
    let start = DVec3::new(
        1.0 + 3.0 * 30f64.to_radians().cos(),
        2.0 + 3.0 * 30f64.to_radians().sin(),
        0.0,
    );
    let end = DVec3::new(
        1.0 + 3.0 * 300f64.to_radians().cos(),
        2.0 + 3.0 * 300f64.to_radians().sin(),
        0.0,
    );
    assert!((a.eval(s) - start).length() <= 1e-14);
    assert!((a.eval(e) - end).length() <= 1e-14);
    // The circle: 2πr, closed, every point at r.
    let c = path(&i, 1);
    assert!(c.is_closed());
    assert!((length(c) - 20.0 * PI).abs() <= 1e-12, "{}", length(c));
    let (s, e) = c.domain();
    for k in 0..=100 {
        let q = c.eval(s + (e - s) * f64::from(k) / 100.0);
        assert!(((q - DVec3::new(-5.0, 0.0, 0.0)).length() - 10.0).abs() <= 1e-13);
    }
    // The ellipse: every point on it ((u/a)² + (v/b)² = 1 in its axes), its ends at the
    // parameters.
    let el = path(&i, 2);
    let major = DVec3::new(4.0, 3.0, 0.0);
    let minor = DVec3::new(-1.5, 2.0, 0.0);
    let (s, e) = el.domain();
    for k in 0..=100 {
        let q = el.eval(s + (e - s) * f64::from(k) / 100.0) - DVec3::new(0.0, 0.0, 1.0);
        let (u, v) = (q.dot(major) / 25.0, q.dot(minor) / 6.25);
        assert!((u * u + v * v - 1.0).abs() <= 1e-13, "{u} {v}");
    }
    let at = |t: f64| DVec3::new(0.0, 0.0, 1.0) + t.cos() * major + t.sin() * minor;
    assert!((el.eval(s) - at(0.25)).length() <= 1e-13);
    assert!((el.eval(e) - at(4.0)).length() <= 1e-13);
}

#[test]
fn bulges_are_exact_arcs_and_ocs_maps_to_the_world() {
    // A slot: two half circles (bulge 1) joined by straight legs, closed.
    let mut p = dxf::entities::LwPolyline::default();
    for (x, y, b) in [
        (0.0, 0.0, 0.0),
        (10.0, 0.0, 1.0),
        (10.0, 4.0, 0.0),
        (0.0, 4.0, 1.0),
    ] {
        p.vertices.push(dxf::LwPolylineVertex {
            x,
            y,
            bulge: b,
            ..Default::default()
        });
    }
    p.set_is_closed(true);
    // A circle whose extrusion is −z: the OCS x axis is −x, so its centre (3, 0) is at
    // (−3, 0) in the world.
    let mut flipped = dxf::entities::Circle::new(Point::new(3.0, 0.0, 0.0), 1.0);
    flipped.normal = dxf::Vector::new(0.0, 0.0, -1.0);
    let i = read(&drawing_of(vec![
        Entity::new(EntityType::LwPolyline(p)),
        Entity::new(EntityType::Circle(flipped)),
    ]));
    let slot = path(&i, 0);
    assert!(slot.is_closed());
    assert!(
        (length(slot) - (20.0 + 4.0 * PI)).abs() <= 1e-12,
        "{}",
        length(slot)
    );
    // The right half circle bulges to x = 12.
    let far = (0..=400)
        .map(|k| slot.eval(slot.domain().1 * f64::from(k) / 400.0).x)
        .fold(f64::MIN, f64::max);
    assert!((far - 12.0).abs() <= 1e-4, "{far}");
    let c = path(&i, 1);
    let (s, e) = c.domain();
    let centre = (c.eval(s) + c.eval(s + 0.5 * (e - s))) / 2.0;
    assert!(
        (centre - DVec3::new(-3.0, 0.0, 0.0)).length() <= 1e-12,
        "{centre}"
    );
}

#[test]
fn blocks_are_inserted_nested_with_scale_rotation_and_colour() {
    let mut d = new_drawing();
    let mut inner = dxf::Block {
        name: "inner".into(),
        base_point: Point::new(1.0, 0.0, 0.0),
        ..Default::default()
    };
    let mut line = Entity::new(EntityType::Line(dxf::entities::Line::new(
        Point::new(1.0, 0.0, 0.0),
        Point::new(2.0, 0.0, 0.0),
    )));
    line.common.color = dxf::Color::by_block();
    inner.entities.push(line);
    let mut outer = dxf::Block {
        name: "outer".into(),
        ..Default::default()
    };
    let mut ins = dxf::entities::Insert {
        name: "inner".into(),
        location: Point::new(0.0, 5.0, 0.0),
        rotation: 90.0,
        x_scale_factor: 2.0,
        ..Default::default()
    };
    ins.y_scale_factor = 1.0;
    ins.z_scale_factor = 1.0;
    let mut e = Entity::new(EntityType::Insert(ins));
    e.common.color = dxf::Color::by_block();
    outer.entities.push(e);
    d.add_block(inner);
    d.add_block(outer);
    let top = dxf::entities::Insert {
        name: "OUTER".into(),
        location: Point::new(100.0, 0.0, 0.0),
        x_scale_factor: 1.0,
        y_scale_factor: 1.0,
        z_scale_factor: 1.0,
        ..Default::default()
    };
    let mut e = Entity::new(EntityType::Insert(top));
    e.common.color = dxf::Color::from_index(1);
    d.add_entity(e);
    let i = read(&d);
    assert_eq!(i.scene.curves.len(), 1);
    let c = &i.scene.curves[0];
    // (1,0)→(2,0) about the base (1,0): (0,0)→(1,0), ×2 in x: (0,0)→(2,0), turned 90°:
    // (0,0)→(0,2), moved to (0,5) and then by (100,0).
    let (s, t) = c.curve.domain();
    assert!((c.curve.eval(s) - DVec3::new(100.0, 5.0, 0.0)).length() <= 1e-12);
    assert!((c.curve.eval(t) - DVec3::new(100.0, 7.0, 0.0)).length() <= 1e-12);
    // By block, through two inserts: the top insert's red.
    assert_eq!(c.style.color.to_rgba8(), [255, 0, 0, 255]);
}

#[test]
fn the_colour_index_follows_its_hues_values_and_saturations() {
    assert_eq!(sdxf::aci_rgb(1), [255, 0, 0]);
    assert_eq!(sdxf::aci_rgb(5), [0, 0, 255]);
    // Hue 0° at full value and saturation, then half saturated, then at 65%.
    assert_eq!(sdxf::aci_rgb(10), [255, 0, 0]);
    assert_eq!(sdxf::aci_rgb(11), [255, 127, 127]);
    assert_eq!(sdxf::aci_rgb(12), [165, 0, 0]);
    // Hue 120° (green) and 240° (blue).
    assert_eq!(sdxf::aci_rgb(90), [0, 255, 0]);
    assert_eq!(sdxf::aci_rgb(170), [0, 0, 255]);
    // 7 is black on the white a scene opens on.
    assert_eq!(sdxf::aci_rgb(7), [0, 0, 0]);
}

fn refused(d: &Drawing) -> String {
    match sdxf::read(&bytes(d), "bad.dxf") {
        Ok(i) => panic!("read: {:?}", i.scene.curves),
        Err(e) => {
            assert!(e.to_string().starts_with("bad.dxf"), "{e}");
            e.to_string()
        }
    }
}

#[test]
fn hostile_files_are_refused_naming_the_entity() {
    // A spline given only by fit points.
    let s = dxf::entities::Spline {
        degree_of_curve: 3,
        fit_points: vec![Point::new(0.0, 0.0, 0.0), Point::new(1.0, 1.0, 0.0)],
        ..Default::default()
    };
    let m = refused(&drawing_of(vec![Entity::new(EntityType::Spline(s))]));
    assert!(
        m.contains("SPLINE (handle") && m.contains("fit points"),
        "{m}"
    );
    // Decreasing knots, a zero weight, a NaN point, a degree past the limit.
    let base = || dxf::entities::Spline {
        degree_of_curve: 2,
        knot_values: vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        control_points: vec![
            Point::new(0.0, 0.0, 0.0),
            Point::new(1.0, 1.0, 0.0),
            Point::new(2.0, 0.0, 0.0),
        ],
        ..Default::default()
    };
    let mut s = base();
    s.knot_values = vec![0.0, 0.0, 1.0, 0.5, 1.0, 1.0];
    let m = refused(&drawing_of(vec![Entity::new(EntityType::Spline(s))]));
    assert!(m.contains("SPLINE"), "{m}");
    let mut s = base();
    s.weight_values = vec![1.0, 0.0, 1.0];
    let m = refused(&drawing_of(vec![Entity::new(EntityType::Spline(s))]));
    assert!(m.contains("weight"), "{m}");
    let mut s = base();
    s.control_points[1].x = f64::NAN;
    refused(&drawing_of(vec![Entity::new(EntityType::Spline(s))]));
    let mut s = base();
    s.degree_of_curve = 1_000_000;
    let m = refused(&drawing_of(vec![Entity::new(EntityType::Spline(s))]));
    assert!(m.contains("SPLINESCOPE_MAX_ORDER"), "{m}");
    // A block that inserts itself, and an insert of a block that is not there.
    let mut d = new_drawing();
    let mut b = dxf::Block {
        name: "loop".into(),
        ..Default::default()
    };
    let ins = dxf::entities::Insert {
        name: "loop".into(),
        x_scale_factor: 1.0,
        y_scale_factor: 1.0,
        z_scale_factor: 1.0,
        ..Default::default()
    };
    b.entities
        .push(Entity::new(EntityType::Insert(ins.clone())));
    d.add_block(b);
    d.add_entity(Entity::new(EntityType::Insert(ins)));
    let m = refused(&d);
    assert!(m.contains("inserts itself"), "{m}");
    let missing = dxf::entities::Insert {
        name: "nowhere".into(),
        x_scale_factor: 1.0,
        y_scale_factor: 1.0,
        z_scale_factor: 1.0,
        ..Default::default()
    };
    let m = refused(&drawing_of(vec![Entity::new(EntityType::Insert(missing))]));
    assert!(m.contains("\"nowhere\" is not in the file"), "{m}");
    // Radii, ratios, bulges and angles that are not usable numbers, named.
    let arc = |r: f64, a: f64| {
        Entity::new(EntityType::Arc(dxf::entities::Arc::new(
            Point::new(0.0, 0.0, 0.0),
            r,
            a,
            90.0,
        )))
    };
    for (e, want) in [
        (arc(0.0, 0.0), "radius 0"),
        (arc(-2.0, 0.0), "radius -2"),
        (arc(f64::NAN, 0.0), "radius NaN"),
        (arc(1.0, f64::INFINITY), "start angle inf"),
        (
            Entity::new(EntityType::Circle(dxf::entities::Circle::new(
                Point::new(0.0, 0.0, 0.0),
                f64::NEG_INFINITY,
            ))),
            "radius -inf",
        ),
        (
            Entity::new(EntityType::Ellipse(dxf::entities::Ellipse {
                major_axis: dxf::Vector::new(2.0, 0.0, 0.0),
                normal: dxf::Vector::new(0.0, 0.0, 1.0),
                minor_axis_ratio: 0.0,
                end_parameter: 1.0,
                ..Default::default()
            })),
            "minor axis ratio 0",
        ),
        (
            Entity::new(EntityType::LwPolyline({
                let mut p = dxf::entities::LwPolyline::default();
                p.vertices.push(dxf::LwPolylineVertex {
                    x: 0.0,
                    y: 0.0,
                    bulge: f64::NAN,
                    ..Default::default()
                });
                p.vertices.push(dxf::LwPolylineVertex {
                    x: 1.0,
                    y: 0.0,
                    ..Default::default()
                });
                p
            })),
            "bulge NaN",
        ),
    ] {
        let m = refused(&drawing_of(vec![e]));
        assert!(m.contains(want), "{want}: {m}");
    }
    // A header date far past the calendar: the `dxf` crate panics on it; that is this
    // file's error, said once, with no panic on stderr (the CLI test below checks that).
    let text = String::from_utf8(bytes(&drawing_of(vec![]))).unwrap();
    let at = text.find("$TDCREATE").expect("a creation date");
    let value = text[at..]
        .match_indices('\n')
        .nth(1)
        .map(|(i, _)| at + i + 1)
        .unwrap();
    let end = value + text[value..].find('\n').unwrap();
    let bad = format!("{}1e300{}", &text[..value], &text[end..]);
    match sdxf::read(bad.as_bytes(), "bad.dxf") {
        Err(ImportError::Io { message, .. }) => assert!(message.contains("failed"), "{message}"),
        other => panic!("{other:?}"),
    }
    // Not a DXF file, and one cut short.
    for junk in [&b"hello"[..], &bytes(&drawing_of(vec![]))[..200]] {
        match sdxf::read(junk, "bad.dxf") {
            Err(ImportError::Io { file, .. }) => assert_eq!(file, "bad.dxf"),
            Err(e) => panic!("{e}"),
            Ok(i) => assert!(i.scene.curves.is_empty()),
        }
    }
}

#[test]
fn text_and_paper_space_are_left_out_with_one_warning() {
    let mut line = Entity::new(EntityType::Line(dxf::entities::Line::new(
        Point::new(0.0, 0.0, 0.0),
        Point::new(1.0, 0.0, 0.0),
    )));
    line.common.is_in_paper_space = true;
    let text = Entity::new(EntityType::Text(dxf::entities::Text::default()));
    let i = read(&drawing_of(vec![line, text.clone(), text]));
    assert!(i.scene.curves.is_empty());
    assert_eq!(i.warnings.len(), 1, "{:?}", i.warnings);
    assert!(
        i.warnings[0].contains("2 texts") && i.warnings[0].contains("1 in paper space"),
        "{:?}",
        i.warnings
    );
}

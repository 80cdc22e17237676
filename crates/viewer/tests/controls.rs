//! The panel's controls as data (`Present::controls` / `Present::apply_control`), driven
//! through the editor as the viewer does, without a window: each family's controls change
//! what they name, refuse bad values with a message (nothing clamped, nothing changed), and
//! every change is undoable.

use glam::DVec3;
use splinescope_core::geom::{
    Bezier, CubicInterpolation, Curve, ModifiedBezier, Nubmp, ParamCurve, Reading,
};
use splinescope_present::{Control, ControlKind, ControlValue, Present};
use splinescope_scene::format::Scene;
use splinescope_viewer::edit::Editor;

fn scene_of(curves: Vec<Curve>) -> Scene {
    Scene::of_curves(curves)
}

fn control(curve: &Curve, label: &str) -> Control {
    curve
        .controls()
        .into_iter()
        .find(|c| c.label == label)
        .unwrap_or_else(|| panic!("no control {label:?} among {:?}", curve.controls()))
}

fn cubic() -> Bezier {
    Bezier::new(vec![
        DVec3::ZERO,
        DVec3::new(1.0, 2.0, 0.0),
        DVec3::new(3.0, 2.0, 0.0),
        DVec3::new(4.0, 0.0, 0.0),
    ])
}

#[test]
fn elevating_a_bezier_keeps_the_curve_and_adds_a_point() {
    let mut e = Editor::new(scene_of(vec![Curve::Bezier(cubic())]), None);
    let before = e.scene().curves[0].curve.clone();
    let c = control(&before, "elevate degree");
    assert_eq!(c.kind, ControlKind::Action);
    e.apply_control(0, &c, ControlValue::Press);
    let after = e.scene().curves[0].curve.clone();
    assert_eq!(after.control_points().len(), 5);
    for i in 0..=20 {
        let t = f64::from(i) / 20.0;
        assert!((after.eval(t) - before.eval(t)).length() < 1e-14, "t = {t}");
    }
    assert_eq!(e.history_len(), (1, 0));
    e.undo();
    assert_eq!(e.scene().curves[0].curve, before);
}

#[test]
fn a_modified_curves_t_star_moves_the_peak_and_bad_values_are_refused() {
    let m = ModifiedBezier::try_new(cubic(), 0.5, DVec3::new(0.0, 1.0, 0.0)).unwrap();
    let mut e = Editor::new(scene_of(vec![Curve::ModifiedBezier(m)]), None);
    let t_star = control(&e.scene().curves[0].curve, "t*");
    // Two slider moves are one edit.
    e.apply_control(0, &t_star, ControlValue::Number(0.6));
    e.apply_control(0, &t_star, ControlValue::Number(0.7));
    e.finish();
    let Curve::ModifiedBezier(now) = &e.scene().curves[0].curve else {
        panic!("family changed")
    };
    assert_eq!(now.t_star(), 0.7);
    // R(t*) = Q(t*) + v: the peak follows t*.
    let q = cubic().eval(0.7);
    assert!((now.eval(0.7) - (q + DVec3::Y)).length() < 1e-14);
    assert_eq!(e.history_len(), (1, 0));
    // A typed value outside (0, 1) is refused, not clamped.
    let before = e.scene().curves[0].curve.clone();
    e.apply_control(0, &t_star, ControlValue::Number(1.5));
    assert_eq!(e.scene().curves[0].curve, before);
    let msg = e.message.clone().expect("a refusal message");
    assert!(msg.contains("1.5") && msg.contains("t*"), "{msg}");
    // The vector.
    let v = control(&before, "v");
    e.apply_control(0, &v, ControlValue::Vector(DVec3::new(0.5, -1.0, 0.0)));
    let Curve::ModifiedBezier(now) = &e.scene().curves[0].curve else {
        panic!()
    };
    assert_eq!(now.v(), DVec3::new(0.5, -1.0, 0.0));
    // A value of the wrong kind is an error naming the control.
    e.apply_control(0, &v, ControlValue::Toggle(true));
    assert!(e.message.clone().unwrap().contains("no control v"));
}

#[test]
fn interpolation_toggle_and_reading_are_single_edits() {
    let points = vec![
        DVec3::ZERO,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
    ];
    let c = CubicInterpolation::try_new(points.clone(), None, None).unwrap();
    let mut e = Editor::new(scene_of(vec![Curve::Interpolation(c)]), None);
    let toggle = control(&e.scene().curves[0].curve, "modified (paper 002)");
    assert!(toggle.kind.is_discrete());
    e.apply_control(0, &toggle, ControlValue::Toggle(true));
    let curve = e.scene().curves[0].curve.clone();
    let reading = control(&curve, "reading");
    assert_eq!(
        reading.kind,
        ControlKind::Choice {
            options: vec!["paper", "bump added"],
            selected: 0
        }
    );
    let v = control(&curve, "v");
    e.apply_control(0, &v, ControlValue::Vector(DVec3::new(0.0, 0.3, 0.0)));
    e.apply_control(0, &reading, ControlValue::Choice(1));
    let Curve::Interpolation(now) = &e.scene().curves[0].curve else {
        panic!()
    };
    let m = now.modification().expect("modified");
    assert_eq!(m.reading, Reading::BumpAdded);
    assert_eq!(m.v, DVec3::new(0.0, 0.3, 0.0));
    // Still interpolates its points (both readings do).
    for (p, t) in points.iter().zip([0.0, 1.0, 2.0]) {
        assert!((now.eval(t) - *p).length() < 1e-14);
    }
    // toggle, v, reading: three edits.
    assert_eq!(e.history_len(), (3, 0));
    // An option that does not exist.
    e.apply_control(0, &reading, ControlValue::Choice(2));
    assert!(e.message.is_some());
    assert_eq!(e.history_len(), (3, 0));
}

/// The standard order-4 NUBMP curve on paper 001's knot vector over a zigzag polygon.
fn zigzag_nubmp() -> Nubmp {
    let pts: Vec<DVec3> = (0..7)
        .map(|i| DVec3::new(f64::from(i), f64::from(i % 2), 0.0))
        .collect();
    let knots = vec![0., 0., 0., 0., 0.3, 0.5, 0.89, 1., 1., 1., 1.];
    Nubmp::try_new(pts, knots, 4).unwrap()
}

#[test]
fn nubmp_sliders_set_one_parameter_with_the_last_member_absorbing() {
    let n = zigzag_nubmp();
    let mut e = Editor::new(scene_of(vec![Curve::Nubmp(n.clone())]), None);
    let curve = e.scene().curves[0].curve.clone();
    // The first adjustable parameter of group 3.
    let g = &n.groups()[3];
    let (i, last) = (g.members[0], *g.members.last().unwrap());
    let slider = control(&curve, &format!("a^{i}_3"));
    let ControlKind::Number {
        value,
        range,
        bands: _,
    } = slider.kind
    else {
        panic!("{slider:?}")
    };
    assert_eq!(value, g.standard[0]);
    assert_eq!(range.0, 0.0);
    let pair = g.standard[0] + g.standard[g.members.len() - 1];
    assert!((range.1 - pair).abs() < 1e-15);
    e.apply_control(0, &slider, ControlValue::Number(0.1));
    let Curve::Nubmp(now) = &e.scene().curves[0].curve else {
        panic!()
    };
    let g2 = &now.groups()[3];
    assert_eq!(g2.value(i), Some(0.1));
    assert!((g2.value(last).unwrap() - (pair - 0.1)).abs() < 1e-15);
    // Now not standard: the reset button (always listed) restores the standard curve.
    let reset = control(&e.scene().curves[0].curve, "reset to the standard curve");
    e.apply_control(0, &reset, ControlValue::Press);
    assert_eq!(e.scene().curves[0].curve, Curve::Nubmp(n));
    e.finish();
    let history = e.history_len();
    let standard = e.scene().clone();
    // A value beyond the pair would make the absorber negative: refused.
    e.apply_control(0, &slider, ControlValue::Number(pair + 0.5));
    assert!(
        e.message.clone().unwrap().contains("negative"),
        "{:?}",
        e.message
    );
    // A negative one too; neither changes the curve (not even to −0) nor leaves an undo
    // step.
    e.apply_control(0, &slider, ControlValue::Number(-0.5));
    assert!(
        e.message.clone().unwrap().contains("≥ 0"),
        "{:?}",
        e.message
    );
    e.finish();
    assert_eq!(e.scene(), &standard);
    assert_eq!(e.history_len(), history);
}

#[test]
fn nubmp_sliders_carry_their_vd_band_and_groups_say_when_they_leave_it() {
    let n = zigzag_nubmp();
    let curve = Curve::Nubmp(n.clone());
    // Every parameter of an order 4 curve has a band; the standard curve is variation
    // diminishing: its values lie in their bands, inside the sliders' ranges.
    let mut narrow = None;
    for c in curve.controls() {
        let ControlKind::Number {
            value,
            range,
            bands,
        } = c.kind
        else {
            continue;
        };
        let [(lo, hi)] = bands[..] else {
            panic!("{}: one VD band on the standard curve: {bands:?}", c.label)
        };
        assert!(
            lo <= value && value <= hi,
            "{}: {lo} ≤ {value} ≤ {hi}",
            c.label
        );
        assert!(range.0 <= lo && hi <= range.1, "{bands:?} in {range:?}");
        assert!(!c.hint.unwrap().starts_with("outside"));
        if hi < range.1 - 1e-9 && narrow.is_none() {
            narrow = Some((c.label, range, hi));
        }
    }
    let (label, range, hi) = narrow.expect("a band that ends inside its slider");
    let notes = |c: &Curve| -> Vec<(String, bool)> {
        c.controls()
            .into_iter()
            .filter_map(|c| match c.kind {
                ControlKind::Note { warning } => Some((c.label, warning)),
                _ => None,
            })
            .collect()
    };
    let standard = notes(&curve);
    assert!(standard.iter().all(|(_, w)| !w), "{standard:?}");
    assert!(
        standard
            .iter()
            .any(|(l, _)| l.contains("variation diminishing")),
        "{standard:?}"
    );
    // At the band's upper end some Theorem 1 value reaches 1; beyond it one exceeds 1,
    // a group says it is outside the range and the slider's hint says so.
    let mut e = Editor::new(Scene::of_curves(vec![curve]), None);
    let at = |e: &mut Editor, v: f64| {
        let s = control(&e.scene().curves[0].curve, &label);
        e.apply_control(0, &s, ControlValue::Number(v));
        e.finish();
        let Curve::Nubmp(now) = e.scene().curves[0].curve.clone() else {
            panic!()
        };
        now
    };
    let edge = at(&mut e, hi);
    let worst = |m: &Nubmp| {
        (0..m.groups().len())
            .filter_map(|j| m.vd_value(j))
            .fold(f64::NEG_INFINITY, f64::max)
    };
    assert!((worst(&edge) - 1.0).abs() < 1e-6, "{}", worst(&edge));
    let beyond = at(&mut e, (hi + range.1) / 2.0);
    assert!(worst(&beyond) > 1.0);
    let c = Curve::Nubmp(beyond);
    assert!(
        notes(&c)
            .iter()
            .any(|(l, w)| *w && l.contains("outside the variation-diminishing range"))
    );
    let s = control(&c, &label);
    let hint = s.hint.clone().unwrap();
    assert!(hint.starts_with("outside its VD range"), "{hint}");
    // The band is the same whatever the current value (the slider keeps showing it).
    let ControlKind::Number { bands, .. } = s.kind else {
        panic!("{s:?}")
    };
    assert!(
        bands.iter().any(|&(_, h)| (h - hi).abs() < 1e-12),
        "{bands:?} {hi}"
    );
}

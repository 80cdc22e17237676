//! Intersections on the hard classes, in bulk: end points on interiors, joins, tangencies
//! of the first and second order, coincident pieces (also of self-crossing curves), and
//! near-parallel near-straight pairs, degrees 1–7, polynomial and rational — each case
//! checked against its construction (exact), and those of degree ≤ 3 against the exact
//! oracle (resultants, Sturm sequences) for everything the pair has in common.
//!
//! `SPLINESCOPE_CLASS_CASES` sets the cases per class (default 1,500; the bench script
//! `scripts/bench-intersections` runs 100,000); `SPLINESCOPE_ORACLE_EVERY` runs the oracle
//! on every k-th case of degree ≤ 3 (default 4); `SPLINESCOPE_LOW_CASES` the cases per
//! class of the low-degree pass, each against the oracle (default a third of the cases);
//! `SPLINESCOPE_CASE` checks one case of each stream (by its index) to study a failure.

mod support;

use glam::DVec3;
use num_traits::{Signed, ToPrimitive};
use splinescope_core::analysis::{CurveAnalysis, HitKind, Intersections};
use splinescope_core::geom::{Bezier, RationalBezier};

use support::classes::{Case, Class, Gen, Seg};
use support::exact::{self, Kind, Q};

fn analysis(seg: &Seg) -> CurveAnalysis {
    let pts: Vec<DVec3> = seg
        .points
        .iter()
        .map(|&(x, y)| DVec3::new(x, y, 0.0))
        .collect();
    match &seg.weights {
        None => CurveAnalysis::new(&Bezier::new(pts)),
        Some(w) => CurveAnalysis::new(&RationalBezier::try_new(pts, w.clone()).expect("weights")),
    }
}

fn f(x: &Q) -> f64 {
    x.to_f64().expect("finite")
}

fn kind(k: Kind) -> HitKind {
    match k {
        Kind::Crossing => HitKind::Crossing,
        Kind::Tangent => HitKind::Tangent,
    }
}

/// The slack every comparison allows beyond a hit's stated error: the rounding of the
/// parameter itself.
const ULP: f64 = 2.0 * f64::EPSILON;

/// Whether the float overlap matches `((s0, s1), (t0, t1))` to `1e−9`.
fn overlap_matches(o: &splinescope_core::analysis::Overlap, s: (f64, f64), t: (f64, f64)) -> bool {
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-9;
    let (fs, ft) = if (o.s.0 <= o.s.1) == (s.0 <= s.1) {
        (o.s, o.t)
    } else {
        ((o.s.1, o.s.0), (o.t.1, o.t.0))
    };
    near(fs.0, s.0) && near(fs.1, s.1) && near(ft.0, t.0) && near(ft.1, t.1)
}

/// What the construction guarantees, against what was found.
fn against_construction(case: &Case, found: &Intersections) -> Vec<String> {
    let mut problems = Vec::new();
    for (s, t, k) in &case.points {
        let (s, t) = (f(s), f(t));
        let hit = found
            .hits
            .iter()
            .find(|h| (h.s - s).abs() <= h.error_s + ULP && (h.t - t).abs() <= h.error_t + ULP);
        match hit {
            None => problems.push(format!(
                "missed the {:?} at (s, t) = ({s}, {t}); found {:?}",
                k, found
            )),
            Some(h) if h.kind != kind(*k) => problems.push(format!(
                "the point at ({s}, {t}) is a {k:?}, found as {:?}",
                h.kind
            )),
            Some(_) => {}
        }
    }
    for ((s0, s1), (t0, t1)) in &case.overlaps {
        let (s, t) = ((f(s0), f(s1)), (f(t0), f(t1)));
        if !found.overlaps.iter().any(|o| overlap_matches(o, s, t)) {
            problems.push(format!(
                "missed the overlap s {s:?} ↔ t {t:?}; found {found:?}"
            ));
        }
    }
    if !case.overlaps.is_empty() {
        for h in &found.hits {
            let inside = case.overlaps.iter().any(|((s0, s1), (t0, t1))| {
                let within = |x: f64, a: f64, b: f64| x > a.min(b) + 1e-9 && x < a.max(b) - 1e-9;
                within(h.s, f(s0), f(s1)) || within(h.t, f(t0), f(t1))
            });
            if inside {
                problems.push(format!("a point reported inside the overlap: {h:?}"));
            }
        }
    }
    problems
}

/// Everything the pair has in common, exactly, against what was found: every exact point
/// within the stated error of a found one of its kind, every found one holding an exact
/// one, the overlaps alike. A found tangency's error is its band — where the curves stay
/// within the resolution of each other — and an exact crossing inside the band of a
/// tangency that holds an exact tangent point is part of that contact (f64 cannot tell
/// the two apart); the count of those is returned.
fn against_oracle(case: &Case, found: &Intersections) -> (Vec<String>, usize) {
    let truth = exact::intersect(&case.a.exact(), &case.b.exact());
    let mut problems = Vec::new();
    let mut merged = 0;
    let holds = |p: &exact::Point, h: &splinescope_core::analysis::Hit| {
        p.s.holds(h.s, h.error_s + ULP) && p.t.holds(h.t, h.error_t + ULP)
    };
    let mut used = vec![false; found.hits.len()];
    for p in &truth.points {
        let same_kind = found
            .hits
            .iter()
            .position(|h| holds(p, h) && h.kind == kind(p.kind));
        if let Some(i) = same_kind {
            used[i] = true;
            continue;
        }
        // A crossing inside a tangency's band, the band holding an exact tangent point.
        let contact = found.hits.iter().position(|h| {
            h.kind == HitKind::Tangent
                && holds(p, h)
                && truth
                    .points
                    .iter()
                    .any(|q| q.kind == Kind::Tangent && holds(q, h))
        });
        if p.kind == Kind::Crossing && contact.is_some() {
            merged += 1;
            continue;
        }
        match found.hits.iter().find(|h| holds(p, h)) {
            None => problems.push(format!(
                "oracle: missed the {:?} at ({}, {}); found {found:?}",
                p.kind,
                p.s.to_f64(),
                p.t.to_f64()
            )),
            Some(h) => problems.push(format!(
                "oracle: the point at ({}, {}) is a {:?}, found as {h:?}",
                p.s.to_f64(),
                p.t.to_f64(),
                p.kind,
            )),
        }
    }
    for (h, u) in found.hits.iter().zip(&used) {
        if !u {
            problems.push(format!(
                "oracle: a point that is not there: {h:?}; truth {truth:?}"
            ));
        }
    }
    for o in &truth.overlaps {
        let s = (o.s.0.to_f64(), o.s.1.to_f64());
        let t = (o.t.0.to_f64(), o.t.1.to_f64());
        if !found.overlaps.iter().any(|x| overlap_matches(x, s, t)) {
            problems.push(format!(
                "oracle: missed the overlap s {s:?} ↔ t {t:?}; found {found:?}"
            ));
        }
    }
    if found.overlaps.len() != truth.overlaps.len() {
        problems.push(format!(
            "oracle: {} overlaps, found {}",
            truth.overlaps.len(),
            found.overlaps.len()
        ));
    }
    (problems, merged)
}

fn cases_per_class() -> usize {
    std::env::var("SPLINESCOPE_CLASS_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1500)
}

/// Cases per class of the low-degree pass (every one against the oracle):
/// `SPLINESCOPE_LOW_CASES`, else a third of [`cases_per_class`].
fn low_cases_per_class() -> usize {
    std::env::var("SPLINESCOPE_LOW_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(cases_per_class() / 3)
        .max(1)
}

fn oracle_every() -> usize {
    std::env::var("SPLINESCOPE_ORACLE_EVERY")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(4)
        .max(1)
}

/// Per class: cases, cases against the oracle, exact crossings inside a contact's band,
/// and the failures.
fn run_class(class: Class, seed: u64, low: bool) -> (usize, usize, usize, Vec<String>) {
    let mut g = Gen::new(seed);
    // The low-degree pass: every case of degree ≤ 3, every one against the oracle.
    let (n, every) = if low {
        g.max_degree = 3;
        (low_cases_per_class(), 1)
    } else {
        (cases_per_class(), oracle_every())
    };
    let mut failures = Vec::new();
    let mut oracle_runs = 0;
    let mut merged = 0;
    let (mut t_gen, mut t_float) = (0.0, 0.0);
    // `SPLINESCOPE_CASE` (an index) checks that case of the stream only.
    let only: Option<usize> = std::env::var("SPLINESCOPE_CASE")
        .ok()
        .and_then(|v| v.parse().ok());
    for i in 0..n {
        let clock = std::time::Instant::now();
        let case = g.case(class);
        if only.is_some_and(|k| k != i) {
            continue;
        }
        let (a, b) = (
            case.a.to_float().expect("representable"),
            case.b.to_float().expect("representable"),
        );
        t_gen += clock.elapsed().as_secs_f64();
        let clock = std::time::Instant::now();
        let found = analysis(&a).intersect(&analysis(&b)).expect("planar");
        t_float += clock.elapsed().as_secs_f64();
        let mut problems = against_construction(&case, &found);
        let (da, db) = case.degrees();
        if problems.is_empty() && da <= 3 && db <= 3 && i % every == 0 {
            oracle_runs += 1;
            match std::panic::catch_unwind(|| against_oracle(&case, &found)) {
                Ok((p, m)) => {
                    problems.extend(p);
                    merged += m;
                }
                Err(e) => problems.push(format!(
                    "the oracle failed: {}",
                    e.downcast_ref::<&str>()
                        .map(|s| s.to_string())
                        .or_else(|| e.downcast_ref::<String>().cloned())
                        .unwrap_or_default()
                )),
            }
        }
        if !problems.is_empty() {
            failures.push(format!(
                "{} case {i} (degrees {da}/{db}): {}\n  a = {a:?}\n  b = {b:?}",
                class.name(),
                problems.join("; ")
            ));
        }
    }
    eprintln!(
        "{}: generating {t_gen:.2} s, intersecting {t_float:.2} s",
        class.name()
    );
    (n, oracle_runs, merged, failures)
}

#[test]
fn constructed_classes_are_never_missed() {
    classes(false);
}

/// Degrees ≤ 3 only, every case against the exact oracle as well as its construction.
#[test]
fn low_degrees_agree_with_the_exact_oracle() {
    classes(true);
}

fn classes(low: bool) {
    let mut report = Vec::new();
    let mut all = Vec::new();
    // `SPLINESCOPE_CLASS` (part of a class's name) runs one class only.
    let only = std::env::var("SPLINESCOPE_CLASS").unwrap_or_default();
    let show: usize = std::env::var("SPLINESCOPE_SHOW")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(3);
    let classes: Vec<(usize, Class)> = Class::ALL
        .iter()
        .copied()
        .enumerate()
        .filter(|(_, c)| c.name().contains(only.as_str()))
        .collect();
    // The classes on every core (each class one seeded stream).
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let next = std::sync::atomic::AtomicUsize::new(0);
    let results = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| {
                loop {
                    let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(&(index, class)) = classes.get(k) else {
                        break;
                    };
                    let r = run_class(class, 1000 + index as u64 + if low { 500 } else { 0 }, low);
                    results.lock().expect("results").push((index, class, r));
                }
            });
        }
    });
    let mut results = results.into_inner().expect("results");
    results.sort_by_key(|r| r.0);
    for (_, class, (n, oracle, merged, failures)) in results {
        report.push(format!(
            "{:<40} {n:>7} cases, {oracle:>6} against the oracle ({merged} crossings inside a \
             contact's band), {:>5} failures",
            class.name(),
            failures.len()
        ));
        all.extend(failures.into_iter().take(show));
    }
    println!("{}", report.join("\n"));
    assert!(
        all.is_empty(),
        "{}\n\n{}",
        report.join("\n"),
        all.join("\n\n")
    );
}

/// The stated error of a crossing — `2 (e₁ + e₂ + r) / (|C′| sin θ)`, a few ε times the
/// crossing's condition number — holds on every near-parallel crossing and is not loose:
/// the worst actual error reaches a tenth of it.
#[test]
fn crossing_errors_hold_and_are_not_loose() {
    let mut g = Gen::new(77);
    let n = (cases_per_class() / 2).max(500);
    let (mut worst, mut measured) = (0.0_f64, 0);
    for i in 0..n {
        let case = g.case(Class::NearParallel);
        let (a, b) = (case.a.to_float().expect("a"), case.b.to_float().expect("b"));
        let found = analysis(&a).intersect(&analysis(&b)).expect("planar");
        for (s, t, _) in &case.points {
            let Some(h) = found.hits.iter().find(|h| {
                (h.s - f(s)).abs() <= h.error_s + ULP && (h.t - f(t)).abs() <= h.error_t + ULP
            }) else {
                panic!(
                    "case {i}: the crossing at ({}, {}) is missed: {found:?}",
                    f(s),
                    f(t)
                );
            };
            // The actual errors, exactly.
            let es = (exact::qf(h.s) - s).abs();
            let et = (exact::qf(h.t) - t).abs();
            for (e, stated, what) in [(es, h.error_s, "s"), (et, h.error_t, "t")] {
                let e = e.to_f64().expect("finite");
                assert!(
                    e <= stated,
                    "case {i}: {what} is off by {e:e}, beyond its stated error {stated:e}: {h:?}"
                );
                if stated > 0.0 {
                    worst = worst.max(e / stated);
                    measured += 1;
                }
            }
        }
    }
    println!("{measured} parameters: the worst actual error is {worst:.3} of the stated one");
    assert!(
        worst >= 0.1,
        "the stated errors are loose by more than 10× (worst actual/stated {worst:.3})"
    );
}

/// A line tangent to a quintic where its curvature is tiny (radius 1.5·10⁸ on a curve 3,000
/// across), crossing it again 4·10⁻⁴ further on, the curves within the resolution of each
/// other all the way between: the touching point is found (case 20,108 of the tangency
/// class at 100,000), and every other point found is a sign change of the exact distance
/// to the line.
#[test]
fn a_tangency_just_before_a_crossing_on_a_nearly_straight_stretch() {
    let a = Seg {
        points: vec![
            (-315.0, 2362.5),
            (-2205.0, -1496.25),
            (-1614.375, 0.0),
            (157.5, 2205.0),
            (-2362.5, 1890.0),
            (-157.5, -945.0),
        ],
        weights: None,
    };
    let b = Seg {
        points: vec![
            (92432.19390106201, 188566.78855133057),
            (-42725.55609893799, -82798.46144866943),
        ],
        weights: None,
    };
    let found = analysis(&a).intersect(&analysis(&b)).expect("planar");
    let (s, t) = (0.125, 9.0 / 13.0);
    assert!(
        found.hits.iter().any(|h| h.kind == HitKind::Tangent
            && (h.s - s).abs() <= h.error_s + ULP
            && (h.t - t).abs() <= h.error_t + ULP),
        "the tangent point at ({s}, {t}) is missed: {found:?}"
    );
    // The exact signed distance of a(s) from the line (times its length).
    let q = |x: f64| exact::qf(x);
    let side = |s: f64| -> Q {
        let s = q(s);
        let n = a.points.len() - 1;
        let (mut x, mut y) = (Q::from_integer(0.into()), Q::from_integer(0.into()));
        for (i, &(px, py)) in a.points.iter().enumerate() {
            let c = Q::from_integer(exact::binomial(n, i))
                * num_traits::pow(Q::from_integer(1.into()) - s.clone(), n - i)
                * num_traits::pow(s.clone(), i);
            x += c.clone() * q(px);
            y += c * q(py);
        }
        let ((x0, y0), (x1, y1)) = (b.points[0], b.points[1]);
        (q(x1) - q(x0)) * (y - q(y0)) - (q(y1) - q(y0)) * (x - q(x0))
    };
    for h in found.hits.iter().filter(|h| h.kind == HitKind::Crossing) {
        let w = h.error_s + 1e-9;
        assert!(
            side(h.s - w).signum() * side(h.s + w).signum() < Q::from_integer(0.into()),
            "no sign change of the distance around the crossing {h:?}"
        );
    }
}

//! Offset curves against kurbo's (`cargo bench --bench offset`): on the same 1,000 random
//! cubics and distances at the same tolerance, the segment counts (printed, with their
//! ratio; splinescope's each with a proven bound, kurbo's estimated) and the time.
#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec3;
use kurbo::offset::CubicOffset;
use kurbo::{CubicBez, Point, fit_to_bezpath, fit_to_bezpath_opt};
use splinescope_core::geom::{Bezier, Curve};
use splinescope_core::ops::{OffsetOptions, offset};
use splinescope_core::rng::Rng;

/// The same cases for both: a cubic in the unit square and a distance in ±[0.01, 0.2].
fn cases(count: usize) -> Vec<([DVec3; 4], f64)> {
    let mut rng = Rng::new(11);
    (0..count)
        .map(|_| {
            let p = [(); 4].map(|()| DVec3::new(rng.range(0.0, 1.0), rng.range(0.0, 1.0), 0.0));
            let d = rng.range(0.01, 0.2) * if rng.range(0.0, 1.0) < 0.5 { -1.0 } else { 1.0 };
            (p, d)
        })
        .collect()
}

fn kurbo_cubic(p: &[DVec3; 4]) -> CubicBez {
    let q = p.map(|v| Point::new(v.x, v.y));
    CubicBez::new(q[0], q[1], q[2], q[3])
}

fn ours(p: &[DVec3; 4], d: f64, tol: f64) -> usize {
    let curve = Curve::Bezier(Bezier::new(p.to_vec()));
    offset(&curve, d, tol, &OffsetOptions::default())
        .map(|o| o.paths.iter().map(|p| p.segments().len()).sum())
        .unwrap_or_else(|e| panic!("offset of {p:?} by {d}: {e}"))
}

fn theirs(p: &[DVec3; 4], d: f64, tol: f64, opt: bool) -> usize {
    // kurbo offsets to the right of travel for d > 0 in y-up terms; the count is the same
    // for either side asked of both, so the sign is passed as it is.
    let co = CubicOffset::new_regularized(kurbo_cubic(p), d, tol);
    let path = if opt {
        fit_to_bezpath_opt(&co, tol)
    } else {
        fit_to_bezpath(&co, tol)
    };
    path.segments().count()
}

fn bench(c: &mut Criterion) {
    let all = cases(1000);
    for tol in [1e-3, 1e-4] {
        let (mut a, mut b, mut bo) = (0usize, 0usize, 0usize);
        for (p, d) in &all {
            a += ours(p, *d, tol);
            b += theirs(p, -*d, tol, false);
            bo += theirs(p, -*d, tol, true);
        }
        println!(
            "offset segments at tolerance {tol}: splinescope {a}, kurbo fit_to_bezpath {b} (ratio {:.3}), kurbo fit_to_bezpath_opt {bo} (ratio {:.3})",
            a as f64 / b as f64,
            a as f64 / bo as f64
        );
    }
    let few = &all[..100];
    let mut g = c.benchmark_group("offset of 100 cubics, tolerance 1e-3");
    g.sample_size(10);
    g.bench_function("splinescope (proven bound)", |bch| {
        bch.iter(|| {
            few.iter()
                .map(|(p, d)| ours(p, black_box(*d), 1e-3))
                .sum::<usize>()
        });
    });
    g.bench_function("kurbo fit_to_bezpath", |bch| {
        bch.iter(|| {
            few.iter()
                .map(|(p, d)| theirs(p, black_box(-*d), 1e-3, false))
                .sum::<usize>()
        });
    });
    g.bench_function("kurbo fit_to_bezpath_opt", |bch| {
        bch.iter(|| {
            few.iter()
                .map(|(p, d)| theirs(p, black_box(-*d), 1e-3, true))
                .sum::<usize>()
        });
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

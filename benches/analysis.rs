//! Analysis benchmarks (criterion): `cargo bench --bench analysis`. Arc length against
//! kurbo's `arclen` at the same accuracy on the same cubics; the nearest point against
//! kurbo's `nearest`; curve–curve intersection per
//! pair (cubics and degree 7, crossing and tangent); all pairs among the stress
//! generator's 10,000 cubics and among 1,000 cubics crowded into one square.
#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::DVec3;
use kurbo::{CubicBez, ParamCurveArclen, ParamCurveExtrema, ParamCurveNearest, Point};
use splinescope_core::analysis::{CurveAnalysis, all_intersections, bezier_length};
use splinescope_core::geom::Bezier;
use splinescope_core::rng::Rng;
use splinescope_scene::format::generate::{StressOptions, random_bezier_scene};
use splinescope_scene::format::shape::{ShapeOptions, markers};

fn cubic(rng: &mut Rng) -> [DVec3; 4] {
    [(); 4].map(|()| DVec3::new(rng.range(0.0, 1.0), rng.range(0.0, 1.0), 0.0))
}

fn bench(c: &mut Criterion) {
    let mut rng = Rng::new(3);
    let cubics: Vec<[DVec3; 4]> = (0..64).map(|_| cubic(&mut rng)).collect();
    let ours: Vec<CurveAnalysis> = cubics
        .iter()
        .map(|p| CurveAnalysis::new(&Bezier::new(p.to_vec())))
        .collect();
    let curves: Vec<Bezier> = cubics.iter().map(|p| Bezier::new(p.to_vec())).collect();
    let theirs: Vec<CubicBez> = cubics
        .iter()
        .map(|p| {
            let q = p.map(|v| Point::new(v.x, v.y));
            CubicBez::new(q[0], q[1], q[2], q[3])
        })
        .collect();
    let mut g = c.benchmark_group("arc length of 64 cubics");
    for acc in [1e-6, 1e-9, 1e-12] {
        g.bench_with_input(BenchmarkId::new("splinescope", acc), &acc, |b, &acc| {
            b.iter(|| {
                ours.iter()
                    .map(|c| c.length(0.0, 1.0, black_box(acc)).map_or(0.0, |l| l.value))
                    .sum::<f64>()
            });
        });
        // The whole call from the control points, as kurbo's is: the analysis built
        // (segments, hodograph, its roots) and the length taken.
        g.bench_with_input(
            BenchmarkId::new("splinescope from points", acc),
            &acc,
            |b, &acc| {
                b.iter(|| {
                    cubics
                        .iter()
                        .map(|p| {
                            CurveAnalysis::new(&Bezier::new(black_box(p).to_vec()))
                                .length(0.0, 1.0, black_box(acc))
                                .map_or(0.0, |l| l.value)
                        })
                        .sum::<f64>()
                });
            },
        );
        // The same from the curves (their control points, as kurbo's `CubicBez`) without
        // the analysis (`bezier_length`).
        g.bench_with_input(
            BenchmarkId::new("splinescope bezier_length", acc),
            &acc,
            |b, &acc| {
                b.iter(|| {
                    curves
                        .iter()
                        .map(|c| {
                            bezier_length(black_box(c), 0.0, 1.0, black_box(acc))
                                .map_or(0.0, |l| l.value)
                        })
                        .sum::<f64>()
                });
            },
        );
        g.bench_with_input(BenchmarkId::new("kurbo", acc), &acc, |b, &acc| {
            b.iter(|| theirs.iter().map(|c| c.arclen(black_box(acc))).sum::<f64>());
        });
    }
    g.finish();

    // The tight box (end points and the derivative's roots) against kurbo's
    // `bounding_box`, on the same cubics, with the analysis built and from the points.
    let mut g = c.benchmark_group("tight box of 64 cubics");
    g.bench_function("splinescope", |b| {
        b.iter(|| {
            ours.iter()
                .map(|c| black_box(c).bounding_box().max.x)
                .sum::<f64>()
        });
    });
    g.bench_function("splinescope from points", |b| {
        b.iter(|| {
            cubics
                .iter()
                .map(|p| {
                    CurveAnalysis::new(&Bezier::new(black_box(p).to_vec()))
                        .bounding_box()
                        .max
                        .x
                })
                .sum::<f64>()
        });
    });
    g.bench_function("kurbo", |b| {
        b.iter(|| {
            theirs
                .iter()
                .map(|c| black_box(c).bounding_box().x1)
                .sum::<f64>()
        });
    });
    g.finish();

    // The nearest point of each of 64 cubics to 16 points (the global minimum at full
    // precision), against kurbo's `nearest` at an accuracy of 1e-12 on the same cubics.
    let mut g = c.benchmark_group("nearest point, 64 cubics x 16 points");
    let queries: Vec<DVec3> = (0..16)
        .map(|_| DVec3::new(rng.range(-0.5, 1.5), rng.range(-0.5, 1.5), 0.0))
        .collect();
    g.bench_function("splinescope", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for c in &ours {
                for q in &queries {
                    sum += c.nearest(black_box(*q)).map_or(0.0, |n| n.distance);
                }
            }
            sum
        });
    });
    g.bench_function("kurbo", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for c in &theirs {
                for q in &queries {
                    sum += black_box(c)
                        .nearest(Point::new(q.x, q.y), black_box(1e-12))
                        .distance_sq;
                }
            }
            sum
        });
    });
    g.finish();

    let mut g = c.benchmark_group("intersect one pair");
    let pair = |pa: &[(f64, f64)], pb: &[(f64, f64)]| {
        let mk = |p: &[(f64, f64)]| {
            CurveAnalysis::new(&Bezier::new(
                p.iter().map(|&(x, y)| DVec3::new(x, y, 0.0)).collect(),
            ))
        };
        (mk(pa), mk(pb))
    };
    let crossing3 = pair(
        &[(0.0, 0.0), (1.0, 3.0), (2.0, -2.0), (3.0, 1.0)],
        &[(0.0, 1.0), (1.5, -2.0), (2.0, 3.0), (3.0, -0.5)],
    );
    // A cubic touching the line y = −0.75 at its lowest point.
    let tangent3 = pair(
        &[(-1.0, 0.0), (-0.5, -1.0), (0.5, -1.0), (1.0, 0.0)],
        &[(-1.0, -0.75), (-0.3, -0.75), (0.3, -0.75), (1.0, -0.75)],
    );
    // Two degree-7 curves crossing three times (fixed points, found by a random draw).
    let crossing7 = pair(
        &[
            (0.131, 0.514),
            (0.25, 0.343),
            (0.817, 0.398),
            (0.784, 0.013),
            (0.999, 0.955),
            (0.679, 0.197),
            (0.657, 0.19),
            (0.373, 0.035),
        ],
        &[
            (0.07, 0.158),
            (0.182, 0.838),
            (0.244, 0.825),
            (0.006, 0.058),
            (0.061, 0.932),
            (0.817, 0.016),
            (0.932, 0.227),
            (0.265, 0.584),
        ],
    );
    for (name, (a, b)) in [
        ("cubics crossing 3 times", &crossing3),
        ("cubics tangent", &tangent3),
        ("degree 7 crossing 3 times", &crossing7),
    ] {
        g.bench_function(name, |bch| {
            bch.iter(|| black_box(a).intersect(black_box(b)))
        });
    }
    g.finish();

    let mut g = c.benchmark_group("all pairs");
    g.sample_size(10);
    let stress = random_bezier_scene(StressOptions {
        curves: 10_000,
        ..StressOptions::default()
    });
    let grid: Vec<CurveAnalysis> = stress
        .curves
        .iter()
        .map(|c| CurveAnalysis::new(&c.curve))
        .collect();
    g.bench_function("10,000 stress cubics (one per cell)", |b| {
        b.iter(|| all_intersections(black_box(&grid)).map(|v| v.pairs.len()))
    });
    let mut rng = Rng::new(9);
    let crowd: Vec<CurveAnalysis> = (0..1000)
        .map(|_| CurveAnalysis::new(&Bezier::new(cubic(&mut rng).to_vec())))
        .collect();
    g.bench_function("1,000 cubics in one square", |b| {
        b.iter(|| all_intersections(black_box(&crowd)).map(|v| v.pairs.len()))
    });
    g.finish();

    // What the viewer recomputes after an edit (off the frame thread): every marker of a
    // 1,000-curve stress scene, from the scene (analyses included).
    let mut g = c.benchmark_group("viewer markers");
    g.sample_size(10);
    let thousand = random_bezier_scene(StressOptions {
        curves: 1000,
        ..StressOptions::default()
    });
    let only_crossings = ShapeOptions {
        intersections: true,
        ..ShapeOptions::default()
    };
    let every = ShapeOptions {
        comb: None,
        comb_cap: Default::default(),
        inflections: true,
        curvature_extrema: true,
        intersections: true,
        joints: true,
    };
    g.bench_function("1,000 stress cubics: intersections", |b| {
        b.iter(|| markers(black_box(&thousand), &only_crossings).len())
    });
    g.bench_function("1,000 stress cubics: every marker", |b| {
        b.iter(|| markers(black_box(&thousand), &every).len())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

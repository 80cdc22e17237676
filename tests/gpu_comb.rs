//! The curvature comb on the GPU (the `comb_*` kernels of `shaders/comb.wgsl`) against
//! the exact `f64` curvature at the same parameters, on every backend: each hair starts at
//! the curve's point and ends at `P − s K` (K the curvature vector), cut to the cap and
//! marked where longer, within the `f32` bound stated below, for every family (rational ones included) in 2D and 3D; a comb for one
//! curve hides every other curve's hairs and envelope; and a planar comb changes side
//! exactly at the inflections the analysis finds.

mod common;

use glam::{DVec2, DVec3};
use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::analysis::comb::curvature_vector;
use splinescope_core::geom::{
    BSpline, Bezier, BezierSegment, Curve, Lower, ModifiedBezier, Nurbs, ParamCurve, RationalBezier,
};
use splinescope_core::ops::{Cap, Join};
use splinescope_encoding::StrokeShape;
use splinescope_gpu::adaptive::{FrameSettings, read_work};
use splinescope_gpu::capture::OFFSCREEN_FORMAT;
use splinescope_gpu::layout::{
    COMB_CAPPED, COMB_HAIRS, COMB_HIDDEN, GpuFrame, GpuVertex, WORK_HEADER,
};
use splinescope_gpu::pack::{PreparedScene, curve_tags};
use splinescope_gpu::renderer::{CombRequest, GpuScene, Renderer, camera_uniform};
use splinescope_gpu::tessellator::read_buffer;
use splinescope_gpu::twin::{comb_hair, comb_hairs_of, comb_point_and_curvature};
use splinescope_scene::format::{Scene, SceneCurve, Style, ViewSpec};

const VIEWPORT: DVec2 = DVec2::new(640.0, 480.0);

fn p(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, 0.0)
}

/// One curve of every family, none with a cusp (the hair is unbounded there).
fn families() -> Vec<Curve> {
    let base = Bezier::new(vec![p(-3.0, 0.0), p(-2.0, 2.0), p(0.0, 2.0), p(1.0, 0.5)]);
    vec![
        // An S: one inflection.
        Curve::Bezier(Bezier::new(vec![
            p(-4.0, -2.0),
            p(-2.0, 1.0),
            p(-1.0, -3.0),
            p(1.0, -1.0),
        ])),
        Curve::Bezier(Bezier::new(
            (0..=7)
                .map(|i| {
                    let t = f64::from(i) / 7.0;
                    p(2.0 * t - 1.0, (3.0 * t).sin() + 1.5)
                })
                .collect(),
        )),
        Curve::ModifiedBezier(ModifiedBezier::try_new(base, 0.4, p(0.0, 0.6)).expect("bump")),
        Curve::RationalBezier(RationalBezier::quarter_ellipse(p(2.0, -2.0), 2.0, 1.0)),
        // A rational cubic (the cubic comb kernel's weighted path).
        Curve::RationalBezier(
            RationalBezier::try_new(
                vec![p(-1.0, -4.0), p(0.0, -2.0), p(1.5, -4.5), p(3.0, -3.0)],
                vec![1.0, 3.0, 0.5, 2.0],
            )
            .expect("rational cubic"),
        ),
        Curve::Nurbs(Nurbs::circle(p(3.0, 2.0), 1.0).expect("circle")),
        Curve::BSpline(
            BSpline::try_new(
                vec![
                    p(-4.0, 2.5),
                    p(-3.0, 3.5),
                    p(-2.0, 2.0),
                    p(-1.0, 3.5),
                    p(0.0, 2.5),
                ],
                vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
                4,
            )
            .expect("spline"),
        ),
    ]
}

fn scene_of(curves: Vec<Curve>) -> Scene {
    let mut scene = splinescope_scene::format::gallery::gallery();
    scene.annotations.clear();
    scene.samples_per_segment = None;
    scene.curves = curves
        .into_iter()
        .map(|curve| SceneCurve {
            name: None,
            curve,
            style: Style::default_for(3),
        })
        .collect();
    scene
}

/// The comb computed on the GPU: per chunk, the placed counts and offsets and the hairs.
struct Combed {
    prepared: PreparedScene,
    /// Per chunk: (counts, offsets, hairs).
    chunks: Vec<(Vec<u32>, Vec<u32>, Vec<GpuVertex>)>,
    /// Per chunk: the frame uniform the comb was computed in.
    frames: Vec<GpuFrame>,
}

fn comb_on_gpu(backend: &common::Backend, scene: &Scene, request: &CombRequest) -> Combed {
    let ctx = &backend.ctx;
    let prepared = common::pack(ctx, scene);
    let renderer = Renderer::new(&ctx.device, &backend.pipelines, OFFSCREEN_FORMAT);
    let mut gpu: GpuScene = renderer.upload(ctx, &prepared);
    gpu.set_comb(ctx, &renderer, Some(request));
    assert!(gpu.has_comb());
    let camera = scene.camera(VIEWPORT);
    let settings = FrameSettings {
        camera: camera_uniform(&camera, VIEWPORT, 1.0),
        tolerance_px: 0.25,
        min_count: gpu.min_count(),
    };
    gpu.prepare_frame(ctx, &renderer, &settings);
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    gpu.encode_tessellation(&renderer, &mut encoder, None);
    ctx.queue.submit([encoder.finish()]);
    let mut chunks = Vec::new();
    let frames = gpu
        .chunks
        .iter()
        .map(|c| c.adaptive.frame_uniform(&settings))
        .collect();
    for (c, chunk) in gpu.chunks.iter().enumerate() {
        let s = prepared.chunks[c].segments.len();
        let work = read_work(&ctx.device, &ctx.queue, &chunk.adaptive).expect("work");
        let counts = work[WORK_HEADER..WORK_HEADER + s].to_vec();
        let offsets = (0..s).map(|i| work[WORK_HEADER + s + 2 * i]).collect();
        let comb = gpu.comb_buffers(c).expect("a comb per chunk");
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let hairs: Vec<GpuVertex> =
            read_buffer(&ctx.device, &ctx.queue, &mut encoder, &comb.hairs).expect("hairs");
        chunks.push((counts, offsets, hairs));
    }
    ctx.check_health().expect("healthy device");
    Combed {
        prepared,
        chunks,
        frames,
    }
}

/// The exact segment behind each adaptive segment of chunk `c`, with its curve's index.
fn exact_segments(
    scene: &Scene,
    prepared: &PreparedScene,
    c: usize,
) -> Vec<(u32, usize, BezierSegment)> {
    let mut out = Vec::new();
    for (curve, places) in prepared.placements.iter().enumerate() {
        let lowered = scene.curves[curve].curve.lower();
        for pl in places.iter().filter(|pl| pl.chunk == c) {
            out.push((pl.first_point, curve, lowered[pl.segment].clone()));
        }
    }
    out
}

/// The exact point and curvature vector of a segment at its own parameter `u`.
fn exact(seg: &BezierSegment, u: f64) -> (DVec3, DVec3) {
    let (point, d1, d2) = match seg.rational() {
        Some(r) => (r.eval(u), r.eval_deriv(u), r.eval_second_deriv(u)),
        None => (
            seg.bezier.eval(u),
            seg.bezier.eval_deriv(u),
            seg.bezier.eval_second_deriv(u),
        ),
    };
    (
        point,
        curvature_vector(d1, d2).expect("no cusp in these curves"),
    )
}

fn v3(v: &GpuVertex) -> DVec3 {
    DVec3::from_array(v.position.map(f64::from))
}

/// Every hair of every drawn segment: `(curve, u, point, tip)` with the exact values.
fn each_hair(
    scene: &Scene,
    combed: &Combed,
    mut f: impl FnMut(usize, f64, (&GpuVertex, &GpuVertex), (DVec3, DVec3)),
) -> usize {
    let mut checked = 0;
    for (c, (counts, offsets, hairs)) in combed.chunks.iter().enumerate() {
        let exacts = exact_segments(scene, &combed.prepared, c);
        for (s, seg) in combed.prepared.chunks[c].segments.iter().enumerate() {
            let (_, curve, exact_seg) = exacts
                .iter()
                .find(|(first, _, _)| *first == seg.first_point)
                .expect("every segment has its exact twin");
            let count = counts[s];
            // The hairs: as many as the twin's rule gives (one every few pixels of the
            // projected polygon), in the segment's sample slots (the count kernel gives it
            // at least that many while a comb is drawn); the rest draw nothing.
            let want = comb_hairs_of(&combed.frames[c], &combed.prepared.chunks[c].points, seg);
            let n = count.min(want);
            assert_eq!(n, want, "curve {curve}: {count} slots for {want} hairs");
            assert!((2..=COMB_HAIRS).contains(&n));
            for j in n..count {
                let k = (offsets[s] + j) as usize;
                assert_ne!(
                    hairs[2 * k].id,
                    hairs[2 * k + 1].id,
                    "slot {j} of {count} drawn"
                );
            }
            for j in 0..n {
                // The kernel's parameter: j / (n − 1) in f32.
                let u = f64::from(j as f32 / (n - 1) as f32);
                let k = (offsets[s] + j) as usize;
                f(
                    *curve,
                    u,
                    (&hairs[2 * k], &hairs[2 * k + 1]),
                    exact(exact_seg, u),
                );
                checked += 1;
            }
        }
    }
    checked
}

#[test]
fn gpu_hairs_match_the_exact_curvature_on_every_family() {
    common::on_each_gpu(
        "gpu_hairs_match_the_exact_curvature_on_every_family",
        |backend| {
            let mut curves = families();
            // A 3D cubic: the hair along the principal normal, |κ| long.
            curves.push(Curve::Bezier(Bezier::new(vec![
                DVec3::new(0.0, -3.0, 0.0),
                DVec3::new(1.0, -2.0, 1.0),
                DVec3::new(2.0, -3.0, 2.0),
                DVec3::new(3.0, -2.0, 0.5),
            ])));
            let scene = scene_of(curves);
            // Hairs longer than the cap are cut to it and their tips marked.
            let (scale, cap) = (0.3_f64, 0.25_f64);
            let combed = comb_on_gpu(
                backend,
                &scene,
                &CombRequest {
                    scale: scale as f32,
                    cap: cap as f32,
                    only: None,
                },
            );
            // The f32 bound: the kernel's Horner sums carry a relative error of a few n ε₃₂
            // in each derivative, and K divides by |P′|² — for these curves (speed bounded
            // away from 0, coordinates within 5) a point within 2e-5 of the curve's extent
            // and a hair within 2e-4 of its own length plus 2e-5 of the extent.
            let extent = 8.0;
            let mut longest = 0.0_f64;
            let (mut capped, mut uncapped) = (0, 0);
            let checked = each_hair(&scene, &combed, |curve, u, (gp, gt), (point, k)| {
                let mut hair = -scale * k;
                longest = longest.max(hair.length());
                let marked = gt.id == gp.id | COMB_CAPPED;
                assert!(marked || gt.id == gp.id, "curve {curve}: hair tags differ");
                // Within f32 noise of the cap either is right.
                if hair.length() > cap * (1.0 + 1e-4) {
                    assert!(
                        marked,
                        "curve {curve} at u = {u}: {hair} past the cap, not marked"
                    );
                    hair *= cap / hair.length();
                    capped += 1;
                } else if hair.length() < cap * (1.0 - 1e-4) {
                    assert!(!marked, "curve {curve} at u = {u}: {hair} marked as capped");
                    uncapped += 1;
                } else if marked {
                    hair *= cap / hair.length();
                }
                let got_point = v3(gp);
                let got_hair = v3(gt) - got_point;
                assert!(
                    (got_point - point).length() <= 2e-5 * extent,
                    "curve {curve} at u = {u}: point {got_point} vs {point}"
                );
                assert!(
                    (got_hair - hair).length() <= 2e-4 * hair.length() + 2e-5 * extent,
                    "curve {curve} at u = {u}: hair {got_hair} vs {hair}"
                );
            });
            assert!(checked > 100, "{checked} hairs checked");
            assert!(longest > 2.0 * cap, "the combs have length: {longest}");
            assert!(
                capped > 10 && uncapped > 100,
                "{capped} capped, {uncapped} not"
            );
        },
    );
}

/// The comb kernels against their CPU twin (`twin::comb_point_and_curvature`, then
/// `twin::comb_hair`): the same operations in `f32` on the same packed control points at
/// the kernel's parameters, so every hair's point and tip agree within a few units in the
/// last place (the GPU may fuse a multiply and an add), and each hair is capped exactly
/// when the twin's is (but within that noise of the cap) — on every family, through the
/// cubic kernel (polynomial and rational cubics), the narrow one (quartics, rational
/// quadratics) and the wide one (degree 7 and the bump's pieces), on every backend.
#[test]
fn gpu_hairs_are_their_cpu_twins() {
    common::on_each_gpu("gpu_hairs_are_their_cpu_twins", |backend| {
        let mut curves = families();
        // A quartic: the narrow kernel's polynomial path.
        curves.push(Curve::Bezier(Bezier::new(vec![
            p(-4.0, 3.0),
            p(-3.0, 5.0),
            p(-2.0, 2.5),
            p(-1.0, 4.5),
            p(0.0, 3.5),
        ])));
        let scene = scene_of(curves);
        let (scale, cap) = (0.3_f32, 0.25_f32);
        let combed = comb_on_gpu(
            backend,
            &scene,
            &CombRequest {
                scale,
                cap,
                only: None,
            },
        );
        let mut checked = [0usize; 3];
        let mut capped = 0;
        for (c, (counts, offsets, hairs)) in combed.chunks.iter().enumerate() {
            let points = &combed.prepared.chunks[c].points;
            for (s, seg) in combed.prepared.chunks[c].segments.iter().enumerate() {
                let n = counts[s].min(comb_hairs_of(&combed.frames[c], points, seg));
                for j in 0..n {
                    let u = j as f32 / (n - 1) as f32;
                    let (point, k) =
                        comb_point_and_curvature(points, seg.first_point, seg.degree, u);
                    let (tip, twin_capped) = comb_hair(point, k, scale, cap);
                    let slot = (offsets[s] + j) as usize;
                    let (gp, gt) = (&hairs[2 * slot], &hairs[2 * slot + 1]);
                    let got_point = glam::Vec3::from(gp.position);
                    let got_tip = glam::Vec3::from(gt.position);
                    let size = point.length() + (tip - point).length() + 1.0;
                    let what = format!(
                        "{}: segment {s} (degree {}, rational {}) at u = {u}",
                        backend.name, seg.degree, seg.rational
                    );
                    assert!(
                        (got_point - point).length() <= 4e-6 * size,
                        "{what}: point {got_point} vs the twin's {point}"
                    );
                    assert!(
                        (got_tip - tip).length() <= 4e-6 * size,
                        "{what}: tip {got_tip} vs the twin's {tip}"
                    );
                    let length = (scale * k).length();
                    if (length - cap).abs() > 1e-5 * cap {
                        let marked = gt.id & COMB_CAPPED != 0;
                        assert_eq!(marked, twin_capped, "{what}: capped or not as the twin");
                    }
                    capped += usize::from(twin_capped);
                    let class = match seg.degree {
                        3 => 0,
                        2 | 4 if seg.degree == 4 || seg.rational != 0 => 1,
                        _ => 2,
                    };
                    checked[class] += 1;
                }
            }
        }
        assert!(
            checked.iter().all(|&c| c > 20) && capped > 10,
            "hairs checked per kernel (cubic, narrow, wide): {checked:?}; capped {capped}"
        );
    });
}

#[test]
fn a_comb_for_one_curve_hides_the_others() {
    common::on_each_gpu("a_comb_for_one_curve_hides_the_others", |backend| {
        let scene = scene_of(families());
        let ctx = &backend.ctx;
        let prepared = common::pack(ctx, &scene);
        let only = 3;
        let request = CombRequest {
            scale: 0.5,
            cap: f32::MAX,
            only: Some(curve_tags(&prepared, only)),
        };
        assert!(!request.only.as_ref().expect("tags").is_empty());
        let combed = comb_on_gpu(backend, &scene, &request);
        let (mut shown, mut hidden) = (0, 0);
        each_hair(&scene, &combed, |curve, _, (gp, gt), _| {
            if curve == only {
                assert_eq!(gp.id, gt.id, "the chosen curve's hairs are drawn");
                shown += 1;
            } else {
                assert_eq!(
                    gt.id,
                    gp.id | COMB_HIDDEN,
                    "curve {curve}'s hairs are hidden"
                );
                hidden += 1;
            }
        });
        assert!(shown > 0 && hidden > 0, "{shown} shown, {hidden} hidden");
    });
}

#[test]
fn a_planar_comb_changes_side_exactly_at_the_inflections() {
    common::on_each_gpu(
        "a_planar_comb_changes_side_exactly_at_the_inflections",
        |backend| {
            let curves = families();
            let scene = scene_of(curves.clone());
            let combed = comb_on_gpu(
                backend,
                &scene,
                &CombRequest {
                    scale: 0.5,
                    cap: f32::MAX,
                    only: None,
                },
            );
            // Per curve: the analysis's inflections (curve parameters), and the side of each
            // GPU hair, (P′ × hair)_z, at its curve parameter.
            let inflections: Vec<Vec<f64>> = curves
                .iter()
                .map(|c| CurveAnalysis::new(c).inflections().expect("planar"))
                .collect();
            assert_eq!(inflections[0].len(), 1, "the S has one inflection");
            let mut sides: Vec<Vec<(f64, f64)>> = vec![Vec::new(); curves.len()];
            for (c, (counts, offsets, hairs)) in combed.chunks.iter().enumerate() {
                let exacts = exact_segments(&scene, &combed.prepared, c);
                for (s, seg) in combed.prepared.chunks[c].segments.iter().enumerate() {
                    let (_, curve, exact_seg) = exacts
                        .iter()
                        .find(|(first, _, _)| *first == seg.first_point)
                        .expect("twin");
                    let n = counts[s].min(comb_hairs_of(
                        &combed.frames[c],
                        &combed.prepared.chunks[c].points,
                        seg,
                    ));
                    for j in 0..n {
                        let u = f64::from(j as f32 / (n - 1) as f32);
                        let t = exact_seg.t0 + u * (exact_seg.t1 - exact_seg.t0);
                        let k = (offsets[s] + j) as usize;
                        let hair = v3(&hairs[2 * k + 1]) - v3(&hairs[2 * k]);
                        let d1 = curves[*curve].eval_deriv(t);
                        sides[*curve].push((t, d1.x * hair.y - d1.y * hair.x));
                    }
                }
            }
            for (curve, (found, side)) in inflections.iter().zip(&mut sides).enumerate() {
                side.sort_by(|a, b| a.0.total_cmp(&b.0));
                // Away from an inflection (where κ is within f32 noise of 0) the side is the
                // sign of −κ; it changes between two hairs exactly when an inflection lies
                // between them.
                let firm: Vec<(f64, f64)> = side
                    .iter()
                    .copied()
                    .filter(|(t, _)| found.iter().all(|i| (t - i).abs() > 1e-3))
                    .collect();
                for w in firm.windows(2) {
                    let (ta, sa) = w[0];
                    let (tb, sb) = w[1];
                    let between = found.iter().filter(|&&i| ta < i && i < tb).count();
                    let changed = (sa > 0.0) != (sb > 0.0);
                    assert_eq!(
                        changed,
                        between % 2 == 1,
                        "curve {curve}: side {sa} at {ta}, {sb} at {tb}, inflections {found:?}"
                    );
                }
            }
        },
    );
}

fn read_back<T: bytemuck::Pod>(
    ctx: &splinescope_gpu::context::GpuContext,
    buffer: &wgpu::Buffer,
) -> Vec<T> {
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    read_buffer(&ctx.device, &ctx.queue, &mut encoder, buffer).expect("read back")
}

/// The layer (`raster_comb` and `raster_curves` in `shaders/layer.wgsl`) against its CPU
/// twin run on the samples, hairs and envelope the GPU wrote, on every backend: the same
/// pixels lit with the same colours (a coverage within one step of 63), but for pixels
/// where the `f32` position of a line rounds to the neighbouring row or column (at most
/// 1 % of them, each with the same colour one pixel away) — for
/// every curve's comb, and for one curve's (the others' hidden hairs and envelope draw
/// nothing: a small part of the pixels).
#[test]
fn the_layer_holds_what_its_twin_rasterizes() {
    common::on_each_gpu("the_layer_holds_what_its_twin_rasterizes", |backend| {
        let ctx = &backend.ctx;
        let scene = scene_of(families());
        let prepared = common::pack(ctx, &scene);
        let renderer = Renderer::new(&ctx.device, &backend.pipelines, OFFSCREEN_FORMAT);
        // Every curve's comb, then curve 3's alone (the others' hairs hidden).
        let mut lit_all = 0;
        for only in [None, Some(curve_tags(&prepared, 3))] {
            let one = only.is_some();
            let lit = layer_against_twin(backend, &scene, &prepared, &renderer, only);
            if one {
                // The curves are drawn either way; the other combs are not.
                assert!(
                    lit > 3000 && lit + 2000 < lit_all,
                    "{}: with one curve's comb {lit} pixels lit, with every curve's {lit_all}",
                    backend.name
                );
            } else {
                assert!(lit > 3000, "{}: {lit} pixels lit", backend.name);
                lit_all = lit;
            }
        }
        // The same curves seen in perspective, one of them leaving the plane: clip-space
        // `w` is not 1, so the pieces' ends are clipped and divided on both sides.
        let mut curves = families();
        curves.push(Curve::Bezier(Bezier::new(vec![
            DVec3::new(-3.0, -1.0, 0.0),
            DVec3::new(-1.0, 1.0, 2.0),
            DVec3::new(1.0, -1.0, -1.5),
            DVec3::new(3.0, 1.0, 0.5),
        ])));
        let mut scene = scene_of(curves);
        scene.view = ViewSpec::ThreeD {
            target: DVec3::ZERO,
            distance: 12.0,
            yaw_deg: 35.0,
            pitch_deg: 25.0,
            fov_deg: 45.0,
        };
        let prepared = common::pack(ctx, &scene);
        let lit = layer_against_twin(backend, &scene, &prepared, &renderer, None);
        assert!(
            lit > 2000,
            "{} in perspective: {lit} pixels lit",
            backend.name
        );
        // Every other curve's width in scene units (it zooms: its pixels follow the
        // projection, in perspective varying with the depth), in 3D and in 2D.
        for view in [scene.view, ViewSpec::Auto] {
            let mut thin = scene.clone();
            thin.view = view;
            let prepared = common::pack(ctx, &thin);
            let lit = layer_against_twin(backend, &thin, &prepared, &renderer, None);
            let mut wide = thin.clone();
            for (i, c) in wide.curves.iter_mut().enumerate() {
                if i % 2 == 0 {
                    c.style.width = 0.12;
                    c.style.width_in_scene = true;
                }
            }
            let prepared = common::pack(ctx, &wide);
            let lit_wide = layer_against_twin(backend, &wide, &prepared, &renderer, None);
            assert!(
                lit_wide > lit,
                "{} with widths in scene units ({view:?}): {lit_wide} pixels lit, {lit} at 2.5 px",
                backend.name
            );
        }
        // Caps and joins other than round, on wide strokes: every curve with one of the
        // cap and join pairs, and closed paths with corners (a triangle, a rectangle)
        // whose seam is a join; in 2D and in perspective.
        let mut shaped = scene_of(families());
        shaped.curves.push(SceneCurve {
            name: None,
            curve: Curve::Path(polygon(&[p(-4.5, -4.5), p(-1.5, -4.0), p(-3.5, -2.2)])),
            style: Style::default_for(1),
        });
        shaped.curves.push(SceneCurve {
            name: None,
            curve: Curve::Path(polygon(&[
                p(1.0, 3.0),
                p(4.0, 3.0),
                p(4.0, 4.5),
                p(1.0, 4.5),
            ])),
            style: Style::default_for(2),
        });
        let pairs = [
            (Cap::Butt, Join::Miter),
            (Cap::Square, Join::Bevel),
            (Cap::Butt, Join::Bevel),
            (Cap::Square, Join::Miter),
            (Cap::Round, Join::Miter),
            (Cap::Butt, Join::Round),
        ];
        for (i, c) in shaped.curves.iter_mut().enumerate() {
            let (cap, join) = pairs[i % pairs.len()];
            c.style.stroke = StrokeShape {
                cap,
                join,
                miter_limit: if i % 3 == 0 { 1.5 } else { 4.0 },
            };
            c.style.width = 0.35;
            c.style.width_in_scene = true;
        }
        for view in [ViewSpec::Auto, scene.view] {
            shaped.view = view;
            let prepared = common::pack(ctx, &shaped);
            let lit = layer_against_twin(backend, &shaped, &prepared, &renderer, None);
            assert!(
                lit > 10_000,
                "{} with caps and joins ({view:?}): {lit} pixels lit",
                backend.name
            );
        }
    });
}

/// A closed path of straight segments through `corners`.
fn polygon(corners: &[DVec3]) -> splinescope_core::geom::Path {
    let n = corners.len();
    splinescope_core::geom::Path::try_new(
        (0..n)
            .map(|i| {
                splinescope_core::geom::PathSegment::polynomial(vec![
                    corners[i],
                    corners[(i + 1) % n],
                ])
            })
            .collect(),
        true,
    )
    .expect("a closed polygon")
}

/// Runs the comb pass and its layer for `only` and compares the layer with the twin's
/// (see above); the pixels lit.
fn layer_against_twin(
    backend: &common::Backend,
    scene: &Scene,
    prepared: &PreparedScene,
    renderer: &Renderer,
    only: Option<Vec<(usize, u32)>>,
) -> usize {
    use splinescope_gpu::layer_twin::{CombLines, layer_size, raster_comb, raster_curves};
    use splinescope_gpu::renderer::comb_styles;
    let ctx = &backend.ctx;
    let mut gpu: GpuScene = renderer.upload(ctx, prepared);
    gpu.set_comb(
        ctx,
        renderer,
        Some(&CombRequest {
            scale: 0.4,
            cap: 0.3,
            only,
        }),
    );
    let camera = camera_uniform(&scene.camera(VIEWPORT), VIEWPORT, 1.0);
    renderer.set_camera(&ctx.queue, &camera);
    let settings = FrameSettings {
        camera,
        tolerance_px: 0.25,
        min_count: gpu.min_count(),
    };
    gpu.prepare_frame(ctx, renderer, &settings);
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    gpu.encode_tessellation(renderer, &mut encoder, None);
    ctx.queue.submit([encoder.finish()]);
    let (layer_buffer, size) = gpu.layer().expect("a layer");
    assert_eq!(size, layer_size(&camera));
    assert_eq!(size, [640, 480]);
    let got: Vec<u32> = read_back(ctx, layer_buffer);
    let mut want = vec![0u32; got.len()];
    for (c, chunk) in prepared.chunks.iter().enumerate() {
        let comb = gpu.comb_buffers(c).expect("a comb per chunk");
        let hairs: Vec<GpuVertex> = read_back(ctx, &comb.hairs);
        let envelope: Vec<GpuVertex> = read_back(ctx, &comb.envelope);
        let args: Vec<u32> = read_back(ctx, &comb.args);
        // The styles as uploaded: each with its place in the scene, which pixels name.
        let styles = gpu.chunks[c].styles();
        assert_eq!(styles.len(), chunk.styles.len());
        let (hair_styles, envelope_styles) = comb_styles(styles);
        let lines = CombLines {
            hairs: &hairs,
            envelope: &envelope,
            hair_styles: &hair_styles,
            envelope_styles: &envelope_styles,
            hair_count: args[0] / 2,
            piece_count: args[4] / 2,
        };
        raster_comb(&camera, &lines, &mut want);
        // The curves over the comb: the chunk's samples and pieces as the GPU left them.
        let samples: Vec<GpuVertex> = read_back(ctx, &gpu.chunks[c].adaptive.samples);
        let work = read_work(&ctx.device, &ctx.queue, &gpu.chunks[c].adaptive).expect("work");
        raster_curves(&camera, &samples, styles, work[1], &mut want);
    }
    ctx.check_health().expect("healthy device");
    let w = size[0] as usize;
    // The same kind and curve, the alpha within one step and the core bit free (a
    // coverage computed in f32 on either side of a rounding boundary).
    let same = |a: u32, b: u32| {
        let rest = !(0x3f | splinescope_gpu::layer_twin::CORE_BIT);
        a == b || ((a & rest) == (b & rest) && (a & 0x3f).abs_diff(b & 0x3f) <= 1)
    };
    let near = |layer: &[u32], i: usize, key: u32| {
        let (x, y) = ((i % w) as i64, (i / w) as i64);
        (-1..=1).any(|dy| {
            (-1..=1).any(|dx| {
                let (nx, ny) = (x + dx, y + dy);
                (0..w as i64).contains(&nx)
                    && ny >= 0
                    && layer
                        .get(ny as usize * w + nx as usize)
                        .is_some_and(|&k| same(k, key))
            })
        })
    };
    let lit = want.iter().filter(|&&k| k != 0).count();
    let mut moved = 0;
    for i in 0..got.len() {
        if same(got[i], want[i]) {
            continue;
        }
        moved += 1;
        for (a, b, which) in [(&got, &want, "GPU"), (&want, &got, "twin")] {
            assert!(
                a[i] == 0 || near(b, i, a[i]),
                "{}: pixel ({}, {}) {:#x} of the {which} has no twin within a pixel",
                backend.name,
                i % w,
                i / w,
                a[i]
            );
        }
    }
    assert!(
        moved * 100 <= lit.max(1),
        "{}: {moved} of {lit} pixels differ",
        backend.name
    );
    eprintln!("{}: {lit} pixels lit, {moved} moved by one", backend.name);
    lit
}

/// The layer draws the pixels the GPU's own rasterizer draws. Combs: a render with the
/// comb through the layer and one with the comb as line lists (the path taken where a
/// layer does not fit; the curves then as quads) change the same pixels of their render
/// without a comb, where that render is background, but for pixels one away (the two
/// place a line's pixels by different rules at a line's ends) — at most a quarter of them
/// (15 % on llvmpipe), each next to one the other changed. Colours are not compared: where
/// translucent lines cross, line lists blend twice and the layer once. Curves: the render
/// without a comb through the layer and as quads agree within 24 of 255 per channel on
/// all but 5 % of the pixels the curves cover (their anti-aliasing is the same formula;
/// they differ at the joints, where pieces overlap: the quads blend the two fringes, the
/// layer keeps the larger coverage — 3.9 % on llvmpipe). The renders are written under `target/test-output/gpu_comb`.
#[test]
fn the_layer_draws_what_line_lists_and_quads_draw() {
    use splinescope_gpu::capture::render_uploaded;
    common::on_each_gpu(
        "the_layer_draws_what_line_lists_and_quads_draw",
        |backend| {
            let ctx = &backend.ctx;
            let scene = scene_of(families());
            let prepared = common::pack(ctx, &scene);
            let renderer = Renderer::new(&ctx.device, &backend.pipelines, OFFSCREEN_FORMAT);
            let (w, h) = (VIEWPORT.x as u32, VIEWPORT.y as u32);
            let camera = scene.camera(VIEWPORT);
            let render = |comb: bool, layer: bool| {
                let mut gpu: GpuScene = renderer.upload(ctx, &prepared);
                if comb {
                    gpu.set_comb(
                        ctx,
                        &renderer,
                        Some(&CombRequest {
                            scale: 0.4,
                            cap: 0.3,
                            only: None,
                        }),
                    );
                }
                gpu.set_layer(layer);
                let image = render_uploaded(ctx, &renderer, &mut gpu, &camera, (w, h), 0.25)
                    .expect("render");
                assert_eq!(
                    gpu.layer().is_some(),
                    layer,
                    "{}: a layer exactly when allowed",
                    backend.name
                );
                image
            };
            let (plain, layer) = (render(false, true), render(true, true));
            let (quads, lines) = (render(false, false), render(true, false));
            let dir = common::out_dir("gpu_comb");
            for (name, img) in [
                ("plain", &plain),
                ("layer", &layer),
                ("quads", &quads),
                ("lines", &lines),
            ] {
                img.write_png(&dir.join(format!("{}-{name}.png", backend.name)))
                    .expect("write");
            }
            let background = &plain.data[..4];
            let covered = plain.data.chunks(4).filter(|p| *p != background).count();
            let unlike = plain
                .data
                .chunks(4)
                .zip(quads.data.chunks(4))
                .filter(|(a, b)| a.iter().zip(*b).any(|(x, y)| x.abs_diff(*y) > 24))
                .count();
            assert!(
                covered > 3000,
                "{}: curves cover {covered} pixels",
                backend.name
            );
            assert!(
                unlike * 20 <= covered,
                "{}: the layer's curves and the quads differ on {unlike} of {covered} pixels",
                backend.name
            );
            let changed = |img: &splinescope_image::RgbaImage,
                           base: &splinescope_image::RgbaImage| {
                img.data
                    .chunks(4)
                    .zip(base.data.chunks(4))
                    .map(|(a, b)| a != b)
                    .collect::<Vec<bool>>()
            };
            let (by_layer, by_lines) = (changed(&layer, &plain), changed(&lines, &quads));
            let wu = w as usize;
            let near = |mask: &[bool], i: usize| {
                let (x, y) = ((i % wu) as i64, (i / wu) as i64);
                (-1..=1).any(|dy| {
                    (-1..=1).any(|dx| {
                        let (nx, ny) = (x + dx, y + dy);
                        (0..wu as i64).contains(&nx)
                            && ny >= 0
                            && mask.get(ny as usize * wu + nx as usize) == Some(&true)
                    })
                })
            };
            // Only where the render without a comb is background within a pixel: under a
            // curve's edge one drawing's pixel shows and the other's, one further in, not.
            let drawn: Vec<bool> = plain
                .data
                .chunks(4)
                .zip(quads.data.chunks(4))
                .map(|(p, q)| p != background || q != background)
                .collect();
            let open = |i: usize| !drawn[i] && !near(&drawn, i);
            let lit = (0..by_lines.len())
                .filter(|&i| by_lines[i] && open(i))
                .count();
            let mut apart = 0;
            for i in 0..by_layer.len() {
                if by_layer[i] == by_lines[i] || !open(i) {
                    continue;
                }
                apart += 1;
                let (mine, other, which) = if by_layer[i] {
                    (&by_layer, &by_lines, "the layer")
                } else {
                    (&by_lines, &by_layer, "the line lists")
                };
                assert!(
                    mine[i] && near(other, i),
                    "{}: pixel ({}, {}) changed by {which} alone, nothing near it by the other",
                    backend.name,
                    i % wu,
                    i / wu
                );
            }
            assert!(
                lit > 3000,
                "{}: the comb changed {lit} pixels",
                backend.name
            );
            assert!(
                apart * 4 <= lit,
                "{}: {apart} of {lit} pixels changed by one drawing only",
                backend.name
            );
            eprintln!(
                "{}: {lit} pixels changed, {apart} by one drawing only",
                backend.name
            );
        },
    );
}

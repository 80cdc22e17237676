//! The WGSL kernel against the exact f64 curves and its f32 CPU twin, on every backend
//! that has an adapter (Vulkan lavapipe and GL llvmpipe in CI; `SPLINESCOPE_TEST_BACKENDS`
//! chooses).
//!
//! Bound: max |GPU − CPU f64| ≤ 1e-6 · S for degree ≤ 12, with S = max(E, R): E the
//! diagonal of the control points' box (the control polygon's extent), R the largest
//! |P_i|. For curves whose box holds the origin R ≤ E, so S = E; for curves far from the
//! origin no f32 computation can do better than ε·R (ε = 2⁻²⁴), hence the max.
//! Above degree 12 the bound grows linearly: 1e-6 · S · n / 12. Why: f32 de Casteljau forms
//! n levels of convex combinations; each level adds at most a few roundings of size ε·R,
//! and the f32 parameter adds |P′| ε ≤ n · E · ε, so the worst-case error grows linearly in
//! n; scaling the degree-12 bound by n / 12 keeps the same margin.

mod common;

use glam::{DVec3, Vec3};
use splinescope_core::geom::{Bezier, ParamCurve};
use splinescope_core::rng::Rng;
use splinescope_encoding::Color;
use splinescope_gpu::chunks::{ChunkBuilder, ChunkLimits, TessChunk};
use splinescope_gpu::layout::{GpuLineStyle, MAX_GPU_DEGREE};
use splinescope_gpu::pack::prepare;
use splinescope_gpu::tessellator::{POISON, Tessellator, plan, read_buffer};
use splinescope_gpu::twin;
use splinescope_scene::format::encoding::encode;
use splinescope_scene::format::generate::{StressOptions, random_bezier_scene};

/// The bound for a curve of `degree` with control points `points` (see the module doc).
fn bound(degree: usize, points: &[DVec3]) -> f64 {
    let extent = splinescope_core::geom::Aabb::from_points(points).diagonal();
    let radius = points.iter().map(|p| p.length()).fold(0.0, f64::max);
    1e-6 * extent.max(radius) * (degree.max(12) as f64 / 12.0)
}

/// How far the GPU may be from its twin, which runs the same `f32` operations in the same
/// order: a compiler may contract `v·a + u·b` into fused multiply-adds (a rounding less per
/// level, up to 2 ulp of `S = max(R, E)` each) and divide `j / (count − 1)` within 2.5 ulp
/// (moving the sample by at most `|P′| · 2.5 ε ≤ 2.5 n E ε`): `8 · n · ε · S` with
/// `ε = 2⁻²⁴`, orders of magnitude below the bound against the exact curve.
fn twin_bound(degree: usize, points: &[DVec3]) -> f64 {
    let extent = splinescope_core::geom::Aabb::from_points(points).diagonal();
    let radius = points.iter().map(|p| p.length()).fold(0.0, f64::max);
    8.0 * degree.max(1) as f64 * f64::from(f32::EPSILON) / 2.0 * extent.max(radius)
}

fn random_curve(rng: &mut Rng, degree: usize, three_d: bool) -> Bezier {
    Bezier::new(
        (0..=degree)
            .map(|_| {
                DVec3::new(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    if three_d { rng.range(-1.0, 1.0) } else { 0.0 },
                )
            })
            .collect(),
    )
}

struct Case {
    curve: Bezier,
    samples: u32,
}

fn pack(cases: &[Case], limits: ChunkLimits) -> Vec<TessChunk> {
    let mut b = ChunkBuilder::new(limits);
    for (i, c) in cases.iter().enumerate() {
        b.begin_segment(
            i,
            GpuLineStyle::solid(Color::WHITE, 1.0),
            c.curve.points(),
            None,
        )
        .expect("fits");
        b.add_samples(c.samples, 0.0, 1.0);
    }
    b.finish()
}

/// Runs the kernel over `chunks`, checks every sample was written with the right tag and
/// lies within the bound of the f64 curve and close to the f32 twin. Returns the largest
/// error relative to each curve's extent.
fn check(backend: &common::Backend, cases: &[Case], chunks: &[TessChunk]) -> f64 {
    let ctx = &backend.ctx;
    let name = &backend.name;
    let tess = Tessellator::new(&ctx.device);
    let mut worst = 0.0_f64;
    tess.tessellate_and_read(&ctx.device, &ctx.queue, chunks, |k, gpu| {
        let chunk = &chunks[k];
        // The twin runs the very dispatches the tessellator issues (records, grid and
        // parameters), starting from the same poison.
        let mut cpu = vec![POISON; gpu.len()];
        for d in plan(
            chunk,
            ctx.device.limits().max_compute_workgroups_per_dimension,
        ) {
            twin::dispatch(&d.params, d.groups, &chunk.points, &chunk.records, &mut cpu);
        }
        for seg in &chunk.records {
            let case = &cases[chunk.first_curve + seg.curve as usize];
            let extent = case.curve.control_box().diagonal();
            let n = case.curve.degree();
            let bound = bound(n, case.curve.points());
            let lanes = seg.sample_offset..(seg.sample_offset + 64).min(seg.sample_count);
            for j in lanes {
                let s = gpu[(seg.first_sample + j) as usize];
                assert_eq!(
                    s.id, seg.curve,
                    "{name}: sample {j} not written or mis-tagged"
                );
                let g = Vec3::from(s.position).as_dvec3();
                assert!(
                    g.is_finite(),
                    "{name}: sample {j} of a degree-{n} curve not written"
                );
                // The kernel's parameter, then the exact curve there.
                let t = f64::from(seg.u0)
                    + (f64::from(seg.u1) - f64::from(seg.u0))
                        * if seg.sample_count > 1 {
                            f64::from(j) / f64::from(seg.sample_count - 1)
                        } else {
                            0.0
                        };
                let exact = case.curve.eval(t);
                let err = (g - exact).length();
                assert!(
                    err <= bound,
                    "{name}: degree {n}, sample {j}/{}: |GPU − f64| = {err:e} > {bound:e}",
                    seg.sample_count,
                );
                let t = cpu[(seg.first_sample + j) as usize];
                assert_eq!(t.id, seg.curve, "{name}: the twin's grid missed sample {j}");
                let twin_err = (g - Vec3::from(t.position).as_dvec3()).length();
                let twin_bound = twin_bound(n, case.curve.points());
                assert!(
                    twin_err <= twin_bound,
                    "{name}: degree {n}: GPU vs twin {twin_err:e} > {twin_bound:e}"
                );
                worst = worst.max(err / extent);
            }
        }
    })
    .expect("readback");
    worst
}

#[test]
fn kernel_matches_the_exact_curves_for_every_degree_2d_and_3d() {
    let test = "kernel_matches_the_exact_curves_for_every_degree_2d_and_3d";
    common::on_each_gpu(test, |backend| {
        let ctx = &backend.ctx;
        let mut rng = Rng::new(2024);
        let mut cases = Vec::new();
        for degree in 1..=MAX_GPU_DEGREE {
            for three_d in [false, true] {
                for _ in 0..4 {
                    cases.push(Case {
                        curve: random_curve(&mut rng, degree, three_d),
                        samples: rng.int(2, 300) as u32,
                    });
                }
            }
        }
        let chunks = pack(
            &cases,
            ChunkLimits::for_binding_size(ctx.max_binding_bytes()),
        );
        assert_eq!(chunks.len(), 1);
        let worst = check(backend, &cases, &chunks);
        eprintln!(
            "{}: largest |GPU − f64| / extent over degrees 1..=31: {worst:e}",
            backend.name
        );
    });
}

#[test]
fn tiny_chunks_split_runs_and_still_write_every_sample() {
    common::on_each_gpu(
        "tiny_chunks_split_runs_and_still_write_every_sample",
        |backend| {
            let mut rng = Rng::new(5);
            let cases: Vec<Case> = (0..40)
                .map(|i| Case {
                    curve: random_curve(&mut rng, 1 + i % 9, i % 2 == 0),
                    samples: rng.int(2, 120) as u32,
                })
                .collect();
            let limits = ChunkLimits {
                max_samples: 97,
                max_points: 40,
                max_records: 7,
                max_styles: 5,
            };
            let chunks = pack(&cases, limits);
            assert!(
                chunks.len() >= 15,
                "limits must force many chunks, got {}",
                chunks.len()
            );
            for c in &chunks {
                assert!(c.sample_count as usize <= limits.max_samples);
                assert!(c.points.len() <= limits.max_points);
                assert!(c.records.len() <= limits.max_records);
                assert!(c.styles.len() <= limits.max_styles);
            }
            check(backend, &cases, &chunks);
        },
    );
}

#[test]
fn dispatch_grid_covers_more_segments_than_one_dimension_allows() {
    use splinescope_gpu::tessellator::dispatch_grid;
    assert_eq!(dispatch_grid(0, 65535), (0, 0));
    assert_eq!(dispatch_grid(10, 65535), (10, 1));
    let (x, y) = dispatch_grid(1_000_000, 65535);
    assert!(x <= 65535 && y <= 65535 && u64::from(x) * u64::from(y) >= 1_000_000);
    // The twin on the planned 2D grid (3 workgroups per dimension at most) writes every
    // sample, exactly as evaluating every record directly does.
    let mut rng = Rng::new(8);
    let cases: Vec<Case> = (0..23)
        .map(|i| Case {
            curve: random_curve(&mut rng, 1 + i % 6, false),
            samples: rng.int(2, 150) as u32,
        })
        .collect();
    let chunks = pack(&cases, ChunkLimits::for_binding_size(1 << 20));
    let chunk = &chunks[0];
    let n = chunk.sample_count as usize;
    let mut direct = vec![POISON; n];
    twin::tessellate(&chunk.points, &chunk.records, &mut direct);
    let mut gridded = vec![POISON; n];
    let planned = plan(chunk, 3);
    assert!(planned.iter().any(|d| d.groups.1 > 1), "a 2D grid is used");
    for d in &planned {
        twin::dispatch(
            &d.params,
            d.groups,
            &chunk.points,
            &chunk.records,
            &mut gridded,
        );
    }
    assert_eq!(gridded, direct);
    assert!(gridded.iter().all(|v| v.id != u32::MAX));
    // A grid one row short leaves samples unwritten: the comparison can fail.
    let mut short = vec![POISON; n];
    for d in &planned {
        twin::dispatch(
            &d.params,
            (d.groups.0, d.groups.1 - 1),
            &chunk.points,
            &chunk.records,
            &mut short,
        );
    }
    assert!(short.iter().any(|v| v.id == u32::MAX));
}

#[test]
fn one_million_cubics_tessellate_correctly_in_chunks() {
    common::on_each_gpu(
        "one_million_cubics_tessellate_correctly_in_chunks",
        |backend| {
            let ctx = &backend.ctx;
            let name = &backend.name;
            let scene = random_bezier_scene(StressOptions {
                curves: 1_000_000,
                degree: 3,
                samples: 64,
                three_d: false,
                seed: 99,
                ..Default::default()
            });
            let limits = ChunkLimits::for_binding_size(ctx.max_binding_bytes());
            let prepared = prepare(&encode(&scene), limits).expect("packs");
            let total: u64 = prepared
                .chunks
                .iter()
                .map(|c| u64::from(c.sample_count))
                .sum();
            assert_eq!(total, 64_000_000);
            // 64M samples × 16 B = 1 GiB: more than one 128 MiB binding, so several chunks.
            assert!(
                prepared.chunks.len() >= 8,
                "{} chunks",
                prepared.chunks.len()
            );
            // More workgroups than one dispatch dimension allows, so the 2D grid is used.
            assert!(prepared.chunks[0].records.len() > 65_535);
            let tess = Tessellator::new(&ctx.device);
            let mut checked = 0u64;
            let mut seen = 0u64;
            tess.tessellate_and_read(&ctx.device, &ctx.queue, &prepared.chunks, |k, gpu| {
                let chunk = &prepared.chunks[k];
                // Every sample written (the buffer was poisoned with NaN / u32::MAX)…
                for (i, s) in gpu.iter().enumerate() {
                    assert!(
                        s.id != u32::MAX && !s.position[0].is_nan(),
                        "{name}: chunk {k}: sample {i} not written"
                    );
                }
                seen += gpu.len() as u64;
                // …and a spread of them equal to the exact curves.
                for seg in chunk.records.iter().step_by(97) {
                    let curve = chunk.first_curve + seg.curve as usize;
                    let b = &scene.curves[curve].curve;
                    let bound = bound(3, b.control_points());
                    for j in [0, 17, 63] {
                        let s = gpu[(seg.first_sample + j) as usize];
                        let t = f64::from(j) / 63.0;
                        let err = (Vec3::from(s.position).as_dvec3() - b.eval(t)).length();
                        assert!(err <= bound, "{name}: curve {curve}: {err:e} > {bound:e}");
                        checked += 1;
                    }
                }
            })
            .expect("readback");
            assert_eq!(seen, 64_000_000);
            assert!(checked > 30_000, "{checked}");
        },
    );
}

/// The self-test that runs when a device opens catches a kernel that computes wrong
/// samples: here a general kernel that returns `P_0` for every sample, the fault Mesa's
/// GL compiler once produced. The real kernels pass it on every backend.
#[test]
fn the_kernel_self_test_refuses_a_wrong_kernel() {
    use splinescope_gpu::selftest;
    use splinescope_gpu::shaders::TESSELLATE;
    common::on_each_gpu("the_kernel_self_test_refuses_a_wrong_kernel", |backend| {
        let ctx = &backend.ctx;
        let good = Tessellator::new(&ctx.device);
        assert_eq!(
            selftest::run(&ctx.device, &ctx.queue, &good).expect("dispatch"),
            None,
            "{}: the real kernels pass",
            backend.name
        );
        // The general kernel returns P_0 instead of the curve.
        let sum = "let p = general_point(seg.first_point, n, seg.rational != 0u, u, v);";
        assert_eq!(TESSELLATE.body.matches(sum).count(), 1);
        let broken_body = TESSELLATE.body.replace(
            sum,
            "let p = control_point(seg.first_point, 0u) + 0.0 * f32(n) * v;",
        );
        let module = ctx
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("broken tessellate"),
                source: wgpu::ShaderSource::Wgsl(TESSELLATE.composed_with(&broken_body).into()),
            });
        let broken = Tessellator::with_module(&ctx.device, &module);
        let fault = selftest::run(&ctx.device, &ctx.queue, &broken)
            .expect("dispatch")
            .unwrap_or_else(|| panic!("{}: a kernel returning P_0 passed", backend.name));
        assert_eq!(fault.kernel, "tessellate_any", "{}", backend.name);
        assert_eq!(
            fault.degree, 1,
            "the first degree the general kernel serves"
        );
        assert!(
            fault.u > 0.0,
            "at u = 0 the sample is P_0 and right: {fault:?}"
        );
        let message = fault.to_string();
        assert!(
            message.contains("tessellate_any") && message.contains("degree-1"),
            "{message}"
        );
    });
}

#[test]
fn the_write_only_kernel_writes_exactly_the_kernels_samples() {
    common::on_each_gpu(
        "the_write_only_kernel_writes_exactly_the_kernels_samples",
        |backend| {
            let ctx = &backend.ctx;
            let name = &backend.name;
            let mut rng = Rng::new(9);
            let cases: Vec<Case> = (0..30)
                .map(|i| Case {
                    curve: random_curve(&mut rng, 1 + i % 12, false),
                    samples: rng.int(2, 150) as u32,
                })
                .collect();
            let limits = ChunkLimits {
                max_samples: 500,
                max_points: 100,
                max_records: 20,
                max_styles: 10,
            };
            let chunks = pack(&cases, limits);
            let tess = Tessellator::new(&ctx.device);
            assert!(
                !tess.write_only_built(),
                "{name}: a tessellator that only draws builds no write-only kernel"
            );
            for chunk in &chunks {
                let buffers = tess.upload(
                    &ctx.device,
                    chunk,
                    wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                );
                let poison = vec![POISON; chunk.sample_count as usize];
                ctx.queue
                    .write_buffer(&buffers.samples, 0, bytemuck::cast_slice(&poison));
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                tess.encode_write_only(&ctx.device, &mut encoder, [&buffers], None);
                assert!(
                    tess.write_only_built(),
                    "{name}: built when first asked for"
                );
                ctx.queue.submit([encoder.finish()]);
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                let got: Vec<splinescope_gpu::layout::GpuVertex> =
                    read_buffer(&ctx.device, &ctx.queue, &mut encoder, &buffers.samples)
                        .expect("readback");
                // Every sample the kernels write, and nothing else, holds its parameter.
                let mut written = vec![false; got.len()];
                for seg in &chunk.records {
                    let lanes = seg.sample_offset..(seg.sample_offset + 64).min(seg.sample_count);
                    for j in lanes {
                        let k = (seg.first_sample + j) as usize;
                        written[k] = true;
                        assert_eq!(got[k].id, seg.curve, "{name}: sample {k} tag");
                        // The parameter in f32 (a fused multiply-add on some adapters).
                        let [u, y, z] = got[k].position;
                        let want = twin::sample_param(seg, j);
                        assert!(
                            (u - want).abs() <= 4.0 * f32::EPSILON && y == 0.0 && z == 0.0,
                            "{name}: sample {k}: {:?}, want ({want}, 0, 0)",
                            got[k].position
                        );
                    }
                }
                for (k, w) in written.iter().enumerate() {
                    if !w {
                        assert_eq!(
                            got[k].id, POISON.id,
                            "{name}: sample {k} written by no record"
                        );
                    }
                }
                assert!(written.iter().all(|&w| w), "{name}: packing leaves no gap");
            }
        },
    );
}

//! `splinescope eval`: evaluate curves (and their derivatives) on the CPU or the GPU and print JSON.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use glam::DVec3;

use splinescope_core::geom::{Lower, ParamCurve};
use splinescope_core::num::Num;
use splinescope_scene::format::Scene;

use crate::{GpuArgs, select_curves};

/// The arguments of `splinescope eval`.
#[derive(Debug, clap::Args)]
pub struct EvalArgs {
    /// Scene file (JSON), or an SVG file read as path curves.
    pub scene: PathBuf,
    /// Number of uniform parameters over each curve's whole domain (ends included).
    #[arg(long, value_parser = crate::words::between::<u32>(2, 10_000_000), conflicts_with = "params", allow_hyphen_values = true)]
    pub samples: Option<u32>,
    /// Comma-separated parameters, in each curve's own parameter.
    #[arg(long, value_name = "T0,T1,...", allow_hyphen_values = true)]
    pub params: Option<String>,
    /// Where to evaluate: the exact f64 CPU path, or the GPU kernel (f32).
    #[arg(long, value_enum, default_value_t = EvalBackend::Cpu)]
    pub backend: EvalBackend,
    /// Only this curve (index in the scene).
    #[arg(long, allow_hyphen_values = true)]
    pub curve: Option<usize>,
    /// Also print the first derivative P′ (`1`), or P′, P″ and the curvature (`2`), at
    /// each parameter.
    #[arg(long, value_parser = crate::words::between::<u32>(1, 2), allow_hyphen_values = true)]
    pub derivatives: Option<u32>,
    #[command(flatten)]
    pub gpu: GpuArgs,
}

/// Runs `splinescope eval`.
///
/// # Errors
/// A scene that does not load, parameters outside a domain, values that are not finite.
pub fn run(a: &EvalArgs) -> Result<()> {
    eval(
        &a.scene,
        &EvalRequest {
            samples: a.samples,
            params: a.params.as_deref(),
            backend: a.backend,
            only: a.curve,
            derivatives: a.derivatives.unwrap_or(0),
        },
        &a.gpu,
    )
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum EvalBackend {
    /// Exact f64 evaluation of each family.
    Cpu,
    /// The WGSL de Casteljau kernel, read back (f32).
    Gpu,
}

/// Parses `--params`: comma-separated finite numbers.
fn parse_params(text: &str) -> Result<Vec<f64>> {
    text.split(',')
        .enumerate()
        .map(|(i, item)| {
            let item = item.trim();
            match item.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                Ok(v) => bail!("--params[{i}]: {v} is not a finite number"),
                Err(_) => bail!("--params[{i}]: {item:?} is not a number"),
            }
        })
        .collect()
}

/// What `eval` was asked for.
struct EvalRequest<'a> {
    samples: Option<u32>,
    params: Option<&'a str>,
    backend: EvalBackend,
    only: Option<usize>,
    /// 0: points only; 1: and P′; 2: and P″ and the curvature.
    derivatives: u32,
}

fn eval(path: &Path, req: &EvalRequest<'_>, gpu: &GpuArgs) -> Result<()> {
    let scene = crate::load::scene(path)?;
    let indices = select_curves(&scene, req.only)?;
    let per_curve = parameters(&scene, &indices, req)?;
    // values[0]: the points; values[k]: the k-th derivative.
    let values = match req.backend {
        EvalBackend::Cpu => cpu_values(&scene, &indices, &per_curve, req.derivatives),
        EvalBackend::Gpu => gpu_values(&scene, &indices, &per_curve, req.derivatives, gpu)?,
    };
    let from_f32 = req.backend == EvalBackend::Gpu;
    check_finite(path, &indices, &per_curve, &values, from_f32)?;
    let curvatures = (values.len() == 3)
        .then(|| curvatures(path, &indices, &per_curve, &values[1], &values[2]))
        .transpose()?;
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    write_eval_json(&mut out, &indices, &values, curvatures.as_deref(), from_f32)?;
    out.flush()?;
    Ok(())
}

/// Each selected curve's parameters: the `--params` given (each checked against the
/// curve's domain) or `--samples` uniform ones, after the total is checked against
/// [`splinescope_io::limits::SAMPLES`].
fn parameters(scene: &Scene, indices: &[usize], req: &EvalRequest<'_>) -> Result<Vec<Vec<f64>>> {
    let given = req.params.map(parse_params).transpose()?;
    let per = match (&given, req.samples) {
        (Some(ts), _) => ts.len() as u64,
        (None, Some(n)) => u64::from(n),
        (None, None) => bail!("give --samples N or --params T0,T1,..."),
    };
    splinescope_io::limits::SAMPLES
        .check(per.saturating_mul(indices.len() as u64))
        .with_context(|| {
            format!(
                "{} curve(s) × {per} parameter(s) to evaluate",
                indices.len()
            )
        })?;
    let mut per_curve = Vec::with_capacity(indices.len());
    for &i in indices {
        let (a, b) = scene.curves[i].curve.domain();
        let ts = match &given {
            Some(ts) => {
                if let Some((k, &t)) = ts.iter().enumerate().find(|(_, t)| !(a..=b).contains(*t)) {
                    bail!(
                        "--params[{k}] = {} is outside the domain [{}, {}] of curves[{i}]",
                        Num(t),
                        Num(a),
                        Num(b)
                    );
                }
                ts.clone()
            }
            None => {
                let n = per as usize;
                (0..n)
                    .map(|j| splinescope_core::geom::batch::uniform(a, b, j, n))
                    .collect()
            }
        };
        per_curve.push(ts);
    }
    Ok(per_curve)
}

/// The exact `f64` values: points by the batch evaluator over the exact lowering, then
/// each family's own first and second derivatives.
fn cpu_values(
    scene: &Scene,
    indices: &[usize],
    per_curve: &[Vec<f64>],
    derivatives: u32,
) -> Vec<Vec<Vec<DVec3>>> {
    (0..=derivatives)
        .map(|k| {
            indices
                .iter()
                .zip(per_curve)
                .map(|(&i, ts)| {
                    let c = &scene.curves[i].curve;
                    if k == 0 {
                        let mut out = vec![DVec3::ZERO; ts.len()];
                        splinescope_core::geom::batch::CurveSampler::new(c).eval_into(ts, &mut out);
                        return out;
                    }
                    ts.iter()
                        .map(|&t| match k {
                            1 => c.eval_deriv(t),
                            _ => c.eval_second_deriv(t),
                        })
                        .collect()
                })
                .collect()
        })
        .collect()
}

/// The GPU kernel's values (`f32`): the points, then each derivative through the
/// hodographs.
fn gpu_values(
    scene: &Scene,
    indices: &[usize],
    per_curve: &[Vec<f64>],
    derivatives: u32,
    gpu: &GpuArgs,
) -> Result<Vec<Vec<Vec<DVec3>>>> {
    let (ctx, pipelines) = gpu.context()?;
    let lowered: Vec<_> = indices
        .iter()
        .map(|&i| (i, scene.curves[i].curve.lower()))
        .collect();
    let mut v = vec![splinescope_gpu::eval::evaluate(
        &ctx, &pipelines, &lowered, per_curve,
    )?];
    for k in 1..=derivatives {
        v.push(splinescope_gpu::eval::evaluate_derivative(
            &ctx, &pipelines, &lowered, per_curve, k,
        )?);
    }
    Ok(v)
}

/// Every number printed is finite, or the command fails naming where it overflowed.
fn check_finite(
    path: &Path,
    indices: &[usize],
    per_curve: &[Vec<f64>],
    values: &[Vec<Vec<DVec3>>],
    from_f32: bool,
) -> Result<()> {
    for (k, pts_all) in values.iter().enumerate() {
        for ((&i, ts), pts) in indices.iter().zip(per_curve).zip(pts_all) {
            if let Some((t, p)) = ts.iter().zip(pts).find(|(_, p)| !p.is_finite()) {
                bail!(
                    "{}: curves[{i}] at t = {t}: the {} {p} is not finite (the curve's coordinates are too large for this computation in {})",
                    path.display(),
                    ["value", "first derivative", "second derivative"][k],
                    if from_f32 { "f32" } else { "f64" }
                );
            }
        }
    }
    Ok(())
}

/// κ = |P′ × P″| / |P′|³ from the derivatives, scaled so that it underflows nowhere:
/// `None` only where P′ = 0; a curvature beyond f64 fails like any other value.
fn curvatures(
    path: &Path,
    indices: &[usize],
    per_curve: &[Vec<f64>],
    d1: &[Vec<DVec3>],
    d2: &[Vec<DVec3>],
) -> Result<Vec<Vec<Option<f64>>>> {
    let all: Vec<Vec<Option<f64>>> = d1
        .iter()
        .zip(d2)
        .map(|(d1s, d2s)| {
            d1s.iter()
                .zip(d2s)
                .map(|(a, b)| splinescope_core::geom::curvature(*a, *b))
                .collect()
        })
        .collect();
    for ((&i, ts), ks) in indices.iter().zip(per_curve).zip(&all) {
        if let Some((t, k)) = ts
            .iter()
            .zip(ks)
            .find_map(|(t, k)| k.filter(|k| !k.is_finite()).map(|k| (t, k)))
        {
            bail!(
                "{}: curves[{i}] at t = {t}: the curvature {k} is beyond f64 (P′ is nearly zero where P″ is not)",
                path.display()
            );
        }
    }
    Ok(all)
}

/// Writes [`EvalOutput`](splinescope::outputs::EvalOutput), streamed curve by curve
/// (scenes may be large), with `"d1"` (P′), `"d2"` (P″) and `"curvature"` when derivatives
/// were asked for. GPU values are `f32`: they are printed in their shortest `f32` form.
fn write_eval_json(
    out: &mut impl Write,
    indices: &[usize],
    values: &[Vec<Vec<DVec3>>],
    curvatures: Option<&[Vec<Option<f64>>]>,
    from_f32: bool,
) -> Result<()> {
    let shortest = |p: DVec3| -> [f64; 3] {
        p.to_array().map(|v| {
            if from_f32 {
                shortest_f32_precision(v)
            } else {
                v
            }
        })
    };
    let list = |pts: &[DVec3]| pts.iter().copied().map(shortest).collect::<Vec<_>>();
    write!(out, "{{\"curves\":[")?;
    for (k, &index) in indices.iter().enumerate() {
        if k > 0 {
            write!(out, ",")?;
        }
        let curvature = curvatures.map(|ks| {
            ks[k]
                .iter()
                .map(|kappa| kappa.map(|v| shortest(DVec3::splat(v))[0]))
                .collect()
        });
        let curve = splinescope::outputs::EvalCurve {
            index,
            samples: list(&values[0][k]),
            d1: values.get(1).map(|v| list(&v[k])),
            d2: values.get(2).map(|v| list(&v[k])),
            curvature,
        };
        writeln!(out)?;
        serde_json::to_writer(&mut *out, &curve)?;
    }
    writeln!(out, "\n]}}")?;
    Ok(())
}

/// The shortest decimal that reads back as `v` rounded to `f32`'s 24 significant bits, at
/// `v`'s own binary exponent — so a GPU value (an `f32` that `eval` may have scaled by a
/// power of two to keep it out of `f32`'s subnormal range) prints as few digits as an `f32`
/// does, whatever its magnitude.
fn shortest_f32_precision(v: f64) -> f64 {
    use splinescope_core::num::{scale_by_power_of_two, split_exponent};
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    // v and its candidates, brought exactly to v's binade [1, 2) before rounding to f32.
    let (_, exponent) = split_exponent(v.abs());
    let at_unit = |x: f64| scale_by_power_of_two(x, -exponent) as f32;
    let target = at_unit(v);
    for digits in 0..9 {
        let x: f64 = format!("{v:.digits$e}").parse().unwrap_or(v);
        if at_unit(x) == target {
            return x;
        }
    }
    v
}

//! `bench --plot FILE.png|FILE.svg`: throughput against problem size, one line per path
//! (CPU f64 one thread and all cores, the f32 twin, the GPU kernel, the GPU write-only
//! bound) and per family and degree, both axes logarithmic.

use std::path::Path;

use anyhow::{Context, Result, anyhow, bail};
use plotters::prelude::*;

use super::BenchReport;

/// The paths drawn: (label, colour, the rate of a row).
type Path_ = (&'static str, RGBColor, fn(&BenchReport) -> Option<f64>);

const PATHS: [Path_; 5] = [
    ("CPU f64, 1 thread", RGBColor(31, 119, 180), |r| {
        Some(r.cpu_f64_one_thread_samples_per_s)
    }),
    ("CPU f64, all cores", RGBColor(255, 127, 14), |r| {
        Some(r.cpu_f64_all_cores_samples_per_s)
    }),
    ("CPU f32 twin", RGBColor(44, 160, 44), |r| {
        r.cpu_f32_twin_one_thread_samples_per_s
    }),
    ("GPU kernel", RGBColor(214, 39, 40), |r| {
        r.gpu_compute_timestamp_samples_per_s
            .or(r.gpu_compute_wall_samples_per_s)
    }),
    ("GPU write-only bound", RGBColor(148, 103, 189), |r| {
        r.gpu_write_limit_samples_per_s
    }),
];

/// Refuses a path that is neither `.png` nor `.svg` (checked before any row runs).
///
/// # Errors
/// The path, named, with what it must end in.
pub fn check_path(path: &Path) -> Result<()> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("png" | "svg") => Ok(()),
        _ => bail!(
            "--plot {}: the file must end in .png or .svg",
            path.display()
        ),
    }
}

/// Draws the rows as the bytes of `path`'s format (PNG or SVG by its extension),
/// 1000 × 640; the caller writes them.
///
/// # Errors
/// An extension other than `.png` or `.svg`, or a drawing that fails.
pub fn encode(path: &Path, reports: &[BenchReport]) -> Result<Vec<u8>> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let size = (1000u32, 640u32);
    // Both backends measure text with ab_glyph: it needs a font registered.
    plotters::style::register_font(
        "sans-serif",
        FontStyle::Normal,
        epaint_default_fonts::UBUNTU_LIGHT,
    )
    .map_err(|_| anyhow!("the built-in font could not be read"))?;
    match ext.as_deref() {
        Some("svg") => {
            let mut svg = String::new();
            draw(
                SVGBackend::with_string(&mut svg, size).into_drawing_area(),
                reports,
            )?;
            Ok(svg.into_bytes())
        }
        Some("png") => {
            let mut rgb = vec![0u8; (size.0 * size.1 * 3) as usize];
            draw(
                BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area(),
                reports,
            )?;
            let image = splinescope_image::RgbaImage {
                width: size.0,
                height: size.1,
                data: rgb
                    .chunks_exact(3)
                    .flat_map(|p| [p[0], p[1], p[2], 255])
                    .collect(),
            };
            image
                .png_bytes(path)
                .with_context(|| format!("drawing {}", path.display()))
        }
        _ => bail!(
            "--plot {}: the file must end in .png or .svg",
            path.display()
        ),
    }
}

fn draw<DB: DrawingBackend>(
    area: DrawingArea<DB, plotters::coord::Shift>,
    reports: &[BenchReport],
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("plot: {e:?}");
    area.fill(&WHITE).map_err(err)?;
    let x = |r: &BenchReport| (r.curves * u64::from(r.samples_per_curve)) as f64;
    let points: Vec<(f64, f64)> = reports
        .iter()
        .flat_map(|r| {
            PATHS
                .iter()
                .filter_map(move |(_, _, f)| f(r).map(|v| (x(r), v / 1e6)))
        })
        .filter(|(a, b)| *a > 0.0 && *b > 0.0)
        .collect();
    if points.is_empty() {
        bail!("plot: no rates to draw");
    }
    let (x0, x1) = points.iter().fold((f64::MAX, 0.0_f64), |(lo, hi), p| {
        (lo.min(p.0), hi.max(p.0))
    });
    let (y0, y1) = points.iter().fold((f64::MAX, 0.0_f64), |(lo, hi), p| {
        (lo.min(p.1), hi.max(p.1))
    });
    let adapter = reports.first().map_or("", |r| r.meta.adapter.as_str());
    let mut chart = ChartBuilder::on(&area)
        .caption(format!("splinescope bench — {adapter}"), ("sans-serif", 18))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(
            (x0 / 1.5..x1 * 1.5).log_scale(),
            (y0 / 1.5..y1 * 1.5).log_scale(),
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("samples per run (curves × samples per curve)")
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v}"))
        .y_desc("M samples / s")
        .label_style(("sans-serif", 13))
        .draw()
        .map_err(err)?;
    // One line per path and per (family, degree, samples per curve).
    let mut groups: Vec<(&str, u64, u32)> = reports
        .iter()
        .map(|r| (r.family, r.degree, r.samples_per_curve))
        .collect();
    groups.sort_unstable();
    groups.dedup();
    for (label, color, f) in PATHS {
        for (k, &(family, degree, samples)) in groups.iter().enumerate() {
            let mut line: Vec<(f64, f64)> = reports
                .iter()
                .filter(|r| (r.family, r.degree, r.samples_per_curve) == (family, degree, samples))
                .filter_map(|r| f(r).map(|v| (x(r), v / 1e6)))
                .collect();
            line.sort_by(|a, b| a.0.total_cmp(&b.0));
            if line.is_empty() {
                continue;
            }
            let style = ShapeStyle::from(color).stroke_width(2);
            let series = chart
                .draw_series(LineSeries::new(line.clone(), style))
                .map_err(err)?;
            if k == 0 {
                series
                    .label(label)
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], style));
            }
            chart
                .draw_series(line.iter().map(|&p| Circle::new(p, 3, color.filled())))
                .map_err(err)?;
        }
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(err)?;
    area.present().map_err(err)?;
    Ok(())
}

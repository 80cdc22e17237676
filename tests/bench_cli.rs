//! `splinescope bench` as a stress-testing tool: a matrix of rows as JSON and CSV with the
//! machine named, GPU rows skipped (with the reason) above the GPU's degree, bad input
//! refused before anything is allocated, and `--compare` failing on a regression.

mod common;

use common::{run, text};
use serde_json::Value;

fn bench_json(extra: &[&str]) -> (Vec<Value>, std::process::Output) {
    let mut args = vec!["bench", "--frames", "0", "--iterations", "1", "--json"];
    args.extend_from_slice(extra);
    let out = run(&args);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    let value: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let rows = match value {
        Value::Array(rows) => rows,
        one => vec![one],
    };
    (rows, out)
}

#[test]
fn a_matrix_gives_one_row_per_combination_as_json_and_csv() {
    if common::gpus("bench matrix").is_empty() {
        return;
    }
    let dir = common::out_dir("bench_cli");
    let csv = dir.join("matrix.csv");
    let csv_arg = csv.to_string_lossy().into_owned();
    let png = dir.join("matrix.png");
    let png_arg = png.to_string_lossy().into_owned();
    let (rows, _) = bench_json(&[
        "--curves",
        "200,3e2",
        "--degrees",
        "3,31",
        "--families",
        "bezier,nubmp",
        "--samples",
        "8",
        "--csv",
        &csv_arg,
        "--plot",
        &png_arg,
    ]);
    // The plot: a 1000 × 640 PNG with a white background and coloured lines on it.
    let plot = splinescope_image::RgbaImage::read_png(&png).expect("plot written");
    assert_eq!((plot.width, plot.height), (1000, 640));
    let coloured = plot
        .data
        .chunks_exact(4)
        .filter(|p| {
            let (max, min) = (p[..3].iter().max().unwrap(), p[..3].iter().min().unwrap());
            max - min > 60
        })
        .count();
    assert!(
        coloured > 1000,
        "the plot has lines ({coloured} coloured pixels)"
    );
    assert_eq!(rows.len(), 8, "2 families × 2 degrees × 2 sizes");
    for row in &rows {
        let family = row["family"].as_str().expect("family");
        let degree = row["degree"].as_u64().expect("degree");
        let curves = row["curves"].as_u64().expect("curves");
        assert!(curves == 200 || curves == 300, "{row}");
        let segments = if family == "bezier" { 1 } else { 4 };
        assert_eq!(
            row["samples_per_curve"].as_u64(),
            Some(8 * segments),
            "{row}"
        );
        assert!(row["cpu_f64_one_thread_samples_per_s"].as_f64().unwrap() > 0.0);
        assert!(row["cpu_f64_all_cores_samples_per_s"].as_f64().unwrap() > 0.0);
        for key in ["adapter", "cpu_model", "build", "date"] {
            assert!(!row[key].as_str().unwrap_or("").is_empty(), "{key}: {row}");
        }
        assert!(row["cores"].as_u64().unwrap() >= 1);
        let date = row["date"].as_str().unwrap();
        assert!(
            date.len() == 20 && date.ends_with('Z') && date.starts_with("20"),
            "{date}"
        );
        // A NUBMP curve of degree 31 lowers to degree 32: over the GPU's maximum.
        let gpu_skipped = family == "nubmp" && degree == 31;
        let gpu = &row["gpu_compute_wall_samples_per_s"];
        if gpu_skipped {
            assert!(gpu.is_null(), "{row}");
            assert!(row["gpu_write_limit_samples_per_s"].is_null());
            let notes = row["notes"].as_array().expect("notes");
            assert!(
                notes.iter().any(|n| n
                    .as_str()
                    .unwrap()
                    .contains("degree 32, over the GPU maximum of 31")),
                "{row}"
            );
        } else {
            assert!(gpu.as_f64().unwrap() > 0.0, "{row}");
            let limit = row["gpu_write_limit_samples_per_s"].as_f64().unwrap();
            let share = row["gpu_kernel_share_of_write_limit"].as_f64().unwrap();
            assert!(limit > 0.0 && share > 0.0, "{row}");
        }
    }
    let text = std::fs::read_to_string(&csv).expect("CSV written");
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 9, "a header and 8 rows:\n{text}");
    let header: Vec<&str> = lines[0].split(',').collect();
    for key in [
        "family",
        "curves",
        "degree",
        "cpu_f64_all_cores_samples_per_s",
        "gpu_write_limit_samples_per_s",
        "cpu_model",
        "date",
    ] {
        assert!(header.contains(&key), "{key} in {header:?}");
    }
}

#[test]
fn bad_bench_input_is_refused_naming_the_value() {
    for (args, says) in [
        (
            vec!["bench", "--curves", "0"],
            "\"0\": the number of curves must be a whole number",
        ),
        (
            vec!["bench", "--curves", "1.5"],
            "\"1.5\": the number of curves must be a whole number",
        ),
        (vec!["bench", "--degrees", "3,64"], "64"),
        (
            vec!["bench", "--threshold", "fast"],
            "\"fast\" is not a percentage",
        ),
        (
            vec!["bench", "--families", "conic"],
            "unknown curve family \"conic\"",
        ),
    ] {
        let out = run(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", text(&out));
        assert!(
            text(&out).contains(says),
            "{args:?} should say {says:?}: {}",
            text(&out)
        );
    }
    // The largest row is refused before any row runs (instantly, nothing allocated).
    let started = std::time::Instant::now();
    let out = run(&[
        "bench",
        "--curves",
        "1e3,1e6",
        "--samples",
        "16,256",
        "--degrees",
        "3",
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    let t = text(&out);
    assert!(
        t.contains("bench row --families bezier --curves 1000000 --degrees 3 --samples 256")
            && t.contains("256000000 is over the limit of 134217728 samples per command"),
        "{t}"
    );
    assert!(
        started.elapsed().as_secs() < 10,
        "refused before running rows"
    );
}

#[test]
fn an_svg_plot_names_every_path_and_other_extensions_are_refused() {
    if common::gpus("bench plot").is_empty() {
        return;
    }
    let dir = common::out_dir("bench_cli");
    let svg = dir.join("plot.svg");
    let out = run(&[
        "bench",
        "--curves",
        "100,200",
        "--samples",
        "8",
        "--frames",
        "0",
        "--iterations",
        "1",
        "--plot",
        &svg.to_string_lossy(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    let text_svg = std::fs::read_to_string(&svg).expect("SVG written");
    assert!(
        text_svg.starts_with("<svg"),
        "{}",
        &text_svg[..100.min(text_svg.len())]
    );
    for label in [
        "CPU f64, 1 thread",
        "CPU f64, all cores",
        "CPU f32 twin",
        "GPU kernel",
        "GPU write-only bound",
    ] {
        assert!(text_svg.contains(label), "legend {label}");
    }
    // Refused before any row runs.
    let bad = dir.join("plot.txt");
    let out = run(&["bench", "--plot", &bad.to_string_lossy()]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    assert!(
        text(&out).contains("must end in .png or .svg"),
        "{}",
        text(&out)
    );
}

#[test]
fn compare_fails_on_a_regression_beyond_the_threshold() {
    if common::gpus("bench compare").is_empty() {
        return;
    }
    let dir = common::out_dir("bench_cli");
    let args = ["--curves", "300", "--samples", "8"];
    let (rows, _) = bench_json(&args);
    // An earlier run a million times faster everywhere: every rate fell (tiny workloads
    // are noisy, so the factors are far beyond any noise).
    let scaled = |factor: f64| {
        let mut rows = rows.clone();
        for row in &mut rows {
            for (k, v) in row.as_object_mut().unwrap() {
                if k.ends_with("_samples_per_s") && v.is_f64() {
                    *v = Value::from(v.as_f64().unwrap() * factor);
                }
            }
        }
        Value::Array(rows)
    };
    let faster = dir.join("faster.json");
    std::fs::write(&faster, scaled(1e6).to_string()).unwrap();
    let faster_arg = faster.to_string_lossy().into_owned();
    let mut with = vec!["bench", "--frames", "0", "--iterations", "1"];
    with.extend_from_slice(&args);
    with.extend_from_slice(&["--compare", &faster_arg, "--threshold", "10%"]);
    let out = run(&with);
    let t = text(&out);
    assert_eq!(out.status.code(), Some(1), "{t}");
    assert!(
        t.contains("regression") && t.contains("fell by more than 10 %"),
        "{t}"
    );
    assert!(t.contains("cpu_f64_one_thread_samples_per_s"), "{t}");
    // An earlier run a million times slower: no regression, exit 0, the changes printed.
    let slower = dir.join("slower.json");
    std::fs::write(&slower, scaled(1e-6).to_string()).unwrap();
    let slower_arg = slower.to_string_lossy().into_owned();
    let last = with.len() - 3;
    with[last] = &slower_arg;
    let out = run(&with);
    let t = text(&out);
    assert_eq!(out.status.code(), Some(0), "{t}");
    assert!(
        t.contains("compare: bezier 300 curves, degree 3, 8 samples:"),
        "{t}"
    );
    assert!(!t.contains("<< regression"), "{t}");
    // Not bench output: refused with the reason.
    let bogus = dir.join("bogus.json");
    std::fs::write(&bogus, "{\"hello\": 1}").unwrap();
    let out = run(&["bench", "--compare", &bogus.to_string_lossy()]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    assert!(
        text(&out).contains("has no whole number `curves`"),
        "{}",
        text(&out)
    );
}

#[test]
fn rational_families_are_benchmarked_through_the_rational_kernel() {
    if common::gpus("bench of rational families").is_empty() {
        return;
    }
    let (rows, _) = bench_json(&[
        "--curves",
        "200",
        "--degrees",
        "2,5",
        "--families",
        "rational_bezier,nurbs",
        "--samples",
        "8",
    ]);
    assert_eq!(rows.len(), 4, "2 families × 2 degrees");
    for row in &rows {
        let family = row["family"].as_str().expect("family");
        assert!(family == "rational_bezier" || family == "nurbs", "{row}");
        // A rational Bézier curve is one segment, the NURBS curve four spans.
        let segments = if family == "rational_bezier" { 1 } else { 4 };
        assert_eq!(
            row["samples_per_curve"].as_u64(),
            Some(8 * segments),
            "{row}"
        );
        for key in [
            "cpu_f64_one_thread_samples_per_s",
            "gpu_compute_wall_samples_per_s",
            "gpu_write_limit_samples_per_s",
        ] {
            assert!(row[key].as_f64().is_some_and(|v| v > 0.0), "{key}: {row}");
        }
    }
}

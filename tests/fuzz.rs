//! Structured fuzzing of every input path: valid scenes and solve requests mutated field by
//! field (extreme, subnormal and non-finite numbers, wrong types, removed and duplicated
//! keys, arrays truncated or grown past the limits, families swapped), argument lists
//! for the CPU commands, PNG images (bits flipped, cut short, headers rewritten to other
//! sizes, depths and colour types) for `diff`, and the commands that write several files
//! or read option values (`schema --write` among obstacles, `regress` tolerances and report
//! directories, `bench --compare` files and thresholds), and figures: `export` to SVG and
//! PDF and `render` with text options over mutated scenes (rational weights at `1e±300`,
//! subnormals), views, tolerances and sizes — through the figure library in-process and
//! the command line. Invariants, for the library and the command line:
//!
//! * nothing panics (the CLI never exits 101 or by a signal);
//! * a command that exits 0 printed only finite numbers, and a loaded scene evaluates to
//!   finite points;
//! * a command that fails writes no output file; `schema --write` writes all or none;
//!   `regress` never touches the references when it fails;
//! * a scene that `solve -o` wrote passes `check`;
//! * a figure that is made is well-formed — its SVG parses as XML with every number
//!   finite, its PDF holds no `NaN` and `pdftoppm` reads every operator — and takes no more
//!   path pieces than the budget;
//! * every run finishes within the time bound, under a memory cap (`ulimit -v`).
//!
//! A bounded run (a fixed number of cases from a fixed seed) is part of the test suite;
//! `scripts/fuzz --minutes N` runs the same generators for N minutes from a fresh seed
//! (`SPLINESCOPE_FUZZ_SECONDS`, `SPLINESCOPE_FUZZ_SEED`), printing any failing input.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use serde_json::{Value, json};
use splinescope_core::geom::{Lower, ParamCurve};
use splinescope_core::rng::Rng;
use splinescope_scene::format::Scene;

mod common;

/// Numbers that have broken or could break derived computations.
const EXTREMES: [f64; 22] = [
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    2.2250738585072014e-308,
    1e-300,
    1e-12,
    0.5,
    1.0,
    -1.0,
    2.0,
    3.0,
    1e15,
    4294967296.0,
    1e20,
    1e38,
    3.4e38,
    1e300,
    1e308,
    -1e308,
    f64::MAX,
    f64::MIN,
];

fn manifest(p: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(p)
}

fn seeds(dir: &str) -> Vec<Value> {
    let mut out = Vec::new();
    let mut paths: Vec<_> = std::fs::read_dir(manifest(dir))
        .expect("seed dir")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    paths.sort();
    for p in paths {
        let text = std::fs::read_to_string(&p).expect("seed");
        out.push(serde_json::from_str(&text).expect("seeds are JSON"));
    }
    out
}

/// Every path (as a list of steps) to a value in `v`.
#[derive(Clone, Debug)]
enum Step {
    Key(String),
    Index(usize),
}

fn paths(v: &Value, prefix: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    out.push(prefix.clone());
    match v {
        Value::Array(a) => {
            for (i, item) in a.iter().enumerate() {
                prefix.push(Step::Index(i));
                paths(item, prefix, out);
                prefix.pop();
            }
        }
        Value::Object(m) => {
            for (k, item) in m {
                prefix.push(Step::Key(k.clone()));
                paths(item, prefix, out);
                prefix.pop();
            }
        }
        _ => {}
    }
}

fn at<'a>(v: &'a mut Value, path: &[Step]) -> &'a mut Value {
    let mut cur = v;
    for s in path {
        cur = match s {
            Step::Key(k) => cur.get_mut(k.as_str()).expect("path exists"),
            Step::Index(i) => cur.get_mut(*i).expect("path exists"),
        };
    }
    cur
}

fn extreme(rng: &mut Rng) -> f64 {
    EXTREMES[rng.int(0, EXTREMES.len() - 1)] * if rng.unit() < 0.2 { -1.0 } else { 1.0 }
}

/// One mutation of `doc`; returns the text (which may hold non-JSON `NaN` literals).
fn mutate(doc: &Value, rng: &mut Rng) -> String {
    let mut v = doc.clone();
    let rounds = 1 + rng.int(0, 2);
    let mut nan_literal = false;
    for _ in 0..rounds {
        let mut all = Vec::new();
        paths(&v, &mut Vec::new(), &mut all);
        let path = all[rng.int(0, all.len() - 1)].clone();
        let target = at(&mut v, &path);
        match rng.int(0, 11) {
            0..=3 => {
                // A number somewhere at or below: an extreme value.
                *target = json!(extreme(rng));
            }
            4 => *target = json!(rng.range(-10.0, 10.0)),
            5 => {
                *target = [
                    json!(null),
                    json!(true),
                    json!("x"),
                    json!([]),
                    json!({}),
                    json!("clamped_uniform"),
                    json!(-1),
                    json!(f64::MAX),
                ][rng.int(0, 7)]
                .clone();
            }
            6 => {
                if let Value::Array(a) = target
                    && !a.is_empty()
                {
                    let keep = rng.int(0, a.len() - 1);
                    a.truncate(keep);
                }
            }
            7 => {
                if let Value::Array(a) = target
                    && !a.is_empty()
                {
                    // Grow: duplicate items, sometimes past the degree limit.
                    let grow = if rng.unit() < 0.1 {
                        1001
                    } else {
                        rng.int(1, 40)
                    };
                    let item = a[rng.int(0, a.len() - 1)].clone();
                    for _ in 0..grow {
                        a.push(item.clone());
                    }
                }
            }
            8 => {
                if let Value::Object(m) = target
                    && !m.is_empty()
                {
                    let keys: Vec<String> = m.keys().cloned().collect();
                    m.remove(&keys[rng.int(0, keys.len() - 1)]);
                }
            }
            9 => {
                if let Value::Object(m) = target {
                    let family = [
                        "bezier",
                        "modified_bezier",
                        "interpolation",
                        "bspline",
                        "nubmp",
                    ][rng.int(0, 4)];
                    if m.contains_key("type") {
                        m.insert("type".into(), json!(family));
                    } else if m.contains_key("order") {
                        m.insert("order".into(), json!(rng.int(0, 70)));
                    } else {
                        m.insert("t".into(), json!(extreme(rng)));
                    }
                }
            }
            10 => {
                if let Value::Array(a) = target
                    && a.len() >= 2
                    && a.iter().all(Value::is_number)
                {
                    // Knots or parameters: make two equal or out of order.
                    let i = rng.int(0, a.len() - 2);
                    a[i + 1] = if rng.unit() < 0.5 {
                        a[i].clone()
                    } else {
                        json!(a[i].as_f64().unwrap_or(0.0) - 5e-324)
                    };
                }
            }
            _ => {
                if target.is_number() {
                    nan_literal = true;
                    *target = json!(123_456.789_f64);
                }
            }
        }
    }
    let text = serde_json::to_string(&v).expect("serialise");
    if nan_literal {
        let word = ["NaN", "Infinity", "-Infinity"][rng.int(0, 2)];
        text.replacen("123456.789", word, 1)
    } else {
        text
    }
}

/// Duplicates a key in the text's first object that has one (JSON allows writing it).
fn duplicate_a_key(text: &str) -> Option<String> {
    let i = text.find("\"points\":")?;
    Some(format!(
        "{}\"points\":[[0,0],[1,1]],{}",
        &text[..i],
        &text[i..]
    ))
}

/// Runs the CLI under a time bound and a memory cap.
fn run_bounded(args: &[String], limit: Duration) -> (Output, Duration) {
    let start = Instant::now();
    let mut cmd = Command::new("sh");
    // 8 GiB of address space: far above any documented limit's need, far below the
    // machine's memory.
    cmd.arg("-c")
        .arg("ulimit -v 8388608; exec timeout -s KILL \"$0\" \"$@\"")
        .arg(format!("{}", limit.as_secs().max(1)))
        .arg(env!("CARGO_BIN_EXE_splinescope"))
        .args(args);
    let out = cmd.output().expect("run");
    (out, start.elapsed())
}

/// Finds a non-finite number in printed JSON, as the invariant requires there is none.
fn non_finite_in(stdout: &str) -> Option<String> {
    let v: Value = serde_json::from_str(stdout).ok()?;
    fn walk(v: &Value, at: &str) -> Option<String> {
        match v {
            Value::Number(n) if n.as_f64().is_none_or(|x| !x.is_finite()) => Some(at.into()),
            Value::Array(a) => a
                .iter()
                .enumerate()
                .find_map(|(i, x)| walk(x, &format!("{at}[{i}]"))),
            Value::Object(m) => m.iter().find_map(|(k, x)| walk(x, &format!("{at}.{k}"))),
            _ => None,
        }
    }
    walk(&v, "")
}

/// The names in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut n: Vec<String> = std::fs::read_dir(dir)
        .map(|d| {
            d.filter_map(Result::ok)
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    n.sort();
    n
}

#[cfg(unix)]
fn set_mode(path: &Path, mode: u32) {
    use std::os::unix::fs::PermissionsExt;
    if std::fs::symlink_metadata(path).is_ok_and(|m| m.is_file()) {
        let _ = std::fs::set_permissions(path, std::fs::Permissions::from_mode(mode));
    }
}

#[cfg(not(unix))]
fn set_mode(_: &Path, _: u32) {}

#[cfg(unix)]
fn symlink(to: &Path, at: &Path) {
    std::os::unix::fs::symlink(to, at).expect("symlink");
}

#[cfg(not(unix))]
fn symlink(_: &Path, _: &Path) {}

/// Seed images for the image cases: 8-bit RGBA (the first, also the comparison's other
/// side), 16-bit RGB, a palette image and 8-bit grey.
fn image_seeds() -> Vec<Vec<u8>> {
    let mut rgba = splinescope_image::RgbaImage::filled(6, 5, [30, 60, 90, 255]);
    rgba.data[7] = 200;
    let first = rgba.png_bytes(Path::new("seed.png")).expect("encode seed");
    let palette = [0, 0, 0, 255, 0, 0, 0, 255, 0, 255, 255, 255];
    vec![
        first,
        common::encode_png(
            (6, 5),
            png::ColorType::Rgb,
            png::BitDepth::Sixteen,
            &[0x42; 6 * 5 * 6],
            None,
        ),
        common::encode_png(
            (6, 5),
            png::ColorType::Indexed,
            png::BitDepth::Eight,
            &[1, 2, 3, 0, 1, 2].repeat(5),
            Some((&palette, &[])),
        ),
        common::encode_png(
            (6, 5),
            png::ColorType::Grayscale,
            png::BitDepth::Eight,
            &[128; 30],
            None,
        ),
    ]
}

struct Fuzz {
    rng: Rng,
    dir: PathBuf,
    failures: Vec<String>,
    cases: usize,
    /// Runs that succeeded, failed cleanly (1) or were refused as arguments (2).
    exits: [usize; 3],
    /// Figures the command line wrote and that were read back.
    figures: usize,
}

impl Fuzz {
    fn fail(&mut self, what: String) {
        eprintln!("FUZZ FAILURE: {what}");
        self.failures.push(what);
    }

    /// The library side: loading never panics; a loaded scene evaluates and lowers to
    /// finite values; inspect's report holds no non-finite number.
    fn library(&mut self, text: &str, case: &str) {
        let result = std::panic::catch_unwind(|| -> Result<(), String> {
            let Ok(scene) = splinescope_scene::format::from_json_str(text) else {
                return Ok(());
            };
            for (i, c) in scene.curves.iter().enumerate() {
                let (a, b) = c.curve.domain();
                for t in [a, 0.5 * a + 0.5 * b, b] {
                    let p = c.curve.eval(t);
                    if !p.is_finite() {
                        return Err(format!("curves[{i}] at t = {t:e}: {p}"));
                    }
                }
                for s in c.curve.lower() {
                    if !s.bezier.points().iter().all(|p| p.is_finite()) {
                        return Err(format!("curves[{i}]: a lowered point is not finite"));
                    }
                }
                if c.curve.control_points().len() <= 200
                    && let Ok(report) =
                        splinescope_present::inspect::curve_report(i, c.name.as_deref(), &c.curve)
                    && let Some(at) =
                        non_finite_in(&serde_json::to_string(&report).unwrap_or_default())
                {
                    return Err(format!("inspect curves[{i}]: non-finite at {at}"));
                }
            }
            Ok(())
        });
        match result {
            Ok(Ok(())) => {}
            Ok(Err(e)) => self.fail(format!("{case}: {e}\ninput: {text}")),
            Err(_) => self.fail(format!("{case}: the library panicked\ninput: {text}")),
        }
    }

    /// The command line side for one argument list: no panic or signal, finite output on
    /// success, no output file on failure, within the time bound.
    fn cli(&mut self, args: Vec<String>, output: Option<&Path>, case: &str, input: &str) -> Output {
        if let Some(o) = output {
            let _ = std::fs::remove_file(o);
        }
        let (out, took) = run_bounded(&args, Duration::from_secs(30));
        let stdout = String::from_utf8_lossy(&out.stdout);
        let stderr = String::from_utf8_lossy(&out.stderr);
        let show = || {
            format!(
                "{case}: splinescope {}\ninput: {input}\nstderr: {stderr}",
                args.join(" ")
            )
        };
        if let Some(c @ 0..=2) = out.status.code() {
            self.exits[c as usize] += 1;
        }
        match out.status.code() {
            Some(0) => {
                if let Some(at) = non_finite_in(&stdout) {
                    self.fail(format!(
                        "exit 0 with a non-finite number at {at}: {}",
                        show()
                    ));
                }
                // Outside quoted text: a curve's name (an SVG id, a DXF layer) may
                // spell "NaN" without any number being one.
                let unquoted: String = stdout.split('"').step_by(2).collect::<Vec<_>>().join(" ");
                if unquoted.contains("NaN") || unquoted.contains("inf,") {
                    self.fail(format!("exit 0 printing NaN/inf: {}", show()));
                }
            }
            Some(1 | 2) => {
                if stderr.contains("panicked") {
                    self.fail(format!("panic: {}", show()));
                }
                if let Some(o) = output
                    && o.exists()
                {
                    self.fail(format!("failed but wrote {}: {}", o.display(), show()));
                }
            }
            other => self.fail(format!(
                "exit {other:?} (panic, signal, time or memory bound): {}",
                show()
            )),
        }
        if took > Duration::from_secs(30) {
            self.fail(format!("took {took:?}: {}", show()));
        }
        out
    }

    fn scene_case(&mut self, seeds: &[Value], requests: &[Value]) {
        let seed = &seeds[self.rng.int(0, seeds.len() - 1)];
        let mut text = mutate(seed, &mut self.rng);
        if self.rng.unit() < 0.05
            && let Some(t) = duplicate_a_key(&text)
        {
            text = t;
        }
        let case = format!("scene case {}", self.cases);
        self.library(&text, &case);
        let path = self.dir.join("scene.json");
        std::fs::write(&path, &text).expect("write case");
        let p = path.to_string_lossy().into_owned();
        let s = |x: &str| x.to_owned();
        let command = self.rng.int(0, 4);
        match command {
            4 => {
                // An operation that makes curves (offsets above all: a new path through
                // every family's lowering), its result checked.
                let value =
                    ["0.5", "-0.25", "1e-9", "1e9", "0", "NaN", "-1e300"][self.rng.int(0, 6)];
                let tolerance = ["1e-3", "1e-9", "1", "1e300", "0"][self.rng.int(0, 4)];
                let out = self.dir.join("op.json");
                let mut args = vec![s("op"), p];
                match self.rng.int(0, 3) {
                    0 => args.extend([s("--offset"), s(value), s("--tolerance"), s(tolerance)]),
                    1 => args.extend([
                        s("--offset"),
                        s(value),
                        s("--tolerance"),
                        s(tolerance),
                        s("--caps"),
                        s(["butt", "round", "square"][self.rng.int(0, 2)]),
                        s("--join"),
                        s(["round", "miter", "bevel"][self.rng.int(0, 2)]),
                    ]),
                    2 => args.extend([
                        s("--offset"),
                        s(value),
                        s("--tolerance"),
                        s(tolerance),
                        s("--trim"),
                    ]),
                    _ => args.extend([s("--to-cubics"), s(tolerance)]),
                }
                args.extend([s("-o"), out.to_string_lossy().into_owned()]);
                self.cli(args, Some(&out), &case, &text);
                if out.exists() {
                    let (checked, _) = run_bounded(
                        &[s("check"), out.to_string_lossy().into_owned()],
                        Duration::from_secs(30),
                    );
                    // The input may already be beyond the GPU's range; anything else
                    // refused is a bad scene written.
                    let stderr = String::from_utf8_lossy(&checked.stderr);
                    if !checked.status.success() && !stderr.contains("not drawable on the GPU") {
                        self.fail(format!(
                            "{case}: op wrote a scene that check fails on: {stderr}\ninput: {text}"
                        ));
                    }
                }
            }
            0 => {
                self.cli(vec![s("check"), p], None, &case, &text);
            }
            1 => {
                let n = ["2", "3", "17"][self.rng.int(0, 2)];
                let mut args = vec![s("eval"), p, s("--samples"), s(n)];
                if self.rng.unit() < 0.5 {
                    args.push(s("--derivatives"));
                    args.push(s(["1", "2"][self.rng.int(0, 1)]));
                }
                self.cli(args, None, &case, &text);
            }
            2 => {
                self.cli(vec![s("inspect"), p], None, &case, &text);
            }
            _ => {
                let req = mutate(
                    &requests[self.rng.int(0, requests.len() - 1)],
                    &mut self.rng,
                );
                let rp = self.dir.join("request.json");
                std::fs::write(&rp, &req).expect("write request");
                let out = self.dir.join("solved.json");
                self.cli(
                    vec![
                        s("solve"),
                        p,
                        rp.to_string_lossy().into_owned(),
                        s("-o"),
                        out.to_string_lossy().into_owned(),
                    ],
                    Some(&out),
                    &case,
                    &format!("{text}\nrequest: {req}"),
                );
                if out.exists() {
                    let (checked, _) = run_bounded(
                        &[s("check"), out.to_string_lossy().into_owned()],
                        Duration::from_secs(30),
                    );
                    if !checked.status.success() {
                        self.fail(format!(
                            "{case}: solve wrote a scene that check refuses: {}\ninput: {text}\nrequest: {req}",
                            String::from_utf8_lossy(&checked.stderr)
                        ));
                    }
                }
            }
        }
    }

    fn argument_case(&mut self) {
        let scenes = [
            "scenes/gallery.json",
            "scenes/bsplines.json",
            "scenes/paper001_fig1.json",
        ];
        let scene = manifest(scenes[self.rng.int(0, 2)])
            .to_string_lossy()
            .into_owned();
        let number = |rng: &mut Rng| -> String {
            match rng.int(0, 4) {
                0 => format!("{:e}", extreme(rng)),
                1 => format!("{}", rng.range(-1.0, 2.0)),
                2 => ["NaN", "inf", "-inf", "", "abc", "1e400", "0x10", "-0"][rng.int(0, 7)].into(),
                3 => format!("{}", rng.int(0, 40)),
                _ => "0.5".into(),
            }
        };
        let mut args = vec![];
        match self.rng.int(0, 2) {
            0 => {
                args.push("eval".into());
                args.push(scene);
                if self.rng.unit() < 0.5 {
                    args.push("--samples".into());
                    args.push(
                        ["0", "1", "2", "100", "10000001", "-3", "4294967296", "x"]
                            [self.rng.int(0, 7)]
                        .into(),
                    );
                } else {
                    let k = self.rng.int(1, 4);
                    let list: Vec<String> = (0..k).map(|_| number(&mut self.rng)).collect();
                    args.push("--params".into());
                    args.push(list.join(","));
                }
                if self.rng.unit() < 0.3 {
                    args.push("--curve".into());
                    args.push(number(&mut self.rng));
                }
            }
            1 => {
                args.push("inspect".into());
                args.push(scene);
                args.push("--tau".into());
                args.push(number(&mut self.rng));
            }
            _ => {
                args.push("check".into());
                args.push(
                    [
                        scene.as_str(),
                        "/dev/null",
                        "/nonexistent.json",
                        env!("CARGO_MANIFEST_DIR"),
                    ][self.rng.int(0, 3)]
                    .into(),
                );
            }
        }
        let case = format!("argument case {}", self.cases);
        self.cli(args, None, &case, "(arguments only)");
    }

    /// Images: valid PNGs with bits flipped, cut short, or their header rewritten to
    /// another size, depth or colour type (its CRC made right, so the decoder believes
    /// it), compared by `diff` — the reader `regress` uses for its references too.
    fn image_case(&mut self, seeds: &[Vec<u8>]) {
        let good = &seeds[0];
        let mut png = seeds[self.rng.int(0, seeds.len() - 1)].clone();
        let fix_ihdr_crc = |png: &mut Vec<u8>| {
            if png.len() >= 33 {
                let crc = common::crc32(&png[12..29]);
                png[29..33].copy_from_slice(&crc.to_be_bytes());
            }
        };
        match self.rng.int(0, 3) {
            0 => {
                for _ in 0..self.rng.int(1, 8) {
                    let i = self.rng.int(0, png.len() - 1);
                    png[i] ^= 1 << self.rng.int(0, 7);
                }
            }
            1 => {
                let n = self.rng.int(0, png.len() - 1);
                png.truncate(n);
            }
            2 => {
                let dims = [
                    0_u32,
                    1,
                    2,
                    3,
                    255,
                    8192,
                    65_535,
                    100_000,
                    1 << 31,
                    u32::MAX,
                ];
                let w = dims[self.rng.int(0, dims.len() - 1)];
                let h = dims[self.rng.int(0, dims.len() - 1)];
                png[16..20].copy_from_slice(&w.to_be_bytes());
                png[20..24].copy_from_slice(&h.to_be_bytes());
                fix_ihdr_crc(&mut png);
            }
            _ => {
                png[24] = [1, 2, 4, 8, 16, 7][self.rng.int(0, 5)];
                png[25] = [0, 2, 3, 4, 6, 5][self.rng.int(0, 5)];
                png[28] = [0, 1, 2][self.rng.int(0, 2)];
                fix_ihdr_crc(&mut png);
            }
        }
        let a = self.dir.join("image.png");
        let b = self.dir.join("good.png");
        std::fs::write(&a, &png).expect("write case");
        std::fs::write(&b, good).expect("write seed");
        let out = self.dir.join("diff.png");
        let (first, second) = if self.rng.unit() < 0.5 {
            (&a, &b)
        } else {
            (&b, &a)
        };
        let case = format!("image case {}", self.cases);
        let shown: String = png.iter().map(|x| format!("{x:02x}")).collect();
        let _ = std::fs::remove_file(&out);
        let result = self.cli(
            vec![
                "diff".into(),
                first.to_string_lossy().into_owned(),
                second.to_string_lossy().into_owned(),
                "-o".into(),
                out.to_string_lossy().into_owned(),
            ],
            None,
            &case,
            &format!("PNG bytes {shown}"),
        );
        // The diff image is written when both images were read and compared, whether they
        // match (exit 0) or differ (exit 1): never after a failure to read one.
        let compared = result.status.success()
            || String::from_utf8_lossy(&result.stderr).contains("beyond the tolerance");
        if out.exists() != compared {
            self.fail(format!(
                "{case}: diff {} the diff image: {}\nPNG bytes {shown}",
                if compared {
                    "compared but did not write"
                } else {
                    "failed but wrote"
                },
                String::from_utf8_lossy(&result.stderr)
            ));
        }
    }

    /// The commands that write several files or read option values: `schema --write`
    /// among read-only files, directories and dangling links (all or none); `regress`
    /// with random tolerances and report directories (the references are never touched);
    /// `bench --compare` with mutated earlier reports and thresholds. The GPU commands run
    /// with `--gpu-backend metal`, which has no adapter here, so that what is fuzzed is
    /// everything checked before a device opens.
    fn output_case(&mut self, bench_seed: &Value) {
        let case = format!("output case {}", self.cases);
        match self.rng.int(0, 2) {
            0 => {
                let dir = self.dir.join("schemas");
                let _ = std::fs::remove_dir_all(&dir);
                std::fs::create_dir_all(&dir).expect("schema dir");
                let names = [
                    "scene", "request", "report", "inspect", "analyze", "eval", "check",
                ];
                let mut obstacles = Vec::new();
                for name in names {
                    let target = dir.join(format!("{name}.schema.json"));
                    match self.rng.int(0, 7) {
                        0 => {
                            std::fs::write(&target, "old").expect("obstacle");
                            set_mode(&target, 0o444);
                        }
                        1 => std::fs::create_dir(&target).expect("obstacle"),
                        2 => symlink(&dir.join("nowhere"), &target),
                        _ => continue,
                    }
                    obstacles.push(name);
                }
                let before = listing(&dir);
                let (out, _) = run_bounded(
                    &[
                        "schema".into(),
                        "--write".into(),
                        dir.to_string_lossy().into_owned(),
                    ],
                    Duration::from_secs(30),
                );
                let after = listing(&dir);
                match out.status.code() {
                    Some(0) if obstacles.is_empty() && after.len() == names.len() => {}
                    Some(1) if !obstacles.is_empty() && after == before => {}
                    other => self.fail(format!(
                        "{case}: schema --write with obstacles {obstacles:?}: exit {other:?}, files before {before:?}, after {after:?}: {}",
                        String::from_utf8_lossy(&out.stderr)
                    )),
                }
                for name in names {
                    set_mode(&dir.join(format!("{name}.schema.json")), 0o644);
                }
            }
            1 => {
                let root = manifest("scenes").to_string_lossy().into_owned();
                let refs = self.dir.join("refs");
                let _ = std::fs::create_dir_all(&refs);
                std::fs::write(refs.join("kept.png"), b"blessed").expect("ref");
                let tolerance = [
                    "",
                    ",",
                    "channel=",
                    "channel=300",
                    "pixels=1%%",
                    "flip=nan",
                    "channel=4,channel=4",
                    "channel=24,pixels=0.1%",
                    "x=1",
                    " pixels = 5 % ",
                ][self.rng.int(0, 9)];
                let report = [
                    refs.clone(),
                    refs.join("r"),
                    self.dir.clone(),
                    manifest("scenes"),
                    manifest("scenes").join("r"),
                    self.dir.join("report"),
                    PathBuf::from("/dev/null"),
                    PathBuf::new(),
                ][self.rng.int(0, 7)]
                .to_string_lossy()
                .into_owned();
                let args = vec![
                    "regress".into(),
                    root,
                    refs.to_string_lossy().into_owned(),
                    "--bless".into(),
                    "--tolerance".into(),
                    tolerance.into(),
                    "--report".into(),
                    report,
                    "--gpu-backend".into(),
                    "metal".into(),
                ];
                let input = format!("{args:?}");
                self.cli(args, None, &case, &input);
                if std::fs::read(refs.join("kept.png")).ok().as_deref()
                    != Some(b"blessed".as_slice())
                    || listing(&refs).len() != 1
                {
                    self.fail(format!("{case}: regress touched the references: {input}"));
                }
            }
            _ => {
                let text = mutate(bench_seed, &mut self.rng);
                let file = self.dir.join("compare.json");
                std::fs::write(&file, &text).expect("compare file");
                let threshold =
                    ["10%", "", "5", "10%%", "nan", "-1", "1e3", "abc", "0%"][self.rng.int(0, 8)];
                self.cli(
                    vec![
                        "bench".into(),
                        "--curves".into(),
                        "10".into(),
                        "--samples".into(),
                        "4".into(),
                        "--compare".into(),
                        file.to_string_lossy().into_owned(),
                        "--threshold".into(),
                        threshold.into(),
                        "--gpu-backend".into(),
                        "metal".into(),
                    ],
                    None,
                    &case,
                    &text,
                );
            }
        }
    }
}

/// Seeds for the figure cases: rational curves with weights that leave the range of
/// ordinary numbers, tiny and huge coordinates.
fn figure_seeds() -> Vec<Value> {
    vec![
        json!({"version": 1, "curves": [
            {"type": "rational_bezier", "points": [[0, 0], [1, 2], [3, 0]], "weights": [1e300, 1e300, 2e300]},
            {"type": "rational_bezier", "points": [[0, 1], [2, 3], [4, 1], [5, 2]], "weights": [1e-300, 3e-300, 1e-300, 2e-300]},
            {"type": "nurbs", "points": [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0]], "weights": [1, 0.7, 1, 0.7, 1], "knots": [0, 0, 0, 0.5, 0.5, 1, 1, 1], "order": 3}
        ]}),
        json!({"version": 1, "curves": [
            {"type": "bezier", "name": "tiny", "points": [[0, 0], [1e-310, 2e-310], [3e-310, 0]]},
            {"type": "bezier", "name": "quintic", "points": [[0, 0], [1, 2], [3, 0], [4, 3], [5, -1]]}
        ]}),
        json!({"version": 1, "curves": [
            {"type": "bezier", "points": [[0, 0, 0], [1, 2, 1], [3, 0, 2], [4, 3, 0]]},
            {"type": "nurbs", "points": [[0, 0, 1], [1, 1, 0], [2, 0, 1]], "weights": [1, 1e300, 1], "knots": "clamped_uniform", "order": 3}
        ]}),
    ]
}

/// Well-formed SVG with every number finite, or what is wrong with it.
fn svg_problem(text: &str) -> Option<String> {
    let doc = match roxmltree::Document::parse(text) {
        Ok(d) => d,
        Err(e) => return Some(format!("not well-formed XML: {e}")),
    };
    for node in doc.descendants().filter(roxmltree::Node::is_element) {
        for attr in node.attributes() {
            if !matches!(
                attr.name(),
                "d" | "x" | "y" | "cx" | "cy" | "r" | "width" | "height" | "stroke-width"
            ) {
                continue;
            }
            for word in attr
                .value()
                .split(|c: char| (c.is_ascii_alphabetic() && c != 'e') || c == ' ')
                .filter(|w| !w.is_empty())
            {
                match word.parse::<f64>() {
                    Ok(v) if v.is_finite() => {}
                    _ => return Some(format!("{}={:?} holds {word:?}", attr.name(), attr.value())),
                }
            }
        }
    }
    None
}

/// Whether `pdftoppm` reads a PDF file without complaint (`None`), or what it said.
fn pdf_problem(path: &Path) -> Option<String> {
    // Bounded: a reader that hangs on a figure is a failure too.
    let out = Command::new("timeout")
        .args(["60", "pdftoppm", "-r", "4", "-png"])
        .arg(path)
        .arg(path.with_extension("page"))
        .output();
    match out {
        Err(e) => Some(format!(
            "pdftoppm did not run ({e}); install poppler-utils (scripts/test does)"
        )),
        Ok(o) if o.status.success() && o.stderr.is_empty() => None,
        Ok(o) => Some(format!(
            "pdftoppm: exit {:?}: {}",
            o.status.code(),
            String::from_utf8_lossy(&o.stderr)
        )),
    }
}

impl Fuzz {
    /// One figure case: a mutated scene with a random view, size, tolerance and text
    /// options, through the figure library (SVG, PDF, and the text `render` draws over its
    /// picture) and, for some, through `export` and `render`.
    fn figure_case(&mut self, seeds: &[Value]) {
        let mut doc = seeds[self.rng.int(0, seeds.len() - 1)].clone();
        if self.rng.unit() < 0.6 {
            let v = |rng: &mut Rng| {
                if rng.unit() < 0.5 {
                    extreme(rng)
                } else {
                    rng.range(-10.0, 10.0)
                }
            };
            let r = &mut self.rng;
            let view = if r.unit() < 0.7 {
                json!({"kind": "2d", "center": [v(r), v(r)], "height": v(r).abs()})
            } else {
                json!({"kind": "3d", "target": [v(r), v(r), v(r)], "distance": v(r).abs(),
                       "yaw_deg": v(r), "pitch_deg": v(r)})
            };
            doc["view"] = view;
        }
        let text = if self.rng.unit() < 0.8 {
            mutate(&doc, &mut self.rng)
        } else {
            doc.to_string()
        };
        let sizes = [1_u32, 2, 10, 16, 17, 50, 100, 320, 640, 1200];
        let (w, h) = (
            sizes[self.rng.int(0, sizes.len() - 1)],
            sizes[self.rng.int(0, sizes.len() - 1)],
        );
        let tolerances = [
            1e-6,
            1e-4,
            0.01,
            0.01,
            0.5,
            20.0,
            1e300,
            5e-324,
            1e-14,
            -1.0,
            f64::NAN,
        ];
        let tolerance = tolerances[self.rng.int(0, tolerances.len() - 1)];
        let flags = [
            self.rng.unit() < 0.5,
            self.rng.unit() < 0.5,
            self.rng.unit() < 0.3,
            self.rng.unit() < 0.3,
        ];
        let case = format!("figure case {}", self.cases);
        let input = format!(
            "{text}\nsize {w}×{h}, tolerance {tolerance:e}, labels/legend/axes/grid {flags:?}"
        );
        self.figure_library(&text, (w, h), tolerance, flags, &case, &input);
        if self.rng.unit() < 0.12 {
            self.figure_cli(&text, (w, h), tolerance, flags, &case, &input);
        }
    }

    fn figure_library(
        &mut self,
        text: &str,
        (w, h): (u32, u32),
        tolerance: f64,
        [labels, legend, axes, grid]: [bool; 4],
        case: &str,
        input: &str,
    ) {
        let started = Instant::now();
        let result = std::panic::catch_unwind(|| -> Result<(), String> {
            let Ok(scene) = splinescope_scene::format::from_json_str(text) else {
                return Ok(());
            };
            let text_opts = splinescope_figure::TextOptions {
                labels,
                legend,
                axes,
                grid,
            };
            let mut opts = splinescope_figure::FigureOptions::new(w, h).with_text(text_opts);
            opts.tolerance = tolerance;
            if let Ok(fig) = splinescope_figure::build(&scene, &opts) {
                let pieces: usize = fig
                    .items
                    .iter()
                    .map(|i| match i {
                        splinescope_figure::Item::Path { runs, .. } => {
                            runs.iter().map(|r| r.pieces.len()).sum()
                        }
                        _ => 0,
                    })
                    .sum();
                let budget = splinescope_io::limits::FIGURE_PIECES.default as usize;
                let overlays = scene
                    .curves
                    .iter()
                    .map(|c| 4 * c.curve.control_points().len())
                    .sum::<usize>();
                if pieces > budget + overlays {
                    return Err(format!("{pieces} pieces, over the budget {budget}"));
                }
                let svg = splinescope_figure::svg::write(&fig);
                if let Some(p) = svg_problem(&svg) {
                    return Err(format!("SVG: {p}"));
                }
                let pdf = splinescope_figure::pdf::write(&fig);
                let content = String::from_utf8_lossy(&pdf);
                if content.contains("NaN") || content.contains("inf ") {
                    return Err("PDF: a non-finite number".into());
                }
            }
            // `render`'s text over its picture: the same guides on a blank canvas.
            if u64::from(w) * u64::from(h) <= 1 << 22 {
                let mut data = vec![255_u8; (w * h * 4) as usize];
                let mut canvas = splinescope_figure::raster::Canvas {
                    data: &mut data,
                    width: w,
                    height: h,
                };
                let _ = splinescope_figure::raster::annotate(&mut canvas, &scene, text_opts);
            }
            Ok(())
        });
        match result {
            Ok(Ok(())) => {}
            Ok(Err(e)) => self.fail(format!("{case}: {e}\ninput: {input}")),
            Err(_) => self.fail(format!(
                "{case}: the figure library panicked\ninput: {input}"
            )),
        }
        if started.elapsed() > Duration::from_secs(10) {
            self.fail(format!(
                "{case}: the figure took {:?}\ninput: {input}",
                started.elapsed()
            ));
        }
    }

    fn figure_cli(
        &mut self,
        text: &str,
        (w, h): (u32, u32),
        tolerance: f64,
        [labels, legend, axes, grid]: [bool; 4],
        case: &str,
        input: &str,
    ) {
        let path = self.dir.join("figure-scene.json");
        std::fs::write(&path, text).expect("write case");
        let render = self.rng.unit() < 0.08;
        let ext = if render {
            "png"
        } else if self.rng.unit() < 0.5 {
            "svg"
        } else {
            "pdf"
        };
        let out = self.dir.join(format!("figure.{ext}"));
        let mut args: Vec<String> = vec![
            if render { "render" } else { "export" }.into(),
            path.to_string_lossy().into_owned(),
            "-o".into(),
            out.to_string_lossy().into_owned(),
            "--width".into(),
            w.to_string(),
            "--height".into(),
            h.to_string(),
        ];
        if !render {
            args.push("--tolerance".into());
            args.push(format!("{tolerance:e}"));
        }
        for (on, flag) in [labels, legend, axes, grid]
            .into_iter()
            .zip(["--labels", "--legend", "--axes", "--grid"])
        {
            if on {
                args.push(flag.into());
            }
        }
        let result = self.cli(args.clone(), Some(&out), case, input);
        if result.status.success() {
            let problem = match ext {
                "svg" => std::fs::read_to_string(&out)
                    .map_err(|e| e.to_string())
                    .map_or_else(Some, |t| svg_problem(&t)),
                "pdf" => pdf_problem(&out),
                _ => (!out.exists()).then(|| "no PNG written".to_owned()),
            };
            if let Some(p) = problem {
                self.fail(format!(
                    "{case}: splinescope {} wrote a bad figure: {p}\ninput: {input}",
                    args.join(" ")
                ));
            }
            self.figures += 1;
        }
    }
}

/// The files the import cases mutate (`tests/import_seeds/`: SVG, ASCII and binary DXF,
/// STEP), each with its extension.
fn import_seeds() -> Vec<(String, Vec<u8>)> {
    let dir = manifest("tests/import_seeds");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/import_seeds")
        .map(|e| e.expect("entry").path())
        .collect();
    files.sort();
    files
        .iter()
        .map(|f| {
            let ext = f
                .extension()
                .map(|e| e.to_string_lossy().into_owned())
                .unwrap_or_default();
            (ext, std::fs::read(f).expect("seed"))
        })
        .collect()
}

/// A textual mutation of an SVG file: cut short, a piece doubled or dropped, a number
/// made extreme, an element nested a thousand deep or referenced many times over, an
/// attribute value swapped for junk.
fn mutate_svg(text: &str, rng: &mut Rng) -> String {
    let mut t = text.to_owned();
    for _ in 0..rng.int(1, 3) {
        let n = t.len().max(1);
        let at = |rng: &mut Rng| {
            let mut i = rng.int(0, n - 1).min(t.len());
            while !t.is_char_boundary(i) {
                i -= 1;
            }
            i
        };
        match rng.int(0, 7) {
            0 => {
                let i = at(rng);
                t.truncate(i);
            }
            1 => {
                let (a, b) = (at(rng), at(rng));
                let (a, b) = (a.min(b), a.max(b));
                let piece = t[a..b].to_owned();
                t.insert_str(b, &piece);
            }
            2 => {
                let (a, b) = (at(rng), at(rng));
                t.replace_range(a.min(b)..a.max(b), "");
            }
            3 => {
                // A number made extreme.
                let digits: Vec<usize> = t
                    .char_indices()
                    .filter(|(_, c)| c.is_ascii_digit())
                    .map(|(i, _)| i)
                    .collect();
                if !digits.is_empty() {
                    let i = digits[rng.int(0, digits.len() - 1)];
                    let x = extreme(rng);
                    t.replace_range(i..=i, &format!("{x:e}"));
                }
            }
            4 => {
                let depth = [10, 300, 3000][rng.int(0, 2)];
                let inner = "<path d=\"M0 0 L1 1\" stroke=\"black\"/>";
                let nest = format!("{}{inner}{}", "<g>".repeat(depth), "</g>".repeat(depth));
                if let Some(i) = t.rfind("</svg>") {
                    t.insert_str(i, &nest);
                }
            }
            5 => {
                // References that multiply: each level uses the one below ten times.
                let mut bomb =
                    String::from("<g id=\"z0\"><path d=\"M0 0 L1 1\" stroke=\"red\"/></g>");
                for k in 1..=rng.int(1, 9) {
                    bomb += &format!(
                        "<g id=\"z{k}\">{}</g>",
                        format!("<use href=\"#z{}\"/>", k - 1).repeat(10)
                    );
                }
                if let Some(i) = t.rfind("</svg>") {
                    t.insert_str(i, &bomb);
                }
            }
            6 => {
                let junk = [
                    "\"NaN\"",
                    "\"-1\"",
                    "\"1e999\"",
                    "\"url(#nothing)\"",
                    "\"#z\"",
                    "\"\"",
                    "\"M\"",
                ];
                if let Some(i) = t.match_indices('"').map(|(i, _)| i).nth(rng.int(0, 40)) {
                    let end = t[i + 1..].find('"').map_or(t.len(), |e| i + 2 + e);
                    t.replace_range(i..end, junk[rng.int(0, junk.len() - 1)]);
                }
            }
            _ => {
                // A reference to itself.
                if let Some(i) = t.rfind("</svg>") {
                    t.insert_str(i, "<g id=\"loop\"><use href=\"#loop\"/></g>");
                }
            }
        }
    }
    t
}

/// The TrueType font the font cases mutate (Debian's fonts-dejavu-core, which
/// scripts/test installs).
fn font_seed() -> &'static [u8] {
    static FONT: std::sync::OnceLock<Vec<u8>> = std::sync::OnceLock::new();
    FONT.get_or_init(|| {
        std::fs::read("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf").unwrap_or_else(|e| {
            panic!("DejaVuSans.ttf: {e}; install fonts-dejavu-core (scripts/test does)")
        })
    })
}

/// A binary file mutated one to eight times: cut short, a byte flipped, or a run of
/// bytes set to 0xff (counts and offsets made huge).
fn mutate_bytes(mut b: Vec<u8>, rng: &mut Rng) -> Vec<u8> {
    for _ in 0..rng.int(1, 8) {
        let at = rng.int(0, b.len() - 1);
        match rng.int(0, 2) {
            0 => b.truncate(at.max(1)),
            1 => b[at] ^= rng.int(1, 255) as u8,
            _ => {
                let end = (at + rng.int(1, 8)).min(b.len());
                b[at..end].fill(0xff);
            }
        }
    }
    b
}

/// A small variable TrueType font (two axes, avar, sparse and intermediate gvar tuples, a
/// composite with moving offsets: `crates/python/tests/test_fonts_variable.py` builds it),
/// or `cff2`, a small variable CFF2 font (two axes, avar, five regions: built by
/// `crates/python/tests/test_fonts_cff2_variable.py`).
fn variable_font_seed(cff2: bool) -> Vec<u8> {
    let name = if cff2 {
        "tests/fonts/variable-cff2.otf"
    } else {
        "tests/fonts/variable.ttf"
    };
    std::fs::read(manifest(name)).expect(name)
}

impl Fuzz {
    /// One mutated font: cut short, bytes flipped or a run of them set to 0xff (counts
    /// and offsets made huge), read as a short text and as a few glyphs — the variable
    /// fonts (TrueType and CFF2) also at a random location, through their f64 outlines: a
    /// typed error or finite outlines, never a panic, in bounded time.
    fn font_case(&mut self) {
        let variable = self.rng.unit() < 0.4;
        let b = mutate_bytes(
            if variable {
                variable_font_seed(self.rng.unit() < 0.5)
            } else {
                font_seed().to_vec()
            },
            &mut self.rng,
        );
        let opts = if variable {
            splinescope_import::font::FontOptions {
                glyphs: Some(vec!["A".into(), "B".into(), "AB".into()]),
                variations: vec![
                    ("wght".into(), 100.0 + 800.0 * self.rng.unit()),
                    ("wdth".into(), 75.0 + 50.0 * self.rng.unit()),
                ],
                ..Default::default()
            }
        } else if self.rng.unit() < 0.5 {
            splinescope_import::font::FontOptions {
                text: Some("Ag&é".into()),
                ..Default::default()
            }
        } else {
            splinescope_import::font::FontOptions {
                glyphs: Some(vec!["gid3".into(), "a".into(), "gid300".into()]),
                ..Default::default()
            }
        };
        let start = Instant::now();
        let result = std::panic::catch_unwind(|| -> Result<(), String> {
            let Ok(imported) = splinescope_import::font::read(&b, "fuzz.ttf", &opts) else {
                return Ok(());
            };
            for (i, c) in imported.scene.curves.iter().enumerate() {
                if !c.curve.control_points().iter().all(|p| p.is_finite()) {
                    return Err(format!("curves[{i}]: a control point is not finite"));
                }
            }
            Ok(())
        });
        match result {
            Ok(Ok(())) => {}
            Ok(Err(e)) => self.fail(format!("font import: {e}")),
            Err(_) => self.fail("font import: the reader panicked".into()),
        }
        if start.elapsed() > Duration::from_secs(10) {
            self.fail(format!("font import took {:?}", start.elapsed()));
        }
    }

    /// One mutated points file (CSV, or JSON) through `splinescope fit`, with a random
    /// smoothing budget or tolerance (0, huge, tiny, negative): a clean refusal (nothing
    /// written) or a finite scene, never a panic, in bounded time.
    fn fit_case(&mut self) {
        let n = self.rng.int(1, 300);
        let json = self.rng.unit() < 0.3;
        let mut text = if json {
            String::from("[")
        } else {
            String::from("x,y\n")
        };
        for i in 0..n {
            let (x, y) = (self.rng.range(-10.0, 10.0), self.rng.range(-10.0, 10.0));
            if json {
                text.push_str(&format!("{}[{x}, {y}]", if i > 0 { ", " } else { "" }));
            } else {
                text.push_str(&format!("{x},{y}\n"));
            }
        }
        if json {
            text.push(']');
        }
        let text = mutate_svg(&text, &mut self.rng);
        let file = self.dir.join(if json {
            "fuzz-points.json"
        } else {
            "fuzz-points.csv"
        });
        let out = self.dir.join("fuzz-fit.json");
        if std::fs::write(&file, &text).is_err() {
            return;
        }
        let value = ["0", "1e-300", "1e300", "-1", "0.5", "NaN", "1e-9"][self.rng.int(0, 6)];
        let flag = if self.rng.unit() < 0.5 {
            "--smoothing"
        } else {
            "--tolerance"
        };
        let short: String = text.chars().take(300).collect();
        self.cli(
            vec![
                "fit".into(),
                file.display().to_string(),
                flag.into(),
                value.into(),
                "-o".into(),
                out.display().to_string(),
            ],
            Some(&out),
            "fit",
            &short,
        );
    }

    /// One mutated file of an imported format (SVG, DXF in ASCII and binary, STEP): read
    /// by the library (no panic, within the time bound, every curve finite) and by the
    /// command line (`check`, no panic or signal).
    fn import_case(&mut self, seeds: &[(String, Vec<u8>)]) {
        let (ext, seed) = &seeds[self.rng.int(0, seeds.len() - 1)];
        let binary = std::str::from_utf8(seed).is_err();
        let bytes: Vec<u8> = if binary {
            mutate_bytes(seed.clone(), &mut self.rng)
        } else {
            mutate_svg(&String::from_utf8_lossy(seed), &mut self.rng).into_bytes()
        };
        let text = String::from_utf8_lossy(&bytes).into_owned();
        let start = Instant::now();
        let result = std::panic::catch_unwind(|| -> Result<(), String> {
            let file = format!("fuzz.{ext}");
            let read = match ext.as_str() {
                "dxf" => splinescope_import::dxf::read(&bytes, &file),
                "step" => splinescope_import::step::read(&text, &file),
                _ => splinescope_import::svg::read(&text, &file),
            };
            let Ok(imported) = read else {
                return Ok(());
            };
            for (i, c) in imported.scene.curves.iter().enumerate() {
                let (a, b) = c.curve.domain();
                for t in [a, 0.5 * (a + b), b] {
                    if !c.curve.eval(t).is_finite() {
                        return Err(format!("curves[{i}] at t = {t}: not finite"));
                    }
                }
            }
            Ok(())
        });
        let short: String = text.chars().take(600).collect();
        match result {
            Ok(Ok(())) => {}
            Ok(Err(e)) => self.fail(format!("import: {e}\ninput: {short}")),
            Err(_) => self.fail(format!("import: the reader panicked\ninput: {short}")),
        }
        if start.elapsed() > Duration::from_secs(10) {
            self.fail(format!("import took {:?}\ninput: {short}", start.elapsed()));
        }
        if self.rng.unit() < 0.15 {
            self.font_case();
        }
        if self.rng.unit() < 0.1 {
            self.fit_case();
        }
        if self.rng.unit() < 0.2 {
            let file = self.dir.join(format!("fuzz.{ext}"));
            if std::fs::write(&file, &bytes).is_ok() {
                self.cli(
                    vec!["check".into(), file.display().to_string()],
                    None,
                    "import check",
                    &short,
                );
            }
        }
    }
}

#[test]
fn fuzz_every_input_path() {
    let seconds: u64 = std::env::var("SPLINESCOPE_FUZZ_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    let seed: u64 = std::env::var("SPLINESCOPE_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20_261_130);
    // The bounded run: a fixed number of cases; a long run: until the time is up.
    let bounded_cases = 1500;
    let scenes = seeds("scenes");
    let requests = seeds("scenes/requests");
    let images = image_seeds();
    let import_seeds = import_seeds();
    let bench_seed = json!({
        "family": "bezier", "curves": 10, "degree": 3, "samples_per_curve": 4,
        "cpu_f64_one_thread_samples_per_s": 1.5e8, "cpu_f64_all_cores_samples_per_s": 2.9e8,
        "gpu_compute_wall_samples_per_s": null, "frames_per_s_1920x1080": 20.5
    });
    // One directory per run: concurrent runs (a long one beside the test suite) must not
    // share their files.
    let dir = common::out_dir(&format!("fuzz/{}", std::process::id()));
    let mut f = Fuzz {
        rng: Rng::new(seed),
        dir,
        failures: Vec::new(),
        cases: 0,
        exits: [0; 3],
        figures: 0,
    };
    // `SPLINESCOPE_FUZZ_ONLY=figures` runs the figure cases alone (scripts/fuzz --only).
    let only_figures = std::env::var("SPLINESCOPE_FUZZ_ONLY").is_ok_and(|v| v == "figures");
    // `import`: the import cases alone.
    let only_import = std::env::var("SPLINESCOPE_FUZZ_ONLY").is_ok_and(|v| v == "import");
    let figure_seeds = figure_seeds();
    let mut figure_scenes = scenes.clone();
    figure_scenes.extend(figure_seeds);
    let start = Instant::now();
    loop {
        if seconds == 0 && f.cases >= bounded_cases {
            break;
        }
        if seconds > 0 && start.elapsed() > Duration::from_secs(seconds) {
            break;
        }
        let pick = f.rng.unit();
        if only_import {
            f.import_case(&import_seeds);
        } else if only_figures || pick < 0.3 {
            f.figure_case(&figure_scenes);
        } else if pick < 0.7 {
            f.scene_case(&scenes, &requests);
        } else if pick < 0.82 {
            f.argument_case();
        } else if pick < 0.88 {
            f.image_case(&images);
        } else if pick < 0.94 {
            f.import_case(&import_seeds);
        } else {
            f.output_case(&bench_seed);
        }
        f.cases += 1;
        if f.failures.len() >= 10 {
            break;
        }
    }
    eprintln!(
        "fuzz: {} cases from seed {seed} in {:.1} s ({} succeeded, {} failed cleanly, {} refused arguments; {} figures written and read back), {} failure(s)",
        f.cases,
        start.elapsed().as_secs_f64(),
        f.exits[0],
        f.exits[1],
        f.exits[2],
        f.figures,
        f.failures.len()
    );
    // A fuzzer whose inputs all fail to parse tests nothing: both outcomes must occur.
    assert!(
        f.cases < 50
            || only_figures
            || only_import
            || (f.exits[0] * 10 > f.cases && f.exits[1] * 10 > f.cases),
        "the mutations must produce both valid and invalid inputs: {:?}",
        f.exits
    );
    assert!(
        f.failures.is_empty(),
        "{} failure(s); the first:\n{}",
        f.failures.len(),
        f.failures[0]
    );
    assert!(f.cases >= bounded_cases.min(50), "ran {} cases", f.cases);
}

/// The mutation engine reaches what it must: extreme numbers, other types, truncated and
/// grown arrays, removed keys, and non-JSON literals.
#[test]
fn mutations_cover_every_kind() {
    let seed =
        json!({"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1, 1], [2, 0]]}]});
    let mut rng = Rng::new(1);
    let (mut nan, mut subnormal, mut grown, mut removed) = (false, false, false, false);
    for _ in 0..2000 {
        let t = mutate(&seed, &mut rng);
        nan |= t.contains("NaN") || t.contains("Infinity");
        subnormal |= t.contains("5e-324");
        grown |= t.matches('[').count() > 12;
        removed |= !t.contains("\"version\"") || !t.contains("\"points\"");
    }
    assert!(
        nan && subnormal && grown && removed,
        "{nan} {subnormal} {grown} {removed}"
    );
    assert!(
        duplicate_a_key(&seed.to_string()).is_some_and(|t| t.matches("\"points\"").count() == 2)
    );
    let parsed: Result<Scene, _> = splinescope_scene::format::from_json_str(
        &duplicate_a_key(&seed.to_string()).unwrap_or_default(),
    );
    assert!(parsed.is_err());
}

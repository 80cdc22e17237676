//! `splinescope regress` and `splinescope diff` end to end, as a user runs them in CI:
//! bless, pass, catch a moved control point with a diff image and report, accept it with
//! `--bless`, and bad input (missing, unreadable and mis-sized references, a scene that
//! fails to load, an empty directory, an unusable report directory).

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;
use splinescope_image::RgbaImage;

use common::{bin, run, text};

fn workspace(name: &str) -> PathBuf {
    let dir = common::out_dir("regress").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("scenes")).unwrap();
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    for scene in ["paper002_fig1.json", "bezier3d.json"] {
        std::fs::copy(src.join(scene), dir.join("scenes").join(scene)).unwrap();
    }
    dir
}

fn s(p: &Path) -> String {
    p.to_string_lossy().into_owned()
}

/// Moves control point 1 of the first curve of `scene` by `dy`.
fn move_point(scene: &Path, dy: f64) {
    let mut v: Value = serde_json::from_str(&std::fs::read_to_string(scene).unwrap()).unwrap();
    let y = v["curves"][0]["points"][1][1].as_f64().unwrap();
    v["curves"][0]["points"][1][1] = serde_json::json!(y + dy);
    std::fs::write(scene, serde_json::to_string_pretty(&v).unwrap()).unwrap();
}

fn json_of(out: &Output) -> Value {
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{e}: {}", text(out)))
}

fn statuses(v: &Value) -> Vec<(String, String)> {
    v["scenes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            (
                r["scene"].as_str().unwrap().to_owned(),
                r["status"].as_str().unwrap().to_owned(),
            )
        })
        .collect()
}

#[test]
fn regress_blesses_passes_catches_a_moved_point_and_accepts_it() {
    common::on_each_gpu("regress end to end", |backend| {
        let dir = workspace(&format!("e2e-{}", backend.name));
        let (scenes, refs, report) = (dir.join("scenes"), dir.join("refs"), dir.join("report"));
        let args = |extra: &[&str]| -> Output {
            let mut a = vec![
                "regress".to_owned(),
                s(&scenes),
                s(&refs),
                "--width".into(),
                "320".into(),
                "--height".into(),
                "240".into(),
                "--json".into(),
                "--gpu-backend".into(),
                backend.name.clone(),
            ];
            a.extend(extra.iter().map(|x| (*x).to_owned()));
            bin().args(&a).output().expect("run")
        };
        // No references yet: every scene is missing, the run fails and says how to fix it.
        let out = args(&[]);
        assert_eq!(out.status.code(), Some(1), "{}", text(&out));
        let missing = statuses(&json_of(&out));
        assert!(missing.iter().all(|(_, st)| st == "missing"), "{missing:?}");
        assert!(text(&out).contains("--bless"), "{}", text(&out));
        assert!(
            !refs.exists(),
            "a failing run without --bless writes nothing"
        );
        // --bless creates them.
        let out = args(&["--bless"]);
        assert!(out.status.success(), "{}", text(&out));
        for stem in ["paper002_fig1", "bezier3d"] {
            let r = RgbaImage::read_png(&refs.join(format!("{stem}.png"))).expect("blessed");
            assert_eq!((r.width, r.height), (320, 240));
        }
        // Unchanged scenes pass, with both metrics at zero.
        let out = args(&[]);
        assert!(out.status.success(), "{}", text(&out));
        let v = json_of(&out);
        for r in v["scenes"].as_array().unwrap() {
            assert_eq!(r["status"], "match", "{r}");
            assert_eq!(r["comparison"]["differing_pixels"], 0);
            assert_eq!(r["comparison"]["flip_mean"], 0.0);
        }
        // A moved control point is caught, with the report's images and page.
        move_point(&scenes.join("paper002_fig1.json"), 0.3);
        let out = args(&["--report", &s(&report)]);
        assert_eq!(out.status.code(), Some(1), "{}", text(&out));
        let v = json_of(&out);
        assert_eq!(
            statuses(&v),
            vec![
                ("bezier3d.json".into(), "match".into()),
                ("paper002_fig1.json".into(), "differs".into())
            ]
        );
        let c = &v["scenes"][1]["comparison"];
        assert!(c["differing_fraction"].as_f64().unwrap() > 0.001, "{c}");
        assert!(c["flip_mean"].as_f64().unwrap() > 0.0, "{c}");
        let diff = RgbaImage::read_png(&report.join("paper002_fig1.diff.png")).expect("diff");
        let red = diff
            .data
            .chunks_exact(4)
            .filter(|p| p == &[255, 0, 0, 255])
            .count();
        assert_eq!(
            red as u64,
            c["differing_pixels"].as_u64().unwrap(),
            "the diff marks exactly the differing pixels"
        );
        for f in ["actual", "reference", "flip"] {
            assert!(
                report.join(format!("paper002_fig1.{f}.png")).is_file(),
                "{f}"
            );
        }
        let page = std::fs::read_to_string(report.join("index.html")).expect("page");
        assert!(page.contains("paper002_fig1.diff.png") && page.contains("differs"));
        assert_eq!(v["report_page"], s(&report.join("index.html")));
        // --bless accepts the change; the next run passes and replaces the old report.
        let out = args(&["--bless"]);
        assert!(out.status.success(), "{}", text(&out));
        assert_eq!(
            statuses(&json_of(&out))[1],
            ("paper002_fig1.json".into(), "blessed".into())
        );
        let out = args(&["--report", &s(&report)]);
        assert!(out.status.success(), "{}", text(&out));
        assert!(
            std::fs::read_to_string(report.join("index.html"))
                .unwrap()
                .contains("2 match")
        );
    });
}

#[test]
fn regress_names_each_bad_input_and_still_compares_the_rest() {
    if common::gpus("regress bad input").is_empty() {
        return;
    }
    let dir = workspace("bad");
    let (scenes, refs) = (dir.join("scenes"), dir.join("refs"));
    let go = |extra: &[&str]| {
        let mut a = vec!["regress".to_owned(), s(&scenes), s(&refs)];
        a.extend(
            ["--width", "200", "--height", "150"]
                .iter()
                .map(|x| (*x).to_owned()),
        );
        a.extend(extra.iter().map(|x| (*x).to_owned()));
        bin().args(&a).output().expect("run")
    };
    assert!(go(&["--bless"]).status.success());
    // A scene that fails to load, a reference that is not a PNG, one of another size.
    std::fs::write(
        scenes.join("broken.json"),
        r#"{"version":1,"curves":[{"type":"bezier","points":[[0,0],[1,"x"]]}]}"#,
    )
    .unwrap();
    std::fs::write(refs.join("broken.png"), b"not a png").unwrap();
    std::fs::write(refs.join("bezier3d.png"), b"not a png").unwrap();
    RgbaImage::filled(10, 10, [255; 4])
        .write_png(&refs.join("paper002_fig1.png"))
        .unwrap();
    let report = dir.join("report");
    let out = go(&["--report", &s(&report)]);
    let all = text(&out);
    assert_eq!(out.status.code(), Some(1), "{all}");
    assert!(
        all.contains("broken.json: curves[0].points[1][1]"),
        "the scene and the value are named: {all}"
    );
    assert!(
        all.contains("bezier3d.png: not a valid PNG image"),
        "unreadable reference named: {all}"
    );
    assert!(
        all.contains("paper002_fig1.png: image size 200×150 differs from the reference's 10×10"),
        "{all}"
    );
    assert!(all.contains("3 error(s)"), "{all}");
    assert!(
        report.join("index.html").is_file(),
        "the report shows the errors too"
    );
    // An empty scenes directory, a references path that is a file, a report directory
    // that holds someone else's files or has no parent: clear errors, nothing written.
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let out = run(&["regress", &s(&empty), &s(&refs)]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        text(&out).contains("no scene files (*.json)"),
        "{}",
        text(&out)
    );
    let file = dir.join("file.txt");
    std::fs::write(&file, "x").unwrap();
    let out = run(&["regress", &s(&scenes), &s(&file)]);
    assert!(text(&out).contains("not a directory"), "{}", text(&out));
    let photos = dir.join("photos");
    std::fs::create_dir_all(&photos).unwrap();
    std::fs::write(photos.join("cat.jpg"), "x").unwrap();
    let out = go(&["--report", &s(&photos)]);
    assert!(
        text(&out).contains("is not an earlier splinescope report"),
        "{}",
        text(&out)
    );
    assert_eq!(
        std::fs::read_dir(&photos).unwrap().count(),
        1,
        "nothing added"
    );
    let out = go(&["--report", &s(&dir.join("no/such/dir"))]);
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out).contains("is not a directory"), "{}", text(&out));
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
    // --bless replaces the unreadable and mis-sized references, not the broken scene's.
    let out = go(&["--bless"]);
    assert_eq!(out.status.code(), Some(1), "the broken scene still fails");
    assert_eq!(
        RgbaImage::read_png(&refs.join("paper002_fig1.png"))
            .unwrap()
            .width,
        200
    );
    assert!(RgbaImage::read_png(&refs.join("bezier3d.png")).is_ok());
    assert_eq!(
        std::fs::read(refs.join("broken.png")).unwrap(),
        b"not a png"
    );
}

/// Refused before any GPU is opened: these need no adapter.
#[test]
fn a_report_directory_that_overlaps_the_references_or_scenes_is_refused() {
    let dir = workspace("overlap");
    let (scenes, refs) = (dir.join("scenes"), dir.join("refs"));
    std::fs::create_dir_all(&refs).unwrap();
    std::fs::write(refs.join("kept.png"), b"blessed earlier").unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(&refs, dir.join("refs-link")).unwrap();
    let mut cases = vec![
        (s(&refs), "is the references directory"),
        (format!("{}/", s(&refs)), "is the references directory"),
        (
            s(&refs.join("report")),
            "is inside the references directory",
        ),
        (s(&scenes), "is the scenes directory"),
        (s(&scenes.join("sub/..")), "is the scenes directory"),
        (s(&scenes.join("out")), "is inside the scenes directory"),
        (s(&dir), "contains the references directory"),
    ];
    if cfg!(unix) {
        cases.push((s(&dir.join("refs-link")), "is the references directory"));
    }
    for (report, says) in cases {
        let out = run(&[
            "regress",
            &s(&scenes),
            &s(&refs),
            "--bless",
            "--report",
            &report,
        ]);
        let all = text(&out);
        assert_eq!(out.status.code(), Some(1), "{report}: {all}");
        assert!(all.contains(says), "{report}: should say {says:?}: {all}");
        assert!(!all.contains("adapter"), "refused before the GPU: {all}");
        assert_eq!(
            std::fs::read(refs.join("kept.png")).unwrap(),
            b"blessed earlier",
            "{report}: the references are untouched"
        );
        assert_eq!(std::fs::read_dir(&refs).unwrap().count(), 1, "{report}");
    }
    // A first bless whose references directory does not exist yet: still refused.
    let fresh = dir.join("fresh-refs");
    let out = run(&[
        "regress",
        &s(&scenes),
        &s(&fresh),
        "--bless",
        "--report",
        &s(&fresh),
    ]);
    assert!(
        text(&out).contains("is the references directory"),
        "{}",
        text(&out)
    );
    assert!(!fresh.exists(), "nothing created");
}

#[test]
fn bless_and_report_are_written_all_or_none_and_report_links_are_followed() {
    if common::gpus("regress all or none").is_empty() {
        return;
    }
    let dir = workspace("all-or-none");
    let (scenes, refs) = (dir.join("scenes"), dir.join("refs"));
    let go = |extra: &[&str]| {
        let mut a = vec!["regress".to_owned(), s(&scenes), s(&refs)];
        a.extend(["--width", "200", "--height", "150"].map(str::to_owned));
        a.extend(extra.iter().map(|x| (*x).to_owned()));
        bin().args(&a).output().expect("run")
    };
    // One reference to replace is read-only: the other, missing one is not written either.
    std::fs::create_dir_all(&refs).unwrap();
    let ro = refs.join("bezier3d.png");
    RgbaImage::filled(3, 3, [9; 4]).write_png(&ro).unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o444)).unwrap();
        let out = go(&["--bless"]);
        assert_eq!(out.status.code(), Some(1), "{}", text(&out));
        assert!(
            text(&out).contains("read-only") && text(&out).contains("nothing was written"),
            "{}",
            text(&out)
        );
        assert!(!refs.join("paper002_fig1.png").exists(), "none written");
        std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o644)).unwrap();
    }
    let out = go(&["--bless"]);
    assert!(out.status.success(), "{}", text(&out));
    assert!(refs.join("paper002_fig1.png").is_file());
    // A report path that is a link to an earlier report: the link stays, its target is
    // replaced.
    let first = dir.join("report-1");
    assert!(go(&["--report", &s(&first)]).status.success());
    std::fs::write(first.join("stale.txt"), "from before").unwrap();
    #[cfg(unix)]
    {
        let link = dir.join("latest");
        std::os::unix::fs::symlink(&first, &link).unwrap();
        let out = go(&["--report", &s(&link)]);
        assert!(out.status.success(), "{}", text(&out));
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink(),
            "the link is still a link"
        );
        assert!(first.join("index.html").is_file());
        assert!(
            !first.join("stale.txt").exists(),
            "the earlier report was replaced"
        );
        let dangling = dir.join("dangling");
        std::os::unix::fs::symlink(dir.join("nowhere"), &dangling).unwrap();
        let out = go(&["--report", &s(&dangling)]);
        assert_eq!(out.status.code(), Some(1));
        assert!(
            text(&out).contains("symbolic link to nothing"),
            "{}",
            text(&out)
        );
    }
}

#[test]
fn a_reference_whose_header_declares_a_huge_image_is_an_error_not_an_abort() {
    if common::gpus("regress huge reference").is_empty() {
        return;
    }
    let dir = workspace("huge-ref");
    let (scenes, refs) = (dir.join("scenes"), dir.join("refs"));
    std::fs::create_dir_all(&refs).unwrap();
    let png = common::crafted_png_header(100_000, 100_000);
    for scene in ["paper002_fig1", "bezier3d"] {
        std::fs::write(refs.join(format!("{scene}.png")), &png).unwrap();
    }
    let out = run(&[
        "regress",
        &s(&scenes),
        &s(&refs),
        "--width",
        "200",
        "--height",
        "150",
    ]);
    let all = text(&out);
    assert_eq!(out.status.code(), Some(1), "{all}");
    assert!(
        all.contains("bezier3d.png: a 100000×100000 image")
            && all.contains("SPLINESCOPE_MAX_IMAGE_PIXELS"),
        "{all}"
    );
    assert!(all.contains("2 error(s)"), "{all}");
}

#[test]
fn diff_compares_two_images_and_writes_the_diff() {
    let dir = common::out_dir("regress").join("diff");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let a = RgbaImage::filled(40, 30, [255; 4]);
    let mut b = a.clone();
    // 12 pixels (1 %) turned black.
    for x in 0..12 {
        let i = (x * 4) as usize;
        b.data[i..i + 3].copy_from_slice(&[0, 0, 0]);
    }
    let (pa, pb) = (dir.join("a.png"), dir.join("b.png"));
    a.write_png(&pa).unwrap();
    b.write_png(&pb).unwrap();
    let out = run(&["diff", &s(&pa), &s(&pa), "--json"]);
    assert!(out.status.success(), "{}", text(&out));
    assert_eq!(json_of(&out)["differing_pixels"], 0);
    let d = dir.join("d.png");
    let flip = dir.join("f.png");
    let out = run(&[
        "diff",
        &s(&pb),
        &s(&pa),
        "-o",
        &s(&d),
        "--flip-map",
        &s(&flip),
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    let v = json_of(&out);
    assert_eq!(v["differing_pixels"], 12);
    assert_eq!(v["max_channel_diff"], 255);
    assert!((v["differing_fraction"].as_f64().unwrap() - 0.01).abs() < 1e-12);
    let diff = RgbaImage::read_png(&d).unwrap();
    assert_eq!(diff.pixel(0, 0), [255, 0, 0, 255]);
    assert_ne!(diff.pixel(20, 20), [255, 0, 0, 255]);
    assert!(RgbaImage::read_png(&flip).is_ok());
    // Two outputs, one impossible: neither is written.
    let _ = std::fs::remove_file(&d);
    let out = run(&[
        "diff",
        &s(&pb),
        &s(&pa),
        "-o",
        &s(&d),
        "--flip-map",
        &s(&dir.join("missing/f.png")),
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    assert!(text(&out).contains("nothing was written"), "{}", text(&out));
    assert!(!d.exists(), "the diff image was not written either");
    // A looser tolerance accepts the same pair.
    let out = run(&["diff", &s(&pb), &s(&pa), "--tolerance", "pixels=2%"]);
    assert!(out.status.success(), "{}", text(&out));
    // Bad input: another size, a file that is not a PNG, a missing file, a bad tolerance.
    RgbaImage::filled(4, 4, [0; 4])
        .write_png(&dir.join("small.png"))
        .unwrap();
    std::fs::write(dir.join("text.png"), "hello").unwrap();
    for (args, says) in [
        (
            vec!["diff", &s(&pa), &s(&dir.join("small.png"))],
            "image size 40×30 differs from the reference's 4×4".to_owned(),
        ),
        (
            vec!["diff", &s(&pa), &s(&dir.join("text.png"))],
            format!("{}: not a valid PNG image", s(&dir.join("text.png"))),
        ),
        (
            vec!["diff", &s(&dir.join("none.png")), &s(&pa)],
            s(&dir.join("none.png")),
        ),
        (
            vec!["diff", &s(&pa), &s(&pa), "--tolerance", "flip=3"],
            "flip=3: not between 0 and 1".to_owned(),
        ),
    ] {
        let out = run(&args);
        assert!(!out.status.success(), "{args:?}");
        assert!(text(&out).contains(&says), "{args:?}: {}", text(&out));
    }
}

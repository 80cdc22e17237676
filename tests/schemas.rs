//! The JSON Schemas in `docs/schemas/` are the ones generated from the types, and every
//! example validates against them: the scenes and requests in `scenes/` and in the docs'
//! code blocks, scenes as written back, and the output of `inspect`, `solve`, `eval` and
//! `check` on them. Documents the reader refuses for their shape are refused by the schema
//! too, so the schemas are not vacuous.

mod common;

use std::path::{Path, PathBuf};

use serde_json::Value;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn schema(name: &str) -> jsonschema::Validator {
    let path = root().join(format!("docs/schemas/{name}.schema.json"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let value: Value = serde_json::from_str(&text).expect("schema is JSON");
    jsonschema::validator_for(&value).unwrap_or_else(|e| panic!("{name}: not a schema: {e}"))
}

fn assert_valid(validator: &jsonschema::Validator, doc: &Value, what: &str) {
    let errors: Vec<String> = validator
        .iter_errors(doc)
        .map(|e| format!("{} at {}", e, e.instance_path()))
        .collect();
    assert!(
        errors.is_empty(),
        "{what} does not validate:\n{}",
        errors.join("\n")
    );
}

fn json_files(dir: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("dir entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    out.sort();
    out
}

fn read_json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The ```json blocks of a Markdown file.
fn json_blocks(path: &Path) -> Vec<Value> {
    let text = std::fs::read_to_string(path).expect("read doc");
    let mut blocks = Vec::new();
    let mut current: Option<String> = None;
    for line in text.lines() {
        match &mut current {
            None if line.trim() == "```json" => current = Some(String::new()),
            Some(block) if line.trim() == "```" => {
                blocks.push(
                    serde_json::from_str(block)
                        .unwrap_or_else(|e| panic!("{}: a json block: {e}", path.display())),
                );
                current = None;
            }
            Some(block) => {
                block.push_str(line);
                block.push('\n');
            }
            None => {}
        }
    }
    blocks
}

#[test]
fn shipped_schemas_are_the_generated_ones() {
    for (stem, generated) in splinescope::schemas::all() {
        let path = root().join(format!("docs/schemas/{stem}.schema.json"));
        let shipped = std::fs::read_to_string(&path).unwrap_or_default();
        assert_eq!(
            shipped,
            splinescope::schemas::to_text(&generated),
            "{} is out of date: run `splinescope schema --write docs/schemas`",
            path.display()
        );
    }
}

#[test]
fn every_example_scene_and_request_validates() {
    let scene = schema("scene");
    let request = schema("request");
    let scenes = json_files(&root().join("scenes"));
    assert!(scenes.len() >= 5, "{scenes:?}");
    for path in &scenes {
        let doc = read_json(path);
        assert_valid(&scene, &doc, &path.display().to_string());
        // Read and written back: still valid.
        let loaded = splinescope_scene::format::Scene::load(path).expect("example loads");
        let written: Value =
            serde_json::from_str(&splinescope_scene::format::to_json_string(&loaded)).unwrap();
        assert_valid(
            &scene,
            &written,
            &format!("{} written back", path.display()),
        );
    }
    let requests = json_files(&root().join("scenes/requests"));
    assert!(!requests.is_empty());
    for path in &requests {
        assert_valid(&request, &read_json(path), &path.display().to_string());
    }
    // The docs' examples: scenes have a "version", requests a "method".
    let mut seen = (0, 0);
    let mut docs = vec![root().join("README.md")];
    let mut guide: Vec<_> = std::fs::read_dir(root().join("docs"))
        .expect("docs/ is readable")
        .map(|entry| entry.expect("docs/ entry").path())
        .filter(|path| path.extension().is_some_and(|ext| ext == "md"))
        .collect();
    guide.sort();
    docs.extend(guide);
    for path in &docs {
        let doc = path.display();
        for block in json_blocks(path) {
            let is_request = match &block {
                Value::Array(items) => items.iter().all(|r| r.get("method").is_some()),
                other => other.get("method").is_some(),
            };
            if is_request {
                assert_valid(&request, &block, &format!("a request in {doc}"));
                seen.1 += 1;
            } else {
                assert_valid(&scene, &block, &format!("a scene in {doc}"));
                seen.0 += 1;
            }
        }
    }
    assert!(seen.0 >= 2 && seen.1 >= 1, "doc examples found: {seen:?}");
    // The built-in gallery as written.
    let gallery: Value = serde_json::from_str(&splinescope_scene::format::to_json_string(
        &splinescope_scene::format::gallery::gallery(),
    ))
    .unwrap();
    assert_valid(&scene, &gallery, "the gallery");
}

#[test]
fn documents_the_reader_refuses_for_their_shape_the_schema_refuses() {
    let scene = schema("scene");
    let request = schema("request");
    let bad_scenes = [
        r##"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1, 1]], "colour": "#fff"}]}"##,
        r#"{"version": 1, "curves": [{"type": "hermite", "points": [[0, 0], [1, 1]]}]}"#,
        r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1, 1, 2, 3]]}]}"#,
        r#"{"version": 2, "curves": []}"#,
        r#"{"version": 1, "curves": [], "samples": 1}"#,
        r#"{"version": 1, "curves": [{"type": "modified_bezier", "points": [[0, 0], [1, 1]], "v": [0, 1]}]}"#,
        r#"{"version": 1, "curves": [{"type": "bspline", "points": [[0, 0], [1, 1]], "knots": "uniform", "order": 2}]}"#,
        r#"{"version": 1, "name": null, "curves": []}"#,
        r#"{"version": 1, "curves": [], "view": {"kind": "2d", "center": [0, 0]}}"#,
    ];
    for text in bad_scenes {
        assert!(
            splinescope_scene::format::from_json_str(text).is_err(),
            "the reader accepts {text}"
        );
        let doc: Value = serde_json::from_str(text).unwrap();
        assert!(!scene.is_valid(&doc), "the schema accepts {text}");
    }
    let bad_requests = [
        r#"{"curve": 0, "method": "single_target"}"#,
        r#"{"curve": 0, "method": "teleport", "target": [0, 0]}"#,
        r#"{"curve": 0, "method": "project", "target": [0, 0], "t": 0.5}"#,
        r#"[{"curve": -1, "method": "project", "target": [0, 0]}]"#,
    ];
    let scene_doc = splinescope_scene::format::gallery::gallery();
    for text in bad_requests {
        assert!(
            splinescope_scene::request::apply_text(&scene_doc, text).is_err(),
            "the reader accepts {text}"
        );
        let doc: Value = serde_json::from_str(text).unwrap();
        assert!(!request.is_valid(&doc), "the schema accepts {text}");
    }
}

fn stdout_json(args: &[&str]) -> Value {
    let out = common::run(args);
    assert!(out.status.success(), "{args:?}: {}", common::text(&out));
    serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{args:?}: not JSON ({e}): {}", common::text(&out)))
}

#[test]
fn command_outputs_validate_against_their_schemas() {
    let inspect = schema("inspect");
    let report = schema("report");
    let eval = schema("eval");
    let check = schema("check");
    let analyze = schema("analyze");
    for path in json_files(&root().join("scenes")) {
        let p = path.to_str().unwrap();
        let analysis = stdout_json(&["analyze", p, "--json"]);
        assert!(!analysis["curves"].as_array().unwrap().is_empty());
        assert_valid(&analyze, &analysis, &format!("analyze {p}"));
        // With intersections for planar scenes (3D ones are refused, tested elsewhere).
        if analysis["curves"]
            .as_array()
            .unwrap()
            .iter()
            .all(|c| c["dimension"] == 2)
        {
            let with = stdout_json(&["analyze", p, "--json", "--intersections"]);
            assert!(with.get("intersections").is_some(), "{with}");
            assert_valid(&analyze, &with, &format!("analyze --intersections {p}"));
        }
        assert_valid(
            &inspect,
            &stdout_json(&["inspect", p]),
            &format!("inspect {p}"),
        );
        assert_valid(
            &check,
            &stdout_json(&["check", p, "--json"]),
            &format!("check {p}"),
        );
        assert_valid(
            &eval,
            &stdout_json(&[
                "eval",
                p,
                "--samples",
                "5",
                "--derivatives",
                "2",
                "--backend",
                "cpu",
            ]),
            &format!("eval {p}"),
        );
    }
    let nubmp = root().join("scenes/paper001_fig1.json");
    let at_tau = stdout_json(&["inspect", nubmp.to_str().unwrap(), "--tau", "0.4"]);
    assert!(at_tau["curves"][0].get("at_tau").is_some(), "{at_tau}");
    assert_valid(&inspect, &at_tau, "inspect --tau");
    let demo = root().join("scenes/solve_demo.json");
    for req in json_files(&root().join("scenes/requests")) {
        let out = stdout_json(&["solve", demo.to_str().unwrap(), req.to_str().unwrap()]);
        assert!(!out["reports"].as_array().unwrap().is_empty());
        assert_valid(&report, &out, &format!("solve {}", req.display()));
    }
    // Every method, including find_tau with and without apply, as one request document.
    let every = r#"[
        {"curve": 0, "method": "cubic_region", "target": [2, 3]},
        {"curve": 0, "method": "single_target", "target": [2, 2.5], "t": 0.4},
        {"curve": 0, "method": "tangent_kept", "target": [2, 2.2]},
        {"curve": 1, "method": "multi_target", "targets": [[7, 3], [9.5, 2.5]]},
        {"curve": 2, "method": "nubmp_find_tau", "group": 5, "target": [16.45, 1.75]},
        {"curve": 2, "method": "nubmp_find_tau", "group": 5, "target": [16.45, 1.75], "apply": true},
        {"curve": 2, "method": "project", "target": [17, 3]}
    ]"#;
    let req = common::out_dir("schemas").join("every_method.json");
    std::fs::write(&req, every).unwrap();
    let out = stdout_json(&["solve", demo.to_str().unwrap(), req.to_str().unwrap()]);
    assert_eq!(out["reports"].as_array().unwrap().len(), 7, "{out}");
    assert!(out["reports"][5].get("values").is_some(), "{out}");
    assert!(out["reports"][4].get("values").is_none(), "{out}");
    assert_valid(&report, &out, "every method");
}

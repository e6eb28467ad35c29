//! The Foxglove layout beside each case's MCAP file (`<case>.layout.json`).
//!
//! Requirements checked:
//! - every topic and message path the layout names exists in the MCAP file beside it, read
//!   back with the repository's MCAP reader: each plot series is a state channel holding
//!   that field, each 3D topic a channel of the file;
//! - the plot of the relative displacement overlays every participant: each engine run,
//!   the external program and the reference;
//! - a scene with geometry gets the 3D panel with every drawn run's scene and forces, and
//!   a file without a 3D view gets none;
//! - the layout's arrangement names exactly the panels it configures.

use std::collections::BTreeSet;

use serde_json::Value;

use rockslide::case::parse_case;
use rockslide::formats::{McapContents, read_mcap};
use rockslide::present::foxglove_layout::layout_path;
use rockslide::report::write_case_outputs;
use rockslide::suite::{CaseResult, run_case};

use crate::common::repo;

/// A message path `topic.field` split, the topic unquoted when it was quoted.
fn topic_and_field(path: &str) -> (String, String) {
    if let Some(rest) = path.strip_prefix('"') {
        let end = rest.find("\".").expect("a quoted topic ends with \".");
        let topic = rest[..end].replace("\\\"", "\"").replace("\\\\", "\\");
        return (topic, rest[end + 2..].to_string());
    }
    let dot = path.rfind('.').expect("a message path names a field");
    (path[..dot].to_string(), path[dot + 1..].to_string())
}

/// The panel ids a layout tree names.
fn panel_ids(tree: &Value, out: &mut BTreeSet<String>) {
    match tree {
        Value::String(id) => {
            out.insert(id.clone());
        }
        Value::Object(split) => {
            panel_ids(&split["first"], out);
            panel_ids(&split["second"], out);
        }
        other => panic!("a layout tree holds panel ids and splits, not {other}"),
    }
}

/// The case at `path` (its text edited by `edit`) run and written; its layout and MCAP
/// file read back, and the topics of the file.
fn written(path: &str, edit: impl Fn(String) -> String) -> (CaseResult, Value, McapContents) {
    let path = repo(path);
    let text = edit(std::fs::read_to_string(&path).unwrap());
    let result = run_case(parse_case(&path, &text).expect("case loads")).expect("case runs");
    let out = tempfile::tempdir().unwrap();
    let dir = write_case_outputs(&result, out.path()).unwrap();
    let mcap_file = dir.join(format!("{}.mcap", result.case.name));
    let layout_file = layout_path(&mcap_file);
    assert_eq!(
        layout_file,
        dir.join(format!("{}.layout.json", result.case.name))
    );
    let layout: Value = serde_json::from_slice(&std::fs::read(&layout_file).unwrap()).unwrap();
    let contents = read_mcap(&mcap_file).unwrap();
    (result, layout, contents)
}

/// Every plot series a state channel of the file holding its field, every 3D topic a
/// channel of the file, the arrangement naming exactly the configured panels; returns the
/// number of series.
fn check_against_file(layout: &Value, contents: &McapContents) -> usize {
    let topics: BTreeSet<&str> = contents.channels.iter().map(|c| c.topic.as_str()).collect();
    let config = layout["configById"].as_object().unwrap();
    let mut series = 0;
    for (id, panel) in config.iter().filter(|(id, _)| id.starts_with("Plot!")) {
        for p in panel["paths"].as_array().unwrap() {
            let (topic, field) = topic_and_field(p["value"].as_str().unwrap());
            assert!(topics.contains(topic.as_str()), "{id}: no channel {topic}");
            let state = contents
                .state(&topic)
                .unwrap_or_else(|| panic!("{topic}: no state"));
            assert!(state.has(&field), "{id}: {topic} has no field {field}");
            series += 1;
        }
    }
    let scene_channels = topics.iter().filter(|t| t.ends_with("/scene")).count();
    match config.get("3D!scene") {
        Some(panel) => {
            let listed = panel["topics"].as_object().unwrap();
            for topic in listed.keys() {
                assert!(topics.contains(topic.as_str()), "3D: no channel {topic}");
            }
            // every drawn run's scene and force arrows
            assert_eq!(listed.len(), 2 * scene_channels);
        }
        None => assert_eq!(scene_channels, 0, "a file with a 3D view has the 3D panel"),
    }
    let mut named = BTreeSet::new();
    panel_ids(&layout["layout"], &mut named);
    let configured: BTreeSet<String> = config.keys().cloned().collect();
    assert_eq!(named, configured);
    series
}

#[test]
fn the_layout_names_only_topics_and_fields_the_mcap_file_holds_and_overlays_every_participant() {
    // the worked external example with every engine: engines, an external program and
    // the exact reference in one file
    let (result, layout, contents) = written("examples/external/pepo-external.toml", |t| {
        t.replace("[engines.fe]\nvariants = [\"single\"]\n", "")
    });
    let series = check_against_file(&layout, &contents);
    let config = layout["configById"].as_object().unwrap();
    let labels: BTreeSet<String> = config["Plot!rel_disp"]["paths"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["label"].as_str().unwrap().to_string())
        .collect();
    let mut expected: BTreeSet<String> = result.runs.iter().map(|r| r.label()).collect();
    expected.insert("reference".to_string());
    assert_eq!(labels, expected);
    assert!(
        labels.iter().any(|l| l.starts_with("mycode/")),
        "{labels:?}"
    );
    for engine in rockslide::engine::ENGINE_IDS {
        let prefix = format!("{engine}/");
        assert!(
            labels.iter().any(|l| l.starts_with(&prefix)),
            "every engine plotted: {labels:?}"
        );
    }
    assert!(
        series > labels.len(),
        "more than one quantity plotted: {series}"
    );
}

#[test]
fn a_scene_with_geometry_gets_the_3d_panel_with_every_drawn_run() {
    let (result, layout, contents) = written("cases/rigid-sliding-block.toml", |t| t);
    check_against_file(&layout, &contents);
    let listed = layout["configById"]["3D!scene"]["topics"]
        .as_object()
        .expect("the rigid block has geometry: a 3D panel");
    for run in &result.runs {
        for suffix in ["scene", "forces"] {
            let topic = format!("/{}/{suffix}", run.label());
            assert!(listed.contains_key(&topic), "3D panel lacks {topic}");
        }
    }
}

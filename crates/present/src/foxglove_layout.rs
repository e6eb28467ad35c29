//! The Foxglove layout written beside a case's MCAP file (`<case>.layout.json`, imported
//! with "Import from file…" in Foxglove or Lichtblick): one plot per key quantity with
//! every participant that records it overlaid — each engine run, each external program
//! and the reference — and, for a scene with geometry, the 3D panel showing every run's
//! scene and force arrows. It names only topics and fields the MCAP file holds: it is
//! built from the same [`TraceLog`] the file is written from.
//!
//! A layout is JSON with `configById` (each panel's settings, by `Type!id`), `layout` (the
//! panels' arrangement, a binary tree of splits), `globalVariables`, `userNodes` and
//! `playbackConfig`.

use std::path::{Path, PathBuf};

use serde_json::{Map, Value, json};

use rockslide_core::error::Error;
use rockslide_core::io::write_atomically;
use rockslide_core::trace::{Quantity, q};
use rockslide_formats::TraceLog;
use rockslide_formats::scene3d::drawable;

/// The quantities plotted when a participant records them, in panel order: the motion,
/// the base's sliding and the forces the paper plots, then rocking and the second
/// horizontal direction of a 3D scene.
pub static KEY_QUANTITIES: [&Quantity; 9] = [
    &q::REL_DISP,
    &q::SLIDE,
    &q::RESISTANCE,
    &q::FORCE,
    &q::ROTATION,
    &q::UPLIFT,
    &q::REL_DISP_Y,
    &q::SLIDE_Y,
    &q::SLIDE_RESULTANT,
];

/// The layout file beside an MCAP file: `<stem>.layout.json`.
pub fn layout_path(mcap: &Path) -> PathBuf {
    mcap.with_extension("layout.json")
}

/// Write the layout of `log` beside the MCAP file `mcap`, atomically.
pub fn write_layout(log: &TraceLog, mcap: &Path) -> Result<(), Error> {
    let text = serde_json::to_string_pretty(&layout(log))
        .map_err(|e| Error::Other(format!("cannot serialise the Foxglove layout: {e}")))?;
    write_atomically(&layout_path(mcap), text.as_bytes())
}

/// A topic as a message path writes it: quoted when it holds characters other than
/// letters, digits, `_`, `/` and `-` (the viewers' unquoted topic syntax).
pub fn quote_topic(topic: &str) -> String {
    let plain = topic
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '/' | '-'));
    if plain {
        topic.to_string()
    } else {
        format!("\"{}\"", topic.replace('\\', "\\\\").replace('"', "\\\""))
    }
}

/// The layout of a log: its plots (and 3D panel) arranged, plots in a column on the left.
pub fn layout(log: &TraceLog) -> Value {
    let mut config = Map::new();
    let plots: Vec<String> = KEY_QUANTITIES
        .iter()
        .filter_map(|quantity| plot(log, quantity).map(|p| (quantity, p)))
        .map(|(quantity, p)| {
            let id = format!("Plot!{}", quantity.key);
            config.insert(id.clone(), p);
            id
        })
        .collect();
    let mut tree = stack(&plots, "column");
    if let Some(panel) = scene_panel(log) {
        let id = "3D!scene".to_string();
        config.insert(id.clone(), panel);
        tree = match tree {
            Some(plots) => Some(split(plots, Value::String(id), "row", 50.0)),
            None => Some(Value::String(id)),
        };
    }
    json!({
        "configById": config,
        "globalVariables": {},
        "userNodes": {},
        "playbackConfig": { "speed": 1.0 },
        "layout": tree.unwrap_or(Value::Null),
    })
}

/// The plot of `quantity`: one series per participant whose state records it, by label.
fn plot(log: &TraceLog, quantity: &Quantity) -> Option<Value> {
    let paths: Vec<Value> = log
        .runs
        .iter()
        .filter(|run| run.trace.has(quantity.key))
        .map(|run| {
            json!({
                "value": format!("{}.{}", quote_topic(&format!("/{}/state", run.label)), quantity.key),
                "label": run.label,
                "enabled": true,
                "timestampMethod": "receiveTime",
            })
        })
        .collect();
    if paths.is_empty() {
        return None;
    }
    Some(json!({
        "title": format!("{} ({})", quantity.label, quantity.unit),
        "paths": paths,
        "xAxisVal": "timestamp",
        "showLegend": true,
        "legendDisplay": "floating",
        "showXAxisLabels": true,
        "showYAxisLabels": true,
        "isSynced": true,
    }))
}

/// The 3D panel: every drawn run's scene and force arrows (their transforms are read
/// from the file by the panel itself), followed from the world frame.
fn scene_panel(log: &TraceLog) -> Option<Value> {
    log.geometry.as_ref()?;
    let mut topics = Map::new();
    for run in log.runs.iter().filter(|run| drawable(run.trace)) {
        for suffix in ["scene", "forces"] {
            topics.insert(
                format!("/{}/{suffix}", run.label),
                json!({ "visible": true }),
            );
        }
    }
    if topics.is_empty() {
        return None;
    }
    Some(json!({
        "followTf": "world",
        "followMode": "follow-pose",
        "scene": { "enableStats": false },
        "transforms": {},
        "topics": topics,
        "layers": {
            "grid": { "layerId": "foxglove.Grid", "visible": true, "frameId": "world", "size": 10, "divisions": 10 }
        },
        "cameraState": {
            "perspective": true,
            "distance": 8.0,
            "phi": 60.0,
            "thetaOffset": 45.0,
            "target": [0.0, 0.0, 0.0],
            "targetOffset": [0.0, 0.0, 0.0],
            "targetOrientation": [0.0, 0.0, 0.0, 1.0],
            "fovy": 45.0,
            "near": 0.01,
            "far": 5000.0
        },
    }))
}

/// Panels stacked along `direction` in equal shares: a balanced tree of splits.
fn stack(ids: &[String], direction: &str) -> Option<Value> {
    match ids {
        [] => None,
        [one] => Some(Value::String(one.clone())),
        _ => {
            let half = ids.len() / 2;
            let share = 100.0 * half as f64 / ids.len() as f64;
            Some(split(
                stack(&ids[..half], direction)?,
                stack(&ids[half..], direction)?,
                direction,
                share,
            ))
        }
    }
}

fn split(first: Value, second: Value, direction: &str, percent: f64) -> Value {
    json!({
        "first": first,
        "second": second,
        "direction": direction,
        "splitPercentage": percent,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn topics_are_quoted_only_when_the_unquoted_syntax_cannot_hold_them() {
        assert_eq!(
            quote_topic("/predictor-corrector/paper/state"),
            "/predictor-corrector/paper/state"
        );
        assert_eq!(quote_topic("/my code/x/state"), "\"/my code/x/state\"");
        assert_eq!(quote_topic("/a\"b.c/state"), "\"/a\\\"b.c/state\"");
    }

    #[test]
    fn panels_stack_as_a_balanced_tree_with_equal_shares() {
        let ids: Vec<String> = ["a", "b", "c"].iter().map(|s| s.to_string()).collect();
        let tree = stack(&ids, "column").unwrap();
        // a | (b | c): a takes 1/3, then b and c half each of the rest
        assert_eq!(tree["first"], "a");
        assert!((tree["splitPercentage"].as_f64().unwrap() - 100.0 / 3.0).abs() < 1e-12);
        assert_eq!(tree["second"]["first"], "b");
        assert_eq!(tree["second"]["splitPercentage"], 50.0);
        assert_eq!(stack(&[], "column"), None);
    }
}

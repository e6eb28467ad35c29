//! The run's log as `foxglove.Log` messages in JSON, with their JSON schema.

use serde_json::{Value, json};

use super::values::time_json;

/// A `foxglove.Log` message (levels: 2 info, 3 warning, 4 error).
pub fn log(ns: u64, level: u8, name: &str, message: &str) -> Value {
    json!({
        "timestamp": time_json(ns),
        "level": level,
        "message": message,
        "name": name,
        "file": "",
        "line": 0
    })
}

// The log's JSON schema is inline (no `$ref`), every object has `properties` and every
// field one concrete `type`: the subset Foxglove's JSON-schema reader accepts.

fn time_schema(d: &str) -> Value {
    json!({
        "type": "object", "title": "time", "description": d,
        "properties": {
            "sec": { "type": "integer", "minimum": 0 },
            "nsec": { "type": "integer", "minimum": 0, "maximum": 999_999_999 }
        }
    })
}

/// JSON schema of `foxglove.Log`.
pub fn log_schema() -> Value {
    json!({
        "title": "foxglove.Log",
        "description": "A log message",
        "type": "object",
        "properties": {
            "timestamp": time_schema("Timestamp of the log message (simulation time)"),
            "level": { "type": "integer", "description": "0 unknown, 1 debug, 2 info, 3 warning, 4 error, 5 fatal" },
            "message": { "type": "string" },
            "name": { "type": "string" },
            "file": { "type": "string" },
            "line": { "type": "integer", "minimum": 0 }
        },
        "required": ["timestamp", "level", "message", "name", "file", "line"]
    })
}

//! MCAP traces (docs/traces.md).
//!
//! Requirements checked:
//! - rockslide shall write one MCAP file per case run with one state channel per engine
//!   run and for the reference, whose values read back equal the CSV trace bit for bit;
//! - per-step channels (state, contacts) as ROS 2 definitions (`ros2msg`, each field's SI
//!   unit in a comment) and CDR messages, decoded here independently of the writer; the
//!   3D view as Foxglove's ROS 2 schemas in CDR (decoded here from the definition text the
//!   file carries), the log as JSON in Foxglove's JSON-schema subset; log time = simulation
//!   time in ns, zstd chunks, indexes and a summary;
//! - only the fields the trace has (no rotation for a sliding-only oscillator, no 3D
//!   channel for a scene without geometry);
//! - for scenes with geometry, `foxglove_msgs/msg/SceneUpdate` and
//!   `foxglove_msgs/msg/FrameTransforms` messages (one per frame: the ground's and the
//!   body's transform) whose transforms put the body where the trace says (checked against rigid-body
//!   kinematics computed here, not by the writer's code);
//! - the case file attached, engine settings, version and commit as metadata;
//! - a diverged run still leaves a readable file with the reason recorded.

use std::collections::BTreeMap;
use std::path::Path;

use rockslide::analysis::responses;
use rockslide::case::{Case, load_case, parse_case};
use rockslide::engine::{Run, RunStatus};
use rockslide::formats::{read_csv, read_mcap};
use rockslide::report::write_case_outputs;
use rockslide::suite::{CaseResult, run_case};
use rockslide::trace::{Trace, q};
use serde_json::Value;

/// Same f64, bit for bit (±∞ included); any NaN equals any NaN (a CSV spells every NaN
/// `NaN`, so its payload does not survive a CSV).
fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

fn assert_traces_equal(csv: &Trace, mcap: &Trace, what: &str) {
    let keys = |t: &Trace| t.channels.iter().map(|c| c.key).collect::<Vec<_>>();
    assert_eq!(keys(csv), keys(mcap), "{what}: fields");
    assert_eq!(csv.len(), mcap.len(), "{what}: rows");
    for i in 0..csv.len() {
        assert!(same(csv.time[i], mcap.time[i]), "{what}: time row {i}");
    }
    for (c, (a, b)) in csv
        .channels
        .iter()
        .zip(csv.columns.iter().zip(&mcap.columns))
    {
        for i in 0..a.len() {
            assert!(
                same(a[i], b[i]),
                "{what}: {} row {i}: csv {:e} mcap {:e}",
                c.key,
                a[i],
                b[i]
            );
        }
    }
}

/// The top-level `float64` field names of a ROS 2 message definition (the text above the
/// first dependency separator), in order; other field types are `None`.
fn ros2_fields(definition: &str) -> Vec<(Option<String>, String)> {
    definition
        .lines()
        .take_while(|l| !l.starts_with("==="))
        .map(|l| l.split('#').next().unwrap().trim())
        .filter(|l| !l.is_empty())
        .map(|l| {
            let mut words = l.split_whitespace();
            let (ty, name) = (words.next().unwrap(), words.next().unwrap());
            assert!(words.next().is_none(), "{l:?}: one type and one name");
            ((ty == "float64").then(|| name.to_string()), ty.to_string())
        })
        .collect()
}

/// A CDR message (little-endian plain CDR, as ROS 2 writes it) of the flat `float64`
/// definition `definition`, decoded here from the bytes: header 00 01 00 00, then 8-byte
/// little-endian values with no padding (all aligned to 8).
fn decode_cdr(definition: &str, data: &[u8]) -> Value {
    assert_eq!(&data[..4], &[0, 1, 0, 0], "little-endian CDR header");
    let fields = ros2_fields(definition);
    let mut v = serde_json::Map::new();
    let mut at = 4;
    for (name, ty) in &fields {
        match name {
            Some(name) => {
                let x = f64::from_le_bytes(data[at..at + 8].try_into().unwrap());
                v.insert(name.clone(), Value::from(x));
                at += 8;
            }
            None => {
                assert_eq!(ty, "rockslide/Contact");
                at += 32; // four float64
            }
        }
    }
    assert_eq!(at, data.len(), "every byte of the message is a field");
    Value::Object(v)
}

/// A ROS 2 definition with its dependencies, parsed: type name → (field type, field
/// name) in order; the root type is `""`. Dependencies follow the 80-`=` separator and
/// `MSG: package/Type`; comments and constants (`NAME=value`) are skipped.
fn parse_definition(text: &str) -> BTreeMap<String, Vec<(String, String)>> {
    let mut types = BTreeMap::new();
    for (k, block) in text.split(&"=".repeat(80)).enumerate() {
        let mut lines = block
            .lines()
            .map(|l| l.split('#').next().unwrap().trim())
            .filter(|l| !l.is_empty() && !l.contains('='));
        let name = match k {
            0 => String::new(),
            _ => lines
                .next()
                .unwrap()
                .strip_prefix("MSG: ")
                .unwrap()
                .to_string(),
        };
        let fields = lines
            .map(|l| {
                let (ty, name) = l.split_once(' ').unwrap();
                (ty.to_string(), name.trim().to_string())
            })
            .collect();
        assert!(types.insert(name, fields).is_none(), "a type defined twice");
    }
    types
}

/// One value of ROS 2 type `ty` read from a CDR message at `at` (alignment counted from
/// the end of the 4-byte header), as JSON.
fn read_cdr(
    types: &BTreeMap<String, Vec<(String, String)>>,
    ty: &str,
    d: &[u8],
    at: &mut usize,
) -> Value {
    let mut take = |align: usize, n: usize| {
        *at = 4 + (*at - 4).div_ceil(align) * align;
        let b = d[*at..*at + n].to_vec();
        *at += n;
        b
    };
    if let Some(item) = ty.strip_suffix("[]") {
        let n = u32::from_le_bytes(take(4, 4).try_into().unwrap());
        return Value::Array((0..n).map(|_| read_cdr(types, item, d, at)).collect());
    }
    match ty {
        "float64" => Value::from(f64::from_le_bytes(take(8, 8).try_into().unwrap())),
        "int32" => Value::from(i32::from_le_bytes(take(4, 4).try_into().unwrap())),
        "uint32" => Value::from(u32::from_le_bytes(take(4, 4).try_into().unwrap())),
        "uint8" => Value::from(take(1, 1)[0]),
        "bool" => Value::from(take(1, 1)[0] != 0),
        "string" => {
            let n = u32::from_le_bytes(take(4, 4).try_into().unwrap()) as usize;
            let b = take(1, n);
            assert_eq!(b[n - 1], 0, "a string ends with NUL");
            Value::from(std::str::from_utf8(&b[..n - 1]).unwrap())
        }
        _ => {
            let fields = types
                .get(ty)
                .unwrap_or_else(|| panic!("{ty} is used but not defined"));
            let mut v = serde_json::Map::new();
            for (fty, name) in fields {
                v.insert(name.clone(), read_cdr(types, fty, d, at));
            }
            Value::Object(v)
        }
    }
}

/// A CDR message of a Foxglove ROS 2 schema, decoded from its definition text.
fn decode_foxglove(definition: &str, data: &[u8]) -> Value {
    assert_eq!(&data[..4], &[0, 1, 0, 0], "little-endian CDR header");
    let types = parse_definition(definition);
    let mut at = 4;
    let v = read_cdr(&types, "", data, &mut at);
    assert_eq!(at, data.len(), "every byte of the message is a field");
    v
}

/// Every message of a file: (topic, schema name, log time, JSON, or the CDR message's
/// top-level `float64` fields as a JSON object, or a 3D-view message decoded from its
/// definition). A `FrameTransforms` message gives one entry per transform.
fn messages(path: &Path) -> Vec<(String, String, u64, Value)> {
    let bytes = std::fs::read(path).unwrap();
    mcap::MessageStream::new(&bytes)
        .unwrap()
        .flat_map(|m| {
            let m = m.unwrap();
            let schema = m.channel.schema.as_ref().unwrap();
            let text = std::str::from_utf8(&schema.data).unwrap();
            let v: Value = match m.channel.message_encoding.as_str() {
                "cdr" if schema.name.starts_with("foxglove_msgs/msg/") => {
                    decode_foxglove(text, &m.data)
                }
                "cdr" => decode_cdr(text, &m.data),
                "json" => serde_json::from_slice(&m.data).unwrap(),
                other => panic!("message encoding {other}"),
            };
            let entries = match schema.name.as_str() {
                "foxglove_msgs/msg/FrameTransforms" => v["transforms"].as_array().unwrap().clone(),
                _ => vec![v],
            };
            entries
                .into_iter()
                .map(|v| (m.channel.topic.clone(), schema.name.clone(), m.log_time, v))
                .collect::<Vec<_>>()
        })
        .collect()
}

/// A ROS 2 message definition Foxglove's `ros2msg` parser and `mcap-ros2-support` read:
/// comment lines, `<type> <name>` lines of `float64` or the one nested type
/// `rockslide/Contact`, field names `[a-z][a-z0-9_]*`, and the nested type defined after
/// the 80-`=` separator and `MSG: rockslide/Contact`.
fn assert_ros2msg(definition: &str, name: &str) {
    let (main, deps) = match definition.split_once(&format!("{}\n", "=".repeat(80))) {
        Some((m, d)) => (m, Some(d)),
        None => (definition, None),
    };
    let good_name = |n: &str| {
        n.starts_with(|c: char| c.is_ascii_lowercase())
            && n.chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
    };
    // a ROS 2 message name: package/Type
    let (package, ty) = name.split_once('/').unwrap();
    assert!(good_name(package), "{name}: package");
    assert!(
        ty.starts_with(|c: char| c.is_ascii_uppercase())
            && ty.chars().all(|c| c.is_ascii_alphanumeric()),
        "{name}: type name"
    );
    let fields = ros2_fields(main);
    assert!(!fields.is_empty(), "{name}: no field");
    let nested = fields.iter().any(|(f, _)| f.is_none());
    for line in main.lines().filter(|l| !l.starts_with('#')) {
        let field = line.split('#').next().unwrap().trim();
        let (_, n) = field.split_once(' ').unwrap();
        assert!(good_name(n), "{name}: field name {n:?}");
    }
    match deps {
        Some(d) => {
            assert!(nested, "{name}: a dependency nobody uses");
            let d = d.strip_prefix("MSG: rockslide/Contact\n").unwrap();
            let inner: Vec<_> = ros2_fields(d)
                .into_iter()
                .map(|(f, _)| f.unwrap())
                .collect();
            assert_eq!(inner, ["normal", "tangential", "slip", "gap"], "{name}");
        }
        None => assert!(!nested, "{name}: rockslide/Contact used but not defined"),
    }
}

/// Foxglove turns a JSON schema into message definitions only within a subset: the root
/// and every nested object `"type": "object"` with `properties`; every field one concrete
/// type (boolean, string, number, integer, object, array); array items typed likewise;
/// no `$ref`, no type lists (Foxglove Studio's `parseJsonSchema`, which throws otherwise
/// and the channel does not load).
fn assert_foxglove_subset(schema: &Value, path: &str) {
    assert_eq!(schema["type"], "object", "{path}: type");
    let props = schema["properties"]
        .as_object()
        .unwrap_or_else(|| panic!("{path}: an object needs properties"));
    for (k, f) in props {
        let p = format!("{path}.{k}");
        assert!(f.get("$ref").is_none(), "{p}: $ref");
        match f["type"].as_str() {
            Some("boolean" | "string" | "number" | "integer") => {}
            Some("object") => assert_foxglove_subset(f, &p),
            Some("array") => match f["items"]["type"].as_str() {
                Some("boolean" | "string" | "number" | "integer") => {}
                Some("object") => assert_foxglove_subset(&f["items"], &p),
                other => panic!("{p}: array items of type {other:?}"),
            },
            _ => panic!("{p}: type {}", f["type"]),
        }
    }
}

fn assert_schemas_in_foxglove_subset(path: &Path) -> usize {
    let bytes = std::fs::read(path).unwrap();
    // the header names the ros2 profile its ros2msg schemas and CDR messages follow
    let header = mcap::read::LinearReader::new(&bytes)
        .unwrap()
        .find_map(|r| match r.unwrap() {
            mcap::records::Record::Header(h) => Some(h),
            _ => None,
        })
        .unwrap();
    assert_eq!(
        (header.profile.as_str(), header.library.as_str()),
        ("ros2", "rockslide")
    );
    let summary = mcap::read::Summary::read(&bytes).unwrap().unwrap();
    for s in summary.schemas.values() {
        if s.encoding == "ros2msg" && s.name.starts_with("foxglove_msgs/msg/") {
            // every type it uses is defined (checked by decoding in `messages`)
            let types = parse_definition(std::str::from_utf8(&s.data).unwrap());
            for (ty, _) in types.values().flatten() {
                let ty = ty.trim_end_matches("[]");
                assert!(
                    ty.chars().all(|c| c.is_ascii_alphanumeric()) || types.contains_key(ty),
                    "{}: {ty} undefined",
                    s.name
                );
            }
            continue;
        }
        if s.encoding == "ros2msg" {
            assert_ros2msg(std::str::from_utf8(&s.data).unwrap(), &s.name);
            continue;
        }
        assert_eq!(s.encoding, "jsonschema");
        let v: Value = serde_json::from_slice(&s.data).unwrap();
        assert_foxglove_subset(&v, &s.name);
    }
    summary.schemas.len()
}

#[test]
fn pepo_case_mcap_reads_back_equal_to_csv() {
    let case = load_case(Path::new("cases/pepo-ground-disp.toml")).unwrap();
    let text = case.text.clone();
    let result = run_case(case).unwrap();
    let out = tempfile::tempdir().unwrap();
    let dir = write_case_outputs(&result, out.path()).unwrap();
    let path = dir.join("pepo-ground-disp.mcap");
    let m = read_mcap(&path).unwrap();

    // One state channel per run (its contacts in the same message), a state channel for
    // the reference, and the log; nothing 3D.
    let topics: Vec<&str> = m.channels.iter().map(|c| c.topic.as_str()).collect();
    let mut expected: Vec<String> = result
        .runs
        .iter()
        .map(|r| format!("/{}/{}/state", r.engine, r.variant))
        .collect();
    expected.push("/reference/state".into());
    expected.push("/log".into());
    assert_eq!(topics, expected);
    assert!(
        result.runs.len() >= 3,
        "at least the three predictor-corrector routes"
    );

    // Values equal the CSV traces bit for bit.
    for r in &result.runs {
        let label = format!("{}-{}", r.engine, r.variant);
        let csv = read_csv(&dir.join(format!("{label}.csv"))).unwrap();
        let topic = format!("/{}/{}/state", r.engine, r.variant);
        assert_traces_equal(&csv, m.state(&topic).unwrap(), &topic);
        assert_traces_equal(&r.trace, m.state(&topic).unwrap(), &topic);
        // the contacts, from the same messages, equal the run's block bit for bit (its
        // CSV file is not written: T is the resistance, the slip the slide, N and the gap
        // constant)
        let back = &m.state(&topic).unwrap().contacts;
        let block = &r.trace.contacts;
        assert_eq!(back.names, block.names, "{topic}");
        assert_eq!(back.compliance, block.compliance, "{topic}");
        assert_eq!(
            back.len(),
            r.trace.len(),
            "{topic}: a contact row per message"
        );
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&back.time), bits(&block.time), "{topic}");
        assert_eq!(bits(&back.values), bits(&block.values), "{topic}");
        assert!(block.repeats(&r.trace), "{topic}");
        assert!(
            !dir.join(format!("{label}-contacts.csv")).exists(),
            "{topic}"
        );
        assert!(m.contacts.is_empty(), "no separate contact channel");
    }
    let reference = result.reference.as_ref().unwrap();
    let csv = read_csv(&dir.join(format!("reference-{}.csv", reference.solution.name()))).unwrap();
    assert_traces_equal(&csv, m.state("/reference/state").unwrap(), "reference");

    // Schemas: ROS 2 definitions and CDR messages, units per field, only the trace's fields.
    for c in m.channels.iter().filter(|c| c.topic.ends_with("/state")) {
        let label = c.topic.trim_start_matches('/').trim_end_matches("/state");
        assert_eq!(c.schema, rockslide::formats::state_schema_name(label));
        assert_eq!(
            (c.schema_encoding.as_str(), c.message_encoding.as_str()),
            ("ros2msg", "cdr")
        );
    }
    let bytes = std::fs::read(&path).unwrap();
    let summary = mcap::read::Summary::read(&bytes).unwrap().unwrap();
    for ch in summary.channels.values() {
        let Some(s) = &ch.schema else {
            panic!("{} has no schema", ch.topic)
        };
        let text = std::str::from_utf8(&s.data).unwrap();
        // the unit of a field: `# [unit]` after its declaration
        let unit_of = |field: &str| {
            text.lines()
                .find(|l| l.split_whitespace().nth(1) == Some(field))
                .and_then(|l| l.split_once("# [")?.1.split_once(']'))
                .map(|(u, _)| u.to_string())
                .unwrap_or_else(|| panic!("{}: {field} has no unit", s.name))
        };
        if s.name.starts_with("rockslide/State") && s.name != "rockslide/StateReference" {
            // After the fields, one rockslide/Contact per contact, each field with its SI unit.
            assert!(text.contains("\nrockslide/Contact base "), "{text}");
            let units: Vec<String> = ["normal", "tangential", "slip", "gap"]
                .iter()
                .map(|k| unit_of(k))
                .collect();
            assert_eq!(units, ["N", "N", "m", "m"], "{}", s.name);
        }
        if !s.name.starts_with("rockslide/State") {
            assert_eq!(s.name, "foxglove.Log");
            continue;
        }
        assert_eq!(s.encoding, "ros2msg");
        let fields: Vec<String> = ros2_fields(text)
            .into_iter()
            .filter_map(|(f, _)| f)
            .collect();
        assert!(!fields.iter().any(|f| f == "rotation" || f == "uplift"));
        assert_eq!(fields[0], "time");
        assert_eq!(unit_of("time"), "s");
        for k in &fields[1..] {
            let qty = q::by_key(k).unwrap();
            let expected = if qty.unit.is_empty() {
                "dimensionless"
            } else {
                qty.unit
            };
            assert_eq!(unit_of(k), expected, "{k}");
        }
    }
    // Chunked, zstd, indexed, with statistics.
    assert!(!summary.chunk_indexes.is_empty());
    assert!(
        summary
            .chunk_indexes
            .iter()
            .all(|c| c.compression == "zstd")
    );
    assert!(
        summary
            .chunk_indexes
            .iter()
            .all(|c| !c.message_index_offsets.is_empty())
    );
    let stats = summary.stats.as_ref().unwrap();
    assert_eq!(stats.message_count, m.message_count);
    assert_eq!(stats.attachment_count, 1);
    // Log time = simulation time in ns.
    for (topic, _, ns, v) in messages(&path) {
        if topic.ends_with("/state") {
            let t = v["time"].as_f64().unwrap();
            assert_eq!(ns, (t * 1e9).round() as u64, "{topic} at t = {t}");
        }
    }
    assert_eq!(m.time_range, (0, 1_000_000_000));

    // Metadata and attachment.
    let head = &m.metadata["rockslide"];
    assert_eq!(head["version"], env!("CARGO_PKG_VERSION"));
    assert!(!head["commit"].is_empty());
    assert_eq!(head["case"], "pepo-ground-disp");
    assert_eq!(head["model"], "oscillator");
    for r in &result.runs {
        let run = &m.metadata[&format!("run {}", r.label())];
        assert_eq!(run["status"], "completed");
        assert_eq!(run["dt_s"], format!("{:?}", r.dt));
        for s in &r.settings {
            assert_eq!(run[&format!("setting.{}", s.label())], s.value_text());
        }
    }
    assert_eq!(
        m.metadata["reference"]["solution"],
        reference.solution.name()
    );
    assert_eq!(m.attachments.len(), 1);
    let (name, media, data) = &m.attachments[0];
    assert_eq!(
        (name.as_str(), media.as_str()),
        ("pepo-ground-disp.toml", "application/toml")
    );
    assert_eq!(data, text.as_bytes());
    assert!(!m.metadata.contains_key("scene3d"));
    // One state schema per run (its contacts defined in it), the reference, and the log.
    assert_eq!(
        assert_schemas_in_foxglove_subset(&path),
        result.runs.len() + 2
    );
}

// ---------------------------------------------------------------------------------------
// Scenes with geometry: traces built by hand (no rocking engine is needed to check the
// 3D output), with motions whose geometry is known in closed form.

const ROCKING_CASE: &str = r#"
# Test-only RPEPO-like scene (the paper's Fig. 7), for the 3D view; units SI.
title = "Rocking body, 3D view test"
source = "AL-Shawaf & Rahman, Fig. 7: RPEPO geometry"
requirement = "rockslide shall draw a body with geometry in Foxglove's 3D panel"
[model]
kind = "rocking-body"
mass = 1.0e6          # kg
gravity = 9.81        # m/s²
cm_height = 0.625     # m
half_width = 0.5      # m
supports = 10
[model.contact]
kx = 2.4e9            # N/m
kz = 3.94784e8        # N/m
mu = 0.5
[excitation]
kind = "ground-displacement"
shape = "sine-pulse"
amplitude = 0.00099   # m
omega = 31.41592653589793
cycles = 5
[run]
duration = 0.05
dt = 0.0005
"#;

const BLOCK_CASE: &str = r#"
# Test-only Newmark sliding block (Newmark 1965), for the 3D view; units SI.
title = "Rigid block, 3D view test"
source = "Newmark 1965: rigid sliding block"
requirement = "rockslide shall draw a sliding block without a rotation field"
[model]
kind = "rigid-block"
mass = 1000.0         # kg
gravity = 9.81        # m/s²
half_width = 0.4      # m
half_height = 0.8     # m
mu = 0.3
[excitation]
kind = "none"
[run]
duration = 0.01
dt = 0.0001
"#;

fn case(text: &str, name: &str) -> Case {
    parse_case(Path::new(&format!("{name}.toml")), text).unwrap()
}

fn result_with(case: Case, runs: Vec<Run>) -> CaseResult {
    CaseResult {
        run_responses: runs.iter().map(|r| responses(&r.trace)).collect(),
        invariants: Vec::new(),
        envelopes: Vec::new(),
        azimuths: None,
        history_errors: runs.iter().map(|_| None).collect(),
        runs,
        case,
        not_applicable: Vec::new(),
        reference: Err("none in this test".into()),
        checks: Vec::new(),
    }
}

fn run(engine: &'static str, variant: &str, trace: Trace, status: RunStatus) -> Run {
    Run {
        engine,
        variant: variant.into(),
        arrangement: Default::default(),
        dt: 0.0005,
        settings: vec![rockslide::engine::Setting::text("integrator", "test")],
        stats: rockslide::engine::SolverStats::steps(trace.len() as u64),
        findings: Vec::new(),
        trace,
        status,
        wall_seconds: 0.0,
    }
}

/// Apply a FrameTransform message to a point.
fn apply(tf: &Value, p: [f64; 3]) -> [f64; 3] {
    let (t, r) = (&tf["translation"], &tf["rotation"]);
    let f = |v: &Value, k: &str| v[k].as_f64().unwrap();
    let (x, y, z, w) = (f(r, "x"), f(r, "y"), f(r, "z"), f(r, "w"));
    // v' = v + 2w(u×v) + 2u×(u×v), u = (x, y, z)
    let u = [x, y, z];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let c1 = cross(u, p);
    let c2 = cross(u, c1);
    [
        p[0] + 2.0 * w * c1[0] + 2.0 * c2[0] + f(t, "x"),
        p[1] + 2.0 * w * c1[1] + 2.0 * c2[1] + f(t, "y"),
        p[2] + 2.0 * w * c1[2] + 2.0 * c2[2] + f(t, "z"),
    ]
}

#[test]
fn rocking_body_pose_and_scene_follow_the_trace() {
    // Rocking about the right support (x = +b at ground level) by θ(t) = −0.05 sin(40t)
    // (clockwise lifts the left edge), while the ground moves: rigid-body kinematics,
    // CM relative to the pivot (−b, h) rotated by θ.
    let (b, h, w) = (0.5, 0.625, 1.0e6 * 9.81);
    let chans = [
        &q::REL_DISP,
        &q::GROUND_DISP,
        &q::CM_X,
        &q::CM_Z,
        &q::ROTATION,
        &q::BASE_SHEAR,
        &q::NORMAL,
    ];
    let mut trace = Trace::with_channels(&chans, 101);
    for i in 0..=100 {
        let t = i as f64 * 0.0005;
        let th = -0.05 * (40.0 * t).sin().abs();
        let (cx, cz) = (
            b - b * th.cos() - h * th.sin(),
            -b * th.sin() + h * th.cos(),
        );
        let ox = cx + h * th.sin(); // base centre O
        trace.push(
            t,
            &[
                ox,
                0.001 * (31.4 * t).sin(),
                cx,
                cz - h,
                th,
                0.2 * w * (9.0 * t).cos(),
                w,
            ],
        );
    }
    let c = case(ROCKING_CASE, "rocking-3d");
    let result = result_with(
        c,
        vec![run("fe", "exact", trace.clone(), RunStatus::Completed)],
    );
    let out = tempfile::tempdir().unwrap();
    let dir = write_case_outputs(&result, out.path()).unwrap();
    let path = dir.join("rocking-3d.mcap");
    let m = read_mcap(&path).unwrap();
    assert_traces_equal(&trace, m.state("/fe/exact/state").unwrap(), "rocking");
    let topics: Vec<&str> = m.channels.iter().map(|c| c.topic.as_str()).collect();
    assert_eq!(
        topics,
        [
            "/fe/exact/state",
            "/fe/exact/scene",
            "/fe/exact/forces",
            "/fe/exact/transform",
            "/log"
        ]
    );
    let schema_of = |t: &str| {
        m.channels
            .iter()
            .find(|c| c.topic == t)
            .unwrap()
            .schema
            .clone()
    };
    assert_eq!(
        schema_of("/fe/exact/scene"),
        "foxglove_msgs/msg/SceneUpdate"
    );
    assert_eq!(
        schema_of("/fe/exact/forces"),
        "foxglove_msgs/msg/SceneUpdate"
    );
    assert_eq!(
        schema_of("/fe/exact/transform"),
        "foxglove_msgs/msg/FrameTransforms"
    );
    // one FrameTransforms message a frame (51 frames, below)
    let transform_channel = m.channels.iter().find(|c| c.topic == "/fe/exact/transform");
    assert_eq!(transform_channel.unwrap().messages, 51);
    assert!(m.metadata.contains_key("scene3d"));
    // State, SceneUpdate, FrameTransforms, Log.
    assert_eq!(assert_schemas_in_foxglove_subset(&path), 4);

    let msgs = messages(&path);
    // The static scene: ground, label and body (2b × depth × 2h box, 10 supports + CM).
    let scene: Vec<_> = msgs.iter().filter(|m| m.0 == "/fe/exact/scene").collect();
    assert_eq!(scene.len(), 1);
    assert_eq!(scene[0].2, 0);
    let ents = scene[0].3["entities"].as_array().unwrap();
    let body = ents.iter().find(|e| e["id"] == "body").unwrap();
    assert_eq!(body["frame_id"], "fe/exact/body");
    let size = &body["cubes"][0]["size"];
    assert_eq!(
        (size["x"].as_f64(), size["z"].as_f64()),
        (Some(2.0 * b), Some(2.0 * h))
    );
    assert_eq!(body["spheres"].as_array().unwrap().len(), 11);
    assert!(
        ents.iter()
            .any(|e| e["id"] == "datum" && e["frame_id"] == "world")
    );

    // Transforms: every row (0.5 ms < 1 ms period → every other row, plus the last).
    let tfs: Vec<_> = msgs
        .iter()
        .filter(|m| m.0 == "/fe/exact/transform")
        .collect();
    let bodies: Vec<_> = tfs
        .iter()
        .filter(|m| m.3["child_frame_id"] == "fe/exact/body")
        .collect();
    let grounds: Vec<_> = tfs
        .iter()
        .filter(|m| m.3["child_frame_id"] == "fe/exact/ground")
        .collect();
    assert_eq!(bodies.len(), 51);
    assert_eq!(grounds.len(), 51);
    for (bt, gt) in bodies.iter().zip(&grounds) {
        let ns = bt.2;
        let i = (ns as f64 / 0.5e6).round() as usize;
        assert_eq!(bt.3["parent_frame_id"], "fe/exact/ground");
        assert_eq!(gt.3["parent_frame_id"], "world");
        assert_eq!(
            gt.3["translation"]["x"].as_f64().unwrap(),
            trace.columns[1][i]
        );
        // The pivot corner (b, 0, −h) in the body frame stays at (b, 0, 0) on the ground;
        // the other corner is lifted by 2b·sin|θ|.
        let th = trace.columns[4][i];
        let pivot = apply(&bt.3, [b, 0.0, -h]);
        let other = apply(&bt.3, [-b, 0.0, -h]);
        // measured: |error| ≤ 2e-16 m (rounding of the quaternion products)
        assert!(
            (pivot[0] - b).abs() < 1e-12 && pivot[2].abs() < 1e-12,
            "pivot at {pivot:?}, θ = {th}"
        );
        assert!(
            (other[2] - 2.0 * b * th.abs().sin()).abs() < 1e-12,
            "lifted corner {other:?}"
        );
        let stamp = &bt.3["timestamp"];
        assert_eq!(
            stamp["sec"].as_u64().unwrap() * 1_000_000_000 + stamp["nanosec"].as_u64().unwrap(),
            ns
        );
    }
    // Forces: the weight drawn as long as the CM is high, ending at O.
    let forces: Vec<_> = msgs.iter().filter(|m| m.0 == "/fe/exact/forces").collect();
    assert_eq!(forces.len(), 51);
    let arrows = forces[0].3["entities"][0]["arrows"].as_array().unwrap();
    assert_eq!(arrows.len(), 2);
    let len = |a: &Value| a["shaft_length"].as_f64().unwrap() + a["head_length"].as_f64().unwrap();
    assert!(
        (len(&arrows[0]) - h).abs() < 1e-12,
        "normal arrow length {}",
        len(&arrows[0])
    );
    assert!(
        (len(&arrows[1]) - 0.2 * h).abs() < 1e-12,
        "shear arrow length {}",
        len(&arrows[1])
    );
    let tail = &arrows[0]["pose"]["position"];
    assert!(
        (tail["z"].as_f64().unwrap() + h).abs() < 1e-12,
        "normal arrow ends at O"
    );
    // The run's end in the log.
    let log: Vec<_> = msgs.iter().filter(|m| m.0 == "/log").collect();
    assert_eq!(log.len(), 1);
    assert_eq!(log[0].3["level"], 2);
}

#[test]
fn sliding_block_without_rotation_has_no_rotation_field() {
    let chans = [&q::CM_X, &q::VEL];
    let mut trace = Trace::with_channels(&chans, 101);
    for i in 0..=100 {
        let t = i as f64 * 1e-4;
        trace.push(t, &[0.5 * 2.0 * t * t, 2.0 * t]);
    }
    let c = case(BLOCK_CASE, "block-3d");
    let result = result_with(
        c,
        vec![run(
            "rapier",
            "inertial",
            trace.clone(),
            RunStatus::Completed,
        )],
    );
    let out = tempfile::tempdir().unwrap();
    let dir = write_case_outputs(&result, out.path()).unwrap();
    let path = dir.join("block-3d.mcap");
    let m = read_mcap(&path).unwrap();
    assert_traces_equal(&trace, m.state("/rapier/inertial/state").unwrap(), "block");
    let bytes = std::fs::read(&path).unwrap();
    let summary = mcap::read::Summary::read(&bytes).unwrap().unwrap();
    let state = summary
        .channels
        .values()
        .find(|c| c.topic == "/rapier/inertial/state")
        .unwrap();
    let schema = std::str::from_utf8(&state.schema.as_ref().unwrap().data).unwrap();
    let fields: Vec<String> = ros2_fields(schema)
        .into_iter()
        .map(|(f, _)| f.unwrap())
        .collect();
    assert_eq!(fields, ["time", "cm_x", "vel"]);
    // The body slides flat at the CM height: identity rotation, z = h.
    let msgs = messages(&path);
    let last = msgs
        .iter()
        .rev()
        .find(|m| m.3["child_frame_id"] == "rapier/inertial/body")
        .unwrap();
    assert_eq!(last.2, 10_000_000);
    assert_eq!(last.3["rotation"]["w"], 1.0);
    assert_eq!(last.3["translation"]["z"], 0.8);
    assert_eq!(
        last.3["translation"]["x"].as_f64().unwrap(),
        trace.columns[0][100]
    );
    // No force channels in the trace: the forces entity has no arrows.
    let f = msgs
        .iter()
        .find(|m| m.0 == "/rapier/inertial/forces")
        .unwrap();
    assert!(f.3["entities"][0]["arrows"].as_array().unwrap().is_empty());
}

#[test]
fn diverged_run_leaves_a_readable_file_with_the_reason() {
    let chans = [&q::REL_DISP, &q::ROTATION];
    let mut trace = Trace::with_channels(&chans, 8);
    for i in 0..7 {
        let t = i as f64 * 0.0005;
        trace.push(t, &[1e-3 * 10f64.powi(i), 0.01 * i as f64]);
    }
    trace.push(0.0035, &[f64::NAN, f64::INFINITY]);
    let status = RunStatus::Diverged {
        time: 0.0035,
        reason: "NaN in the displacement".into(),
    };
    let ok = {
        let mut t = Trace::with_channels(&chans, 101);
        for i in 0..=100 {
            t.push(i as f64 * 0.0005, &[0.0, 0.0]);
        }
        t
    };
    let c = case(ROCKING_CASE, "diverged");
    let result = result_with(
        c,
        vec![
            run("fe", "exact", trace.clone(), status),
            run("fe", "small-rotation", ok, RunStatus::Completed),
        ],
    );
    let out = tempfile::tempdir().unwrap();
    let dir = write_case_outputs(&result, out.path()).unwrap();
    let path = dir.join("diverged.mcap");
    let m = read_mcap(&path).unwrap();
    let back = m.state("/fe/exact/state").unwrap();
    assert_traces_equal(&trace, back, "diverged");
    // CDR carries non-finite values exactly (JSON had to write them as null)
    assert!(back.columns[0][7].is_nan());
    assert_eq!(back.columns[1][7], f64::INFINITY);
    let meta = &m.metadata["run fe/exact"];
    assert_eq!(meta["status"], "diverged");
    assert_eq!(meta["stop_time_s"], "0.0035");
    assert_eq!(meta["stop_reason"], "NaN in the displacement");
    assert_eq!(m.metadata["run fe/small-rotation"]["status"], "completed");
    // The log says so at the stop time, as an error; the 3D view stops at the last finite row.
    let msgs = messages(&path);
    let log: BTreeMap<u64, &Value> = msgs
        .iter()
        .filter(|m| m.0 == "/log")
        .map(|m| (m.2, &m.3))
        .collect();
    assert_eq!(log[&3_500_000]["level"], 4);
    assert!(
        log[&3_500_000]["message"]
            .as_str()
            .unwrap()
            .contains("NaN in the displacement")
    );
    let last_tf = msgs
        .iter()
        .filter(|m| m.0 == "/fe/exact/transform")
        .map(|m| m.2)
        .max()
        .unwrap();
    assert_eq!(last_tf, 3_000_000);
}

#[test]
fn same_case_gives_identical_bytes_apart_from_wall_time() {
    // Determinism: two writes of the same result are byte-identical (wall time is in the
    // metadata; here it is fixed at 0).
    let chans = [&q::CM_X, &q::ROTATION];
    let mut trace = Trace::with_channels(&chans, 11);
    for i in 0..=10 {
        trace.push(i as f64 * 1e-3, &[0.1 * i as f64, 0.0]);
    }
    let result = result_with(
        case(ROCKING_CASE, "det"),
        vec![run("fe", "exact", trace, RunStatus::Completed)],
    );
    let a = rockslide::formats::mcap_bytes(&rockslide::report::case_trace_log(&result)).unwrap();
    let b = rockslide::formats::mcap_bytes(&rockslide::report::case_trace_log(&result)).unwrap();
    assert_eq!(a, b);
}

#[test]
fn a_minute_long_run_has_one_transform_message_per_scene_frame_with_the_exact_pose() {
    // 60 s of trace every 20 ms (3,001 rows): the 3D view keeps one frame every
    // 60 s / MAX_SCENE_FRAMES = 40 ms, i.e. every other row, and the last: 1,501 frames,
    // each one FrameTransforms message (ground and body) and one forces message.
    let chans = [&q::CM_X, &q::VEL];
    let rows = 3001;
    let mut trace = Trace::with_channels(&chans, rows);
    for i in 0..rows {
        let t = i as f64 * 0.02;
        trace.push(t, &[0.001 * t.sin() / 3.0, 0.001 * t.cos() / 3.0]);
    }
    let result = result_with(
        case(BLOCK_CASE, "block-minute"),
        vec![run(
            "rapier",
            "inertial",
            trace.clone(),
            RunStatus::Completed,
        )],
    );
    let out = tempfile::tempdir().unwrap();
    let dir = write_case_outputs(&result, out.path()).unwrap();
    let path = dir.join("block-minute.mcap");
    let m = read_mcap(&path).unwrap();
    let count = |topic: &str| {
        m.channels
            .iter()
            .find(|c| c.topic == topic)
            .unwrap()
            .messages
    };
    assert_eq!(rockslide::formats::MAX_SCENE_FRAMES, 1_500);
    assert_eq!(count("/rapier/inertial/transform"), 1_501);
    assert_eq!(count("/rapier/inertial/forces"), 1_501);
    assert_eq!(count("/rapier/inertial/state"), 3_001);
    let msgs = messages(&path);
    let bodies: Vec<_> = msgs
        .iter()
        .filter(|m| m.3["child_frame_id"] == "rapier/inertial/body")
        .collect();
    assert_eq!(bodies.len(), 1_501);
    for (k, b) in bodies.iter().enumerate() {
        let i = 2 * k; // rows 0, 2, 4, …, 3000
        assert_eq!(b.2, (trace.time[i] * 1e9).round() as u64);
        // the pose the trace holds, bit for bit: x = cm_x, z = h, no rotation
        assert_eq!(
            b.3["translation"]["x"].as_f64().unwrap(),
            trace.columns[0][i]
        );
        assert_eq!(b.3["translation"]["z"].as_f64().unwrap(), 0.8);
        assert_eq!(b.3["rotation"]["w"].as_f64().unwrap(), 1.0);
    }
}

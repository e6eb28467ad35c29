//! MCAP traces: every run of a case in one MCAP file that Foxglove (or any MCAP reader)
//! opens, plots and animates; and reading such a file back (`rockslide trace-info`, tests).
//!
//! Layout of a file (see docs/traces.md):
//! - one channel per run, `/<label>/state` (`label` = `engine/variant` or `reference`),
//!   schema `rockslide/State<Label>` (ROS 2 definition, encoding `ros2msg`, each field's
//!   SI unit in a comment), messages `cdr` (see [`crate::cdr`]; JSON before, still read),
//!   one per trace row, with exactly the trace's fields and then, for a run with a contact
//!   block, each contact's N, T, slip and gap (see [`crate::contacts`]);
//! - for scenes with geometry: `/<label>/scene` and `/<label>/forces`
//!   (`foxglove_msgs/msg/SceneUpdate`) and `/<label>/transform`
//!   (`foxglove_msgs/msg/FrameTransforms`: the ground's and the body's transform of one
//!   frame), `ros2msg`/`cdr`, see [`crate::scene3d`]; one frame per [`scene_period_ns`];
//! - files written before the contacts joined the state message have a channel
//!   `/<label>/contacts` (schema `rockslide/Contacts<Label>`) beside it: still read;
//! - `/log` (`foxglove.Log`): how each run ended, at the time it stopped;
//! - metadata records (`rockslide`, `run <label>`, `reference`, `scene3d`) and attachments
//!   (the case file).
//!
//! Message log time = publish time = simulation time in nanoseconds; messages of all
//! channels are interleaved in time order so chunks are time-local. The file is written
//! in zstd chunks (fast level −3, measured: see [`CHUNKS`]) of 1 MiB, each compressed whole by
//! our own writer ([`writer`]),
//! with message, chunk, attachment and metadata indexes, statistics, summary and CRCs, streamed
//! to a temporary sibling, then atomically renamed.
//! Non-finite values (a diverged run's last row) are written as JSON `null` and read back
//! as NaN: JSON has no NaN or infinity.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io::Write;
use std::path::Path;

use serde_json::Value;

use rockslide_core::error::{Error, InputError, InputErrors};
use rockslide_core::io::write_atomically_with;
use rockslide_core::trace::{CONTACT_FIELDS, ContactBlock, ContactState, Quantity, Trace, q};

use crate::cdr;
use crate::contacts;
use crate::scene3d::{self, Geometry, Pose};

mod writer;
pub use writer::{ChunkCompression, ChunkOptions, McapWriter};

/// Schema name prefix of the per-run state channels.
pub const STATE_SCHEMA: &str = "rockslide/State";

/// The prefix state schemas had when their messages were JSON (files written before the
/// CDR encoding; still read).
const JSON_STATE_SCHEMA: &str = "rockslide.State";

/// The state schema name of a run: `rockslide/State<Label>`, the label in CamelCase, e.g.
/// `rockslide/StateFeDouble`, `rockslide/StatePredictorCorrectorPaper`: a ROS 2 message
/// name (`package/Type`, as ROS 2 tools and `mcap-ros2-support` require). One name per
/// run, because viewers (Foxglove among them) key message definitions by schema name
/// across the whole file, and runs record different fields.
pub fn state_schema_name(label: &str) -> String {
    format!("{STATE_SCHEMA}{}", cdr::camel_case(label))
}
/// Shortest interval between 3D messages of a run, ns (1 ms of simulated time): enough for
/// smooth playback, far fewer messages than steps.
pub const SCENE_PERIOD_NS: u64 = 1_000_000;
/// Most 3D frames of one run: 1,500 (25 frames per simulated second over a 60-s record).
/// The 3D view's transforms and force arrows are 90 % of a record case's MCAP bytes before
/// compression; a minute of record needs no more frames than a video of it.
pub const MAX_SCENE_FRAMES: u64 = 1_500;

/// Interval between 3D messages of a run lasting `duration_s`, ns: [`SCENE_PERIOD_NS`], or
/// longer so that the run has at most [`MAX_SCENE_FRAMES`] frames.
pub fn scene_period_ns(duration_s: f64) -> u64 {
    let spread = (duration_s.max(0.0) * 1e9 / MAX_SCENE_FRAMES as f64).ceil();
    if spread.is_finite() {
        SCENE_PERIOD_NS.max(spread as u64)
    } else {
        SCENE_PERIOD_NS
    }
}

/// One run to log.
#[derive(Debug, Clone)]
pub struct LoggedRun<'a> {
    /// `engine/variant` or `reference`: topics are `/<label>/state` etc.
    pub label: String,
    /// Its time histories.
    pub trace: &'a Trace,
    /// One-word status (`completed`, `diverged`, `not converged`).
    pub status: String,
    /// Time and reason when it stopped early.
    pub stop: Option<(f64, String)>,
    /// Its `run <label>` metadata record (settings, solver statistics, ...).
    pub metadata: BTreeMap<String, String>,
}

/// Everything one MCAP file holds.
#[derive(Debug, Clone, Default)]
pub struct TraceLog<'a> {
    /// The runs, in channel order.
    pub runs: Vec<LoggedRun<'a>>,
    /// The scene's geometry, if it has one (then the 3D channels are written).
    pub geometry: Option<Geometry>,
    /// Metadata records, (name, key → value).
    pub metadata: Vec<(String, BTreeMap<String, String>)>,
    /// Attachments, (name, media type, bytes).
    pub attachments: Vec<(String, String, Vec<u8>)>,
}

fn mcap_error(e: std::io::Error) -> Error {
    Error::Other(format!("writing MCAP: {e}"))
}

/// Write `log` to `path` atomically, streamed: only the open chunk and the indexes are
/// held in memory, not the file.
pub fn write_mcap(log: &TraceLog, path: &Path) -> Result<(), Error> {
    write_atomically_with(path, |file| {
        // the compressed chunks (hundreds of kB) straight to the file, small records
        // gathered in a buffer below the atomic writer's (which stays empty): one copy of
        // every byte less
        let direct = std::io::BufWriter::with_capacity(DIRECT_BELOW, file.get_mut());
        write_mcap_to(log, direct, CHUNKS)?
            .flush()
            .map_err(mcap_error)
    })
}

/// Log time of a simulation time, ns (non-finite or negative times clamp to `floor`).
fn ns_of(t: f64, floor: u64) -> u64 {
    if t.is_finite() && t >= 0.0 {
        ((t * 1e9).round() as u64).max(floor)
    } else {
        floor
    }
}

/// Channel ids of one run.
struct RunChannels {
    /// The state channel: the row's channels and its contacts, one message a row.
    state: u16,
    /// (scene, forces, transform) when the run is drawn in 3D.
    view: Option<(u16, u16, u16)>,
}

/// The MCAP writer with the JSON messages' helper.
struct Out<W: Write> {
    w: McapWriter<W>,
}

impl<W: Write> Out<W> {
    fn put(&mut self, channel_id: u16, ns: u64, data: &[u8]) -> Result<(), Error> {
        self.w.message(channel_id, ns, data).map_err(mcap_error)
    }

    fn put_json(&mut self, channel_id: u16, ns: u64, v: &Value) -> Result<(), Error> {
        self.put(channel_id, ns, v.to_string().as_bytes())
    }
}

/// Records shorter than this are gathered before they are written; longer ones (the
/// compressed chunks) are written as they are.
const DIRECT_BELOW: usize = 64 << 10;

/// Chunks of the file: zstd at its fast level −3 in chunks of 1 MiB, each compressed in
/// one call. Measured on the 10⁶-step PEPO run (docs/performance.md §1, CPU of the whole
/// `rockslide run`, MCAP size): level 1 2.00 s, 139.6 MB; −1 1.88 s, 141.4 MB; −3 1.78 s,
/// 146.1 MB; −7 1.80 s, 176.2 MB; none 1.58 s, 313.1 MB. Full-precision doubles barely
/// compress: what zstd takes out is the framing, index entries and near-constant fields,
/// which its fastest levels find as well as level 1 does, until −3. With the contacts in
/// the state message (callgrind, 10⁵ − 10³ steps): −1 13,520 instructions a step, −3
/// 12,256, −5 12,016; the MCAP task, the longest of the file stage, −20 % at −3; the
/// default run's MCAP 13.73 → 14.51 MB (−5: 15.50 MB).
pub const CHUNKS: ChunkOptions = ChunkOptions {
    chunk_bytes: 1 << 20,
    compression: ChunkCompression::Zstd(-3),
};

/// The MCAP bytes of `log`.
pub fn mcap_bytes(log: &TraceLog) -> Result<Vec<u8>, Error> {
    mcap_bytes_with(log, CHUNKS)
}

/// The MCAP bytes of `log` with other chunk options (benchmarks compare them).
pub fn mcap_bytes_with(log: &TraceLog, chunks: ChunkOptions) -> Result<Vec<u8>, Error> {
    write_mcap_to(log, Vec::new(), chunks)
}

/// Write the MCAP file of `log` into `sink`; returns the sink. The order of its records:
/// attachments and metadata, schemas and channels, the static scenes at t = 0, then the
/// runs' rows interleaved in time.
fn write_mcap_to<W: Write>(log: &TraceLog, sink: W, options: ChunkOptions) -> Result<W, Error> {
    let mut out = Out {
        w: McapWriter::new(sink, options).map_err(mcap_error)?,
    };
    write_metadata(&mut out, log)?;
    let (channels, log_channel) = add_channels(&mut out, log)?;
    let mut buf = Vec::with_capacity(512);
    write_static_scenes(&mut out, log, &channels, &mut buf)?;
    write_rows(&mut out, log, &channels, log_channel, &mut buf)?;
    out.w.finish().map_err(mcap_error)
}

/// The attachments, the file's metadata and each run's (`run <label>`).
fn write_metadata<W: Write>(out: &mut Out<W>, log: &TraceLog) -> Result<(), Error> {
    for (name, media_type, data) in &log.attachments {
        out.w.attach(name, media_type, data).map_err(mcap_error)?;
    }
    for (name, m) in &log.metadata {
        out.w.metadata(name, m).map_err(mcap_error)?;
    }
    let run_meta = |run: &LoggedRun, topic: &str| {
        let mut m = run.metadata.clone();
        m.insert("label".into(), run.label.clone());
        m.insert("topic".into(), topic.into());
        m.insert("status".into(), run.status.clone());
        m.insert("rows".into(), run.trace.len().to_string());
        m.insert("end_time_s".into(), format!("{:?}", run.trace.end_time()));
        if let Some((t, reason)) = &run.stop {
            m.insert("stop_time_s".into(), format!("{t:?}"));
            m.insert("stop_reason".into(), reason.clone());
        }
        m
    };
    for run in &log.runs {
        let meta = run_meta(run, &format!("/{}/state", run.label));
        out.w
            .metadata(&format!("run {}", run.label), &meta)
            .map_err(mcap_error)?;
    }
    Ok(())
}

/// A ROS 2 schema of the 3D view.
fn ros2_schema<W: Write>(out: &mut Out<W>, m: &'static scene3d::Msg) -> Result<u16, Error> {
    out.w
        .add_schema(
            &m.schema_name(),
            cdr::SCHEMA_ENCODING,
            scene3d::definition(m).as_bytes(),
        )
        .map_err(mcap_error)
}

/// The schemas and channels: the 3D view's schemas (with a geometry), the log's, then each
/// run's state channel (and its view channels when drawn), then `/log`.
fn add_channels<W: Write>(
    out: &mut Out<W>,
    log: &TraceLog,
) -> Result<(Vec<RunChannels>, u16), Error> {
    let scene_schema = match &log.geometry {
        Some(_) => Some((
            ros2_schema(out, &scene3d::SCENE_UPDATE)?,
            ros2_schema(out, &scene3d::FRAME_TRANSFORMS)?,
        )),
        None => None,
    };
    let log_schema = out
        .w
        .add_schema(
            "foxglove.Log",
            "jsonschema",
            scene3d::log_schema().to_string().as_bytes(),
        )
        .map_err(mcap_error)?;
    let mut channels = Vec::with_capacity(log.runs.len());
    for run in &log.runs {
        let name = state_schema_name(&run.label);
        let schema = out
            .w
            .add_schema(
                &name,
                cdr::SCHEMA_ENCODING,
                cdr::state_definition(run.trace).as_bytes(),
            )
            .map_err(mcap_error)?;
        let meta = state_channel_metadata(run);
        let state = out
            .w
            .add_channel(
                schema,
                &format!("/{}/state", run.label),
                cdr::MESSAGE_ENCODING,
                &meta,
            )
            .map_err(mcap_error)?;
        let view = match scene_schema {
            Some((scene, tf)) if scene3d::drawable(run.trace) => {
                let none = BTreeMap::new();
                let mut ch = |schema: u16, suffix: &str| {
                    out.w
                        .add_channel(
                            schema,
                            &format!("/{}/{suffix}", run.label),
                            cdr::MESSAGE_ENCODING,
                            &none,
                        )
                        .map_err(mcap_error)
                };
                Some((
                    ch(scene, "scene")?,
                    ch(scene, "forces")?,
                    ch(tf, "transform")?,
                ))
            }
            _ => None,
        };
        channels.push(RunChannels { state, view });
    }
    let log_channel = out
        .w
        .add_channel(log_schema, "/log", "json", &BTreeMap::new())
        .map_err(mcap_error)?;
    Ok((channels, log_channel))
}

/// A run's state channel metadata: the run, its fields and units, its contacts.
fn state_channel_metadata(run: &LoggedRun) -> BTreeMap<String, String> {
    let mut meta = BTreeMap::new();
    meta.insert("run".to_string(), run.label.clone());
    meta.insert(
        "fields".to_string(),
        run.trace
            .channels
            .iter()
            .map(|c| c.key)
            .collect::<Vec<_>>()
            .join(","),
    );
    meta.insert(
        "units".to_string(),
        run.trace
            .channels
            .iter()
            .map(|c| c.unit)
            .collect::<Vec<_>>()
            .join(","),
    );
    contact_metadata(&mut meta, &run.trace.contacts);
    meta
}

/// The static scenes, at t = 0 (the datum with the first).
fn write_static_scenes<W: Write>(
    out: &mut Out<W>,
    log: &TraceLog,
    channels: &[RunChannels],
    buf: &mut Vec<u8>,
) -> Result<(), Error> {
    if let Some(g) = &log.geometry {
        let mut first = true;
        for (lane, (run, ch)) in log.runs.iter().zip(channels).enumerate() {
            if let Some((scene, _, _)) = ch.view {
                let mut s = scene3d::static_scene(g, lane, &run.label);
                if first {
                    if let Some(e) = s["entities"].as_array_mut() {
                        e.push(scene3d::datum(g));
                    }
                    first = false;
                }
                scene3d::encode(&scene3d::SCENE_UPDATE, &s, buf);
                out.put(scene, 0, buf)?;
            }
        }
    }
    Ok(())
}

/// The runs' rows: state messages, the 3D view at its period, and a log line at each run's
/// end.
fn write_rows<W: Write>(
    out: &mut Out<W>,
    log: &TraceLog,
    channels: &[RunChannels],
    log_channel: u16,
    buf: &mut Vec<u8>,
) -> Result<(), Error> {
    // Interleave the runs' rows in time order (ties: run order). Each run's next log
    // time is computed once, when the run moves on (its rows' times never go back: each
    // is clamped to the one before).
    let frame_names: Vec<(String, String)> = log
        .runs
        .iter()
        .map(|run| scene3d::frames(&run.label))
        .collect();
    let mut row = vec![0usize; log.runs.len()];
    let mut next_ns: Vec<Option<u64>> = log
        .runs
        .iter()
        .map(|run| run.trace.time.first().map(|&t| ns_of(t, 0)))
        .collect();
    let mut next_view = vec![0u64; log.runs.len()];
    let view_period: Vec<u64> = log
        .runs
        .iter()
        .map(|run| scene_period_ns(run.trace.end_time()))
        .collect();
    loop {
        let mut next: Option<(usize, u64)> = None;
        for (r, ns) in next_ns.iter().enumerate() {
            if let Some(ns) = *ns
                && next.is_none_or(|(_, earliest)| ns < earliest)
            {
                next = Some((r, ns));
            }
        }
        let Some((r, ns)) = next else { break };
        let (run, ch, i) = (&log.runs[r], &channels[r], row[r]);
        out.w
            .message_with(ch.state, ns, |r| cdr::append_state_message(r, run.trace, i))
            .map_err(mcap_error)?;
        let last_row = i + 1 == run.trace.len();
        if let (Some((_, forces, tf)), Some(g)) = (ch.view, &log.geometry)
            && (ns >= next_view[r] || last_row)
            && let Some(p) = Pose::at(run.trace, i, g)
        {
            let lane_y = r as f64 * g.lane_spacing();
            let (ground, body) = &frame_names[r];
            let frames = (ground.as_str(), body.as_str());
            scene3d::encode_frame_transforms(ns, run.trace, i, lane_y, &p, frames, buf);
            out.put(tf, ns, buf)?;
            scene3d::encode_forces(run.trace, i, ns, g, &p, ground, buf);
            out.put(forces, ns, buf)?;
            next_view[r] = ns + view_period[r];
        }
        if last_row {
            let (level, text) = match &run.stop {
                None => (2, format!("{}: {}", run.label, run.status)),
                Some((t, reason)) => (
                    4,
                    format!("{}: {} at t = {t} s: {reason}", run.label, run.status),
                ),
            };
            let at = run.stop.as_ref().map_or(ns, |(t, _)| ns_of(*t, ns));
            out.put_json(log_channel, at, &scene3d::log(at, level, &run.label, &text))?;
        }
        row[r] += 1;
        next_ns[r] = run.trace.time.get(row[r]).map(|&t| ns_of(t, ns));
    }
    Ok(())
}

/// The contacts a state channel carries after its fields, in its metadata: their names
/// in order (`contacts`), each one's normal compliance in m/N (`contact_compliance`, as
/// Rust's shortest round-trip decimals), and the fields and units of each
/// (`contact_fields`, `contact_units`). Nothing for a run without a contact block.
fn contact_metadata(meta: &mut BTreeMap<String, String>, block: &ContactBlock) {
    if block.count() == 0 {
        return;
    }
    meta.insert("contacts".to_string(), block.names.join(","));
    let compliance: Vec<String> = block.compliance.iter().map(|c| format!("{c:?}")).collect();
    meta.insert("contact_compliance".to_string(), compliance.join(","));
    let (fields, units): (Vec<&str>, Vec<&str>) =
        CONTACT_FIELDS.iter().map(|(k, u, _)| (*k, *u)).unzip();
    meta.insert("contact_fields".to_string(), fields.join(","));
    meta.insert("contact_units".to_string(), units.join(","));
}

/// The contact block a state channel's metadata announces (empty, without rows).
fn contact_block_of(meta: &BTreeMap<String, String>) -> ContactBlock {
    let list = |key: &str| -> Vec<&str> {
        meta.get(key)
            .map_or("", String::as_str)
            .split(',')
            .filter(|n| !n.is_empty())
            .collect()
    };
    let names = list("contacts");
    let compliance: Vec<f64> = list("contact_compliance")
        .iter()
        .map(|c| c.parse().unwrap_or(f64::NAN))
        .chain(std::iter::repeat(f64::NAN))
        .take(names.len())
        .collect();
    ContactBlock::with_contacts(&names, &compliance, 0)
}

/// One channel of an MCAP file, as read back.
#[derive(Debug, Clone, PartialEq)]
pub struct McapChannel {
    /// Topic.
    pub topic: String,
    /// Schema name (empty: none).
    pub schema: String,
    /// Schema encoding.
    pub schema_encoding: String,
    /// Message encoding.
    pub message_encoding: String,
    /// Channel metadata.
    pub metadata: BTreeMap<String, String>,
    /// Number of messages read.
    pub messages: u64,
}

/// An MCAP file read back and checked: channels, the state traces, metadata, attachments.
#[derive(Debug, Clone, Default)]
pub struct McapContents {
    /// Number of messages read (checked against the summary's statistics).
    pub message_count: u64,
    /// First and last message log time, ns.
    pub time_range: (u64, u64),
    /// Every channel, by id order.
    pub channels: Vec<McapChannel>,
    /// The `rockslide/State*` channels as traces, (topic, trace), in channel order.
    pub states: Vec<(String, Trace)>,
    /// The contact channels of files written before the contacts joined the state
    /// messages (`/<label>/contacts`, schema `rockslide/Contacts*`), as contact blocks,
    /// (topic, block); a newer file's contacts are in its state traces' `contacts`.
    pub contacts: Vec<(String, ContactBlock)>,
    /// Metadata records by name.
    pub metadata: BTreeMap<String, BTreeMap<String, String>>,
    /// Attachments: (name, media type, bytes).
    pub attachments: Vec<(String, String, Vec<u8>)>,
}

impl McapContents {
    /// The trace of a state topic (`/fe/double/state`).
    pub fn state(&self, topic: &str) -> Option<&Trace> {
        self.states.iter().find(|(t, _)| t == topic).map(|(_, t)| t)
    }

    /// The contact block of a run (`fe/single`): carried by its state messages, or by its
    /// own `/<label>/contacts` channel in a file written before they were one message.
    pub fn contact_block(&self, label: &str) -> Option<&ContactBlock> {
        let in_state = self
            .state(&format!("/{label}/state"))
            .map(|t| &t.contacts)
            .filter(|b| b.count() > 0);
        let legacy = format!("/{label}/contacts");
        in_state.or_else(|| {
            self.contacts
                .iter()
                .find(|(t, _)| *t == legacy)
                .map(|(_, b)| b)
        })
    }
}

/// Read and check an MCAP file: structure, CRCs, summary, every message's JSON; the
/// state channels become traces. Any damage is one clear error naming the file.
pub fn read_mcap(path: &Path) -> Result<McapContents, InputErrors> {
    let bytes = read_bounded(path, MAX_MCAP_BYTES)
        .map_err(|e| InputError::new(path, "", format!("cannot read the MCAP file: {e}")))?;
    read_mcap_bytes(path, &bytes)
}

/// Largest MCAP file `trace-info` reads (1 GiB; rockslide's own are a few MB).
pub const MAX_MCAP_BYTES: u64 = 1 << 30;

/// Largest uncompressed chunk accepted (256 MiB; rockslide writes chunks under 1 MB).
pub const MAX_CHUNK_BYTES: u64 = 256 << 20;

/// The file's bytes, refusing more than `limit` (read through a bounded reader, so that a
/// device such as `/dev/zero` or a file growing while read cannot exhaust memory).
pub(crate) fn read_bounded(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let file = std::fs::File::open(path)?;
    let mut bytes = Vec::new();
    file.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(std::io::Error::other(format!(
            "larger than the limit of {limit} bytes"
        )));
    }
    Ok(bytes)
}

/// Walk the top-level records of an MCAP file before the `mcap` crate parses them: every
/// record's length must fit in the file, and every chunk's declared uncompressed size must
/// be within [`MAX_CHUNK_BYTES`] — so that a flipped byte gives an error instead of an
/// allocation of exabytes.
fn check_framing(bytes: &[u8]) -> Result<(), String> {
    const MAGIC: &[u8] = b"\x89MCAP0\r\n";
    const CHUNK: u8 = 0x06;
    const FOOTER: u8 = 0x02;
    if !bytes.starts_with(MAGIC) {
        return Err("does not start with the MCAP magic bytes".into());
    }
    let mut at = MAGIC.len();
    loop {
        let Some(head) = bytes.get(at..at + 9) else {
            return Err(format!("record header cut short at byte {at}"));
        };
        let op = head[0];
        let len = u64_at(head, 1);
        let body_start = at + 9;
        let remaining = (bytes.len() - body_start) as u64;
        if len > remaining {
            return Err(format!(
                "record 0x{op:02x} at byte {at} claims {len} bytes, only {remaining} follow"
            ));
        }
        let body = &bytes[body_start..body_start + len as usize];
        check_fields(op, body).map_err(|why| format!("record 0x{op:02x} at byte {at}: {why}"))?;
        if op == CHUNK {
            check_chunk(body).map_err(|why| format!("chunk at byte {at}: {why}"))?;
        }
        at = body_start + len as usize;
        if op == FOOTER {
            return if bytes[at..].starts_with(MAGIC) {
                Ok(())
            } else {
                Err("no closing magic bytes after the footer".into())
            };
        }
    }
}

/// The fields of a record's body, in the MCAP specification's layout: fixed-size
/// integers (`1`, `2`, `4`, `8` bytes), strings and byte arrays with a u32 length (`s`),
/// byte arrays with a u64 length (`b`), maps with a u32 byte length (`m`; `M` a map of
/// strings to strings, whose every entry is checked too); `r` the rest.
fn layout(op: u8) -> &'static [u8] {
    match op {
        0x01 => b"ss",        // header: profile, library
        0x02 => b"884",       // footer
        0x03 => b"2sss",      // schema: id, name, encoding, data (u32 length)
        0x04 => b"22ssM",     // channel
        0x05 => b"2488r",     // message
        0x06 => b"8884sb",    // chunk
        0x07 => b"2m",        // message index: channel, records (u32 byte length)
        0x08 => b"8888m8s88", // chunk index
        0x09 => b"88ssb4",    // attachment
        0x0A => b"88888ss",   // attachment index
        0x0B => b"82444488m", // statistics
        0x0C => b"sM",        // metadata
        0x0D => b"88s",       // metadata index
        0x0E => b"188",       // summary offset
        0x0F => b"4",         // data end
        _ => b"r",            // unknown: skipped by readers
    }
}

/// Every length prefix of the record's fields fits inside its body.
fn check_fields(op: u8, body: &[u8]) -> Result<(), String> {
    let mut at = 0usize;
    let take = |at: &mut usize, n: u64, what: &str| -> Result<(), String> {
        let left = (body.len() - *at) as u64;
        if n > left {
            return Err(format!(
                "{what} of {n} bytes, only {left} left in the record"
            ));
        }
        *at += n as usize;
        Ok(())
    };
    for &f in layout(op) {
        match f {
            b'1' | b'2' | b'4' | b'8' => take(&mut at, u64::from(f - b'0'), "a field")?,
            b's' | b'm' | b'M' => {
                let n = body
                    .get(at..at + 4)
                    .map(|b| u64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])));
                take(&mut at, 4, "a length")?;
                let start = at;
                take(&mut at, n.unwrap_or(0), "a string, array or map")?;
                if f == b'M' {
                    check_string_map(&body[start..at])?;
                }
            }
            b'b' => {
                let n = body.get(at..at + 8).map(|b| u64_at(b, 0));
                take(&mut at, 8, "a length")?;
                take(&mut at, n.unwrap_or(0), "a byte array")?;
            }
            _ => return Ok(()),
        }
    }
    Ok(())
}

/// Every key and value of a map of strings (u32 length each) lies inside the map: the
/// `mcap` crate reserves a string's declared length before reading it.
fn check_string_map(map: &[u8]) -> Result<(), String> {
    let mut at = 0usize;
    while at < map.len() {
        let Some(len) = map.get(at..at + 4) else {
            return Err(format!(
                "a map entry's length cut short at byte {at} of the map"
            ));
        };
        let n = u32::from_le_bytes([len[0], len[1], len[2], len[3]]) as u64;
        let left = (map.len() - at - 4) as u64;
        if n > left {
            return Err(format!(
                "a map string of {n} bytes, only {left} left in the map"
            ));
        }
        at += 4 + n as usize;
    }
    Ok(())
}

/// A chunk's declared size within [`MAX_CHUNK_BYTES`] (checked before anything reads the
/// file; its records are checked when [`for_each_message`] decompresses it).
fn check_chunk(body: &[u8]) -> Result<(), String> {
    // layout 8884sb, checked by `check_fields`
    let declared = u64_at(body, 16);
    if declared > MAX_CHUNK_BYTES {
        return Err(format!(
            "claims {declared} uncompressed bytes, above the limit of {MAX_CHUNK_BYTES}"
        ));
    }
    Ok(())
}

/// A chunk's records, decompressed once, checked against the chunk's CRC (when it has
/// one) and framed as the file's are: every inner record's length fits, and the fields of
/// each fit in it (the `mcap` crate trusts them).
fn chunk_records(body: &[u8]) -> Result<std::borrow::Cow<'_, [u8]>, String> {
    let declared = u64_at(body, 16);
    let crc = u32::from_le_bytes([body[24], body[25], body[26], body[27]]);
    let name_len = u32::from_le_bytes([body[28], body[29], body[30], body[31]]) as usize;
    let compression = &body[32..32 + name_len];
    let records = &body[32 + name_len + 8..];
    let inner: std::borrow::Cow<'_, [u8]> = match compression {
        b"" => records.into(),
        b"zstd" => decompress_at_most(records, declared)?.into(),
        b"lz4" => lz4_at_most(records, declared)?.into(),
        other => {
            return Err(format!(
                "compression \"{}\" is not read (zstd, lz4 and none are)",
                String::from_utf8_lossy(other)
            ));
        }
    };
    if inner.len() as u64 != declared {
        return Err(format!(
            "holds {} uncompressed bytes, declares {declared}",
            inner.len()
        ));
    }
    if crc != 0 && crc32fast::hash(&inner) != crc {
        return Err("its records do not match its CRC".into());
    }
    let mut at = 0usize;
    while at < inner.len() {
        let Some(head) = inner.get(at..at + 9) else {
            return Err(format!("inner record header cut short at byte {at}"));
        };
        let (op, len) = (head[0], u64_at(head, 1));
        let remaining = (inner.len() - at - 9) as u64;
        if len > remaining {
            return Err(format!(
                "inner record 0x{op:02x} claims {len} bytes, only {remaining} follow"
            ));
        }
        let body = &inner[at + 9..at + 9 + len as usize];
        check_fields(op, body).map_err(|why| format!("inner record 0x{op:02x}: {why}"))?;
        at += 9 + len as usize;
    }
    Ok(inner)
}

/// The records of `bytes` (a data section or a chunk's records), as (offset, opcode,
/// body); stops at the first that does not fit.
fn records(bytes: &[u8]) -> impl Iterator<Item = (usize, u8, &[u8])> {
    let mut at = 0usize;
    std::iter::from_fn(move || {
        let head = bytes.get(at..at + 9)?;
        let (op, len) = (head[0], usize::try_from(u64_at(head, 1)).ok()?);
        let body = bytes.get(at + 9..(at + 9).checked_add(len)?)?;
        let here = at;
        at += 9 + len;
        Some((here, op, body))
    })
}

/// One message as read: channel id, sequence, log time, data.
struct RawMessage<'a> {
    channel: u16,
    sequence: u32,
    log_time: u64,
    data: &'a [u8],
}

/// The message of a message record's body (22 bytes of header, then the data).
fn raw_message(body: &[u8]) -> Result<RawMessage<'_>, String> {
    if body.len() < 22 {
        return Err(format!(
            "a message record of {} bytes, shorter than its header",
            body.len()
        ));
    }
    Ok(RawMessage {
        channel: u16::from_le_bytes([body[0], body[1]]),
        sequence: u32::from_le_bytes([body[2], body[3], body[4], body[5]]),
        log_time: u64_at(body, 6),
        data: &body[22..],
    })
}

/// Every message of the data section in file order, each chunk decompressed once (the
/// file's framing already checked by [`check_framing`]).
fn for_each_message(
    bytes: &[u8],
    mut on: impl FnMut(RawMessage) -> Result<(), InputError>,
) -> Result<(), Result<String, InputError>> {
    const MAGIC_LEN: usize = 8;
    const MESSAGE: u8 = 0x05;
    const CHUNK: u8 = 0x06;
    const DATA_END: u8 = 0x0F;
    const FOOTER: u8 = 0x02;
    for (at, op, body) in records(&bytes[MAGIC_LEN..]) {
        match op {
            MESSAGE => on(raw_message(body).map_err(Ok)?).map_err(Err)?,
            CHUNK => {
                let inner = chunk_records(body)
                    .map_err(|why| Ok(format!("chunk at byte {}: {why}", at + MAGIC_LEN)))?;
                for (_, op, body) in records(&inner) {
                    if op == MESSAGE {
                        on(raw_message(body).map_err(Ok)?).map_err(Err)?;
                    }
                }
            }
            DATA_END | FOOTER => break,
            _ => {}
        }
    }
    Ok(())
}

/// A zstd chunk's records, at most `declared` bytes of them. The buffer grows with what
/// actually decompresses instead of being reserved at the declared size up front, so a
/// small corrupt file that claims a large chunk costs memory in proportion to its real
/// content, not to its claim.
fn decompress_at_most(records: &[u8], declared: u64) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let decoder = zstd::stream::read::Decoder::new(records)
        .map_err(|e| format!("does not decompress: {e}"))?;
    let mut inner = Vec::new();
    decoder
        .take(declared + 1)
        .read_to_end(&mut inner)
        .map_err(|e| format!("does not decompress: {e}"))?;
    if inner.len() as u64 > declared {
        return Err(format!(
            "decompresses to more than its declared {declared} uncompressed bytes"
        ));
    }
    Ok(inner)
}

/// An lz4 chunk's records (an LZ4 frame), at most `declared` bytes of them, grown as
/// [`decompress_at_most`] grows a zstd chunk's.
fn lz4_at_most(records: &[u8], declared: u64) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let decoder =
        lz4::Decoder::new(records).map_err(|e| format!("does not decompress (lz4): {e}"))?;
    let mut inner = Vec::new();
    decoder
        .take(declared + 1)
        .read_to_end(&mut inner)
        .map_err(|e| format!("does not decompress (lz4): {e}"))?;
    if inner.len() as u64 > declared {
        return Err(format!(
            "decompresses to more than its declared {declared} uncompressed bytes"
        ));
    }
    Ok(inner)
}

fn u64_at(b: &[u8], i: usize) -> u64 {
    let mut le = [0u8; 8];
    le.copy_from_slice(&b[i..i + 8]);
    u64::from_le_bytes(le)
}

/// [`read_mcap`] on bytes already in memory (`path` names them in messages).
pub fn read_mcap_bytes(path: &Path, bytes: &[u8]) -> Result<McapContents, InputErrors> {
    let damaged = |what: &str, e: &dyn std::fmt::Display| {
        InputError::new(
            path,
            "",
            format!("not a readable MCAP file ({what}: {e}); it may be truncated or corrupt"),
        )
    };
    check_framing(bytes).map_err(|why| damaged("framing", &why))?;
    let summary = mcap::read::Summary::read(bytes)
        .map_err(|e| damaged("summary", &e))?
        .ok_or_else(|| {
            InputError::new(
                path,
                "",
                "the MCAP file has no summary section (not written by rockslide, or cut short)",
            )
        })?;
    let (mut contents, index) = read_channels(path, &summary)?;
    let (first, last) = read_messages(path, bytes, &summary, &index, &mut contents)?;
    contents.time_range = if first <= last { (first, last) } else { (0, 0) };
    if let Some(stats) = &summary.stats
        && stats.message_count != contents.message_count
    {
        return Err(damaged(
            "statistics",
            &format!(
                "{} messages read, {} in the summary",
                contents.message_count, stats.message_count
            ),
        )
        .into());
    }
    for idx in &summary.metadata_indexes {
        let m = mcap::read::metadata(bytes, idx).map_err(|e| damaged("metadata", &e))?;
        contents.metadata.insert(m.name, m.metadata);
    }
    for idx in &summary.attachment_indexes {
        let a = mcap::read::attachment(bytes, idx).map_err(|e| damaged("attachment", &e))?;
        contents
            .attachments
            .push((a.name, a.media_type, a.data.into_owned()));
    }
    Ok(contents)
}

/// Where each channel's messages go: its index in [`McapContents::channels`], the state
/// trace it fills (with its quantities) or the old contact block.
#[derive(Default)]
struct ChannelIndex {
    index_of: BTreeMap<u16, usize>,
    builders: BTreeMap<u16, (usize, Vec<&'static Quantity>)>,
    contact_channels: BTreeMap<u16, usize>,
}

/// The contents' channels from the summary (by id), with an empty trace per state channel
/// and an empty block per old contact channel.
fn read_channels(
    path: &Path,
    summary: &mcap::read::Summary,
) -> Result<(McapContents, ChannelIndex), InputError> {
    let mut contents = McapContents::default();
    let mut ids: Vec<u16> = summary.channels.keys().copied().collect();
    ids.sort_unstable();
    let mut index_of = BTreeMap::new();
    let mut builders: BTreeMap<u16, (usize, Vec<&'static Quantity>)> = BTreeMap::new();
    let mut contact_channels: BTreeMap<u16, usize> = BTreeMap::new();
    for id in ids {
        let c = &summary.channels[&id];
        let (schema, schema_encoding) = c
            .schema
            .as_ref()
            .map_or((String::new(), String::new()), |s| {
                (s.name.clone(), s.encoding.clone())
            });
        let state = schema.starts_with(STATE_SCHEMA) || schema.starts_with(JSON_STATE_SCHEMA);
        if state && c.metadata.contains_key("fields") {
            let fields = c.metadata.get("fields").map_or("", String::as_str);
            let mut qs = Vec::new();
            for key in fields.split(',').filter(|k| !k.is_empty()) {
                qs.push(q::by_key(key).ok_or_else(|| {
                    InputError::new(
                        path,
                        "",
                        format!("channel {}: unknown quantity \"{key}\"", c.topic),
                    )
                })?);
            }
            builders.insert(id, (contents.states.len(), qs.clone()));
            let mut trace = Trace::with_channels(&qs, 0);
            trace.contacts = contact_block_of(&c.metadata);
            contents.states.push((c.topic.clone(), trace));
        }
        if schema.starts_with(contacts::CONTACTS_SCHEMA)
            || schema.starts_with(contacts::JSON_CONTACTS_SCHEMA)
        {
            let names = c.metadata.get("contacts").map_or("", String::as_str);
            let names: Vec<&str> = names.split(',').filter(|n| !n.is_empty()).collect();
            contact_channels.insert(id, contents.contacts.len());
            let block = ContactBlock::with_contacts(&names, &vec![0.0; names.len()], 0);
            contents.contacts.push((c.topic.clone(), block));
        }
        index_of.insert(id, contents.channels.len());
        contents.channels.push(McapChannel {
            topic: c.topic.clone(),
            schema,
            schema_encoding,
            message_encoding: c.message_encoding.clone(),
            metadata: c.metadata.clone(),
            messages: 0,
        });
    }
    Ok((
        contents,
        ChannelIndex {
            index_of,
            builders,
            contact_channels,
        },
    ))
}

/// Every message read into `contents` (counted per channel; states, old contact blocks
/// and JSON decoded, the 3D view decoded to check it); returns the first and last log
/// times.
fn read_messages(
    path: &Path,
    bytes: &[u8],
    summary: &mcap::read::Summary,
    index: &ChannelIndex,
    contents: &mut McapContents,
) -> Result<(u64, u64), InputError> {
    let damaged = |what: &str, e: &dyn std::fmt::Display| {
        InputError::new(
            path,
            "",
            format!("not a readable MCAP file ({what}: {e}); it may be truncated or corrupt"),
        )
    };
    let mut values = Vec::new();
    let (mut first, mut last) = (u64::MAX, 0u64);
    let mut topics: BTreeMap<u16, String> = BTreeMap::new();
    for (id, c) in &summary.channels {
        topics.insert(*id, c.topic.clone());
    }
    for_each_message(bytes, |m| {
        let id = m.channel;
        let Some(&ci) = index.index_of.get(&id) else {
            return Err(damaged("data", &format!("message on unknown channel {id}")));
        };
        let topic = &topics[&id];
        contents.channels[ci].messages += 1;
        contents.message_count += 1;
        first = first.min(m.log_time);
        last = last.max(m.log_time);
        let bad = |e: &dyn std::fmt::Display| {
            InputError::new(
                path,
                "",
                format!(
                    "channel {topic}, message {}: not valid JSON for its schema: {e}",
                    m.sequence
                ),
            )
        };
        let is_cdr = contents.channels[ci].message_encoding == cdr::MESSAGE_ENCODING;
        if let Some((si, qs)) = index.builders.get(&id)
            && is_cdr
        {
            push_cdr_state(&mut contents.states[*si].1, qs.len(), m.data, &mut values).map_err(
                |e| {
                    InputError::new(
                        path,
                        "",
                        format!("channel {topic}, message {}: {e}", m.sequence),
                    )
                },
            )?;
        } else if let Some(&bi) = index.contact_channels.get(&id)
            && is_cdr
        {
            push_cdr_contacts(&mut contents.contacts[bi].1, m.data, &mut values).map_err(|e| {
                InputError::new(
                    path,
                    "",
                    format!("channel {topic}, message {}: {e}", m.sequence),
                )
            })?;
        } else if let Some((si, qs)) = index.builders.get(&id) {
            let obj: BTreeMap<String, Option<f64>> =
                serde_json::from_slice(m.data).map_err(|e| bad(&e))?;
            let field = |k: &str| {
                obj.get(k)
                    .map(|v| v.unwrap_or(f64::NAN))
                    .ok_or_else(|| bad(&format!("missing field \"{k}\"")))
            };
            let t = field("time")?;
            values.clear();
            for qty in qs {
                values.push(field(qty.key)?);
            }
            contents.states[*si].1.push(t, &values);
        } else if let Some(&bi) = index.contact_channels.get(&id) {
            read_contact_message(&mut contents.contacts[bi].1, m.data).map_err(|e| bad(&e))?;
        } else if contents.channels[ci].message_encoding == "json" {
            serde_json::from_slice::<serde::de::IgnoredAny>(m.data).map_err(|e| bad(&e))?;
        } else if let Some(ty) = scene3d::message_type(&contents.channels[ci].schema)
            && is_cdr
        {
            // the 3D view: decoded to check it, not kept
            scene3d::decode(ty, m.data).map_err(|e| bad(&e))?;
        }
        Ok(())
    })
    .map_err(|e| match e {
        Ok(why) => damaged("data", &why),
        Err(e) => e,
    })?;
    Ok((first, last))
}

/// An old CDR contact message appended to its block; `values` is scratch.
fn push_cdr_contacts(
    block: &mut ContactBlock,
    data: &[u8],
    values: &mut Vec<f64>,
) -> Result<(), String> {
    let width = block.count() * CONTACT_FIELDS.len();
    cdr::read_values(data, width + 1, values)
        .map_err(|e| format!("not a CDR contact message of {} values: {e}", width + 1))?;
    block.push_values(values[0], &values[1..]);
    Ok(())
}

/// A CDR state message appended to its trace (and the contacts it carries to the trace's
/// block); `values` is scratch.
fn push_cdr_state(
    trace: &mut Trace,
    quantities: usize,
    data: &[u8],
    values: &mut Vec<f64>,
) -> Result<(), String> {
    let count = cdr::state_values(trace);
    cdr::read_values(data, count, values)
        .map_err(|e| format!("not a CDR state message of {count} values: {e}"))?;
    let (row, contact_values) = values[1..].split_at(quantities);
    trace.push(values[0], row);
    if trace.contacts.count() > 0 {
        trace.contacts.push_values(values[0], contact_values);
    }
    Ok(())
}

/// One contact message appended to its block: `time` and, per contact, its four fields.
fn read_contact_message(block: &mut ContactBlock, data: &[u8]) -> Result<(), String> {
    let obj: BTreeMap<String, Value> = serde_json::from_slice(data).map_err(|e| e.to_string())?;
    let number = |v: Option<&Value>, what: &str| match v {
        Some(Value::Null) => Ok(f64::NAN),
        Some(v) => v.as_f64().ok_or_else(|| format!("{what} is not a number")),
        None => Err(format!("missing field \"{what}\"")),
    };
    let t = number(obj.get("time"), "time")?;
    let mut row = Vec::with_capacity(block.count());
    for name in &block.names {
        let c = obj.get(name);
        let field = |k: &str| number(c.and_then(|c| c.get(k)), &format!("{name}.{k}"));
        row.push(ContactState {
            normal: field("normal")?,
            tangential: field("tangential")?,
            slip: field("slip")?,
            gap: field("gap")?,
        });
    }
    block.push(t, &row);
    Ok(())
}

/// A human summary of an MCAP file (`rockslide trace-info`): channels, time range,
/// metadata, attachments.
pub fn describe(contents: &McapContents) -> String {
    let mut s = String::new();
    let (t0, t1) = contents.time_range;
    let _ = writeln!(
        s,
        "{} messages, simulation time {} s to {} s",
        contents.message_count,
        t0 as f64 * 1e-9,
        t1 as f64 * 1e-9
    );
    let _ = writeln!(s, "channels:");
    for c in &contents.channels {
        let _ = writeln!(s, "  {:<40} {:>8} msgs  {}", c.topic, c.messages, c.schema);
        if let Some(f) = c.metadata.get("fields") {
            let _ = writeln!(s, "  {:<40} fields: time,{f}", "");
        }
        if let (Some(names), Some(fields)) =
            (c.metadata.get("contacts"), c.metadata.get("contact_fields"))
        {
            let _ = writeln!(s, "  {:<40} contacts: {names} (each {fields})", "");
        }
    }
    for (name, m) in &contents.metadata {
        let _ = writeln!(s, "metadata \"{name}\":");
        for (k, v) in m {
            let _ = writeln!(s, "  {k} = {}", v.replace('\n', " "));
        }
    }
    for (name, media, data) in &contents.attachments {
        let _ = writeln!(s, "attachment {name} ({media}, {} bytes)", data.len());
    }
    s
}

/// Read an MCAP file and describe it (`rockslide trace-info`).
pub fn mcap_info(path: &Path) -> Result<String, Error> {
    Ok(describe(&read_mcap(path)?))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A run with one contact, its contacts in its state messages, written with every
    /// chunk compression and read back: every value and contact field bit for bit.
    #[test]
    fn states_and_their_contacts_read_back_from_every_chunk_compression() {
        let mut trace = Trace::with_channels(&[&q::RESISTANCE, &q::SLIDE], 3);
        trace.contacts = ContactBlock::with_contacts(&["base"], &[2.5e-10], 3);
        for (i, x) in [0.0, -0.0, f64::NAN].into_iter().enumerate() {
            let t = i as f64 * 1e-3;
            trace.push(t, &[x, 1e-300 * i as f64]);
            let c = ContactState {
                normal: 9.81e6,
                tangential: x,
                slip: -1.5 * i as f64,
                gap: f64::INFINITY,
            };
            trace.contacts.push(t, &[c]);
        }
        let log = TraceLog {
            runs: vec![LoggedRun {
                label: "pc/paper".into(),
                trace: &trace,
                status: "completed".into(),
                stop: None,
                metadata: BTreeMap::new(),
            }],
            ..TraceLog::default()
        };
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for compression in [
            CHUNKS.compression,
            ChunkCompression::Zstd(-1),
            ChunkCompression::Lz4(0),
            ChunkCompression::None,
        ] {
            let chunks = ChunkOptions {
                chunk_bytes: 64,
                compression,
            };
            let bytes = mcap_bytes_with(&log, chunks).unwrap();
            let m = read_mcap_bytes(Path::new("t.mcap"), &bytes).unwrap();
            assert_eq!(m.channels.len(), 2, "{compression:?}: state and log");
            let back = m.state("/pc/paper/state").unwrap();
            assert_eq!(bits(&back.time), bits(&trace.time));
            for (a, b) in back.columns.iter().zip(&trace.columns) {
                assert_eq!(bits(a), bits(b), "{compression:?}");
            }
            let block = m.contact_block("pc/paper").unwrap();
            assert_eq!(block.names, ["base"]);
            assert_eq!(block.compliance, [2.5e-10]);
            assert_eq!(bits(&block.time), bits(&trace.contacts.time));
            assert_eq!(bits(&block.values), bits(&trace.contacts.values));
        }
    }

    #[test]
    fn a_chunk_costs_memory_for_what_it_holds_not_for_what_it_claims() {
        let content: Vec<u8> = (0..1000u32).map(|i| (i % 251) as u8).collect();
        let packed = zstd::bulk::compress(&content, 1).unwrap();
        assert_eq!(decompress_at_most(&packed, 1000).unwrap(), content);
        // a claim of 200 MiB for 1000 bytes: the buffer follows the bytes, not the claim
        let inner = decompress_at_most(&packed, 200 << 20).unwrap();
        assert_eq!(inner, content);
        assert!(inner.capacity() < 1 << 20, "{}", inner.capacity());
        let e = decompress_at_most(&packed, 999).unwrap_err();
        assert!(e.contains("more than its declared 999"), "{e}");
        assert!(decompress_at_most(b"not zstd", 10).is_err());
    }
}

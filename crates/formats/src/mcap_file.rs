//! MCAP traces: every run of a case in one MCAP file that Foxglove (or any MCAP reader)
//! opens, plots and animates (this file, over our chunk writer `writer`); and reading such
//! a file back (`read`: `rockslide trace-info`, external participants, tests).
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
use std::io::Write;
use std::path::Path;

use serde_json::Value;

use rockslide_core::error::Error;
use rockslide_core::io::write_atomically_with;
use rockslide_core::trace::{CONTACT_FIELDS, ContactBlock, Trace};

use crate::cdr;
use crate::scene3d::{self, Geometry, Pose};

mod read;
mod writer;
pub(crate) use read::read_bounded;
pub use read::{McapChannel, McapContents, describe, mcap_info, read_mcap, read_mcap_bytes};
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

#[cfg(test)]
mod tests {
    use super::*;
    use rockslide_core::trace::{ContactState, q};

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
}

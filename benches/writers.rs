//! The trace writers alone, per row, on a real trace: the predictor-corrector on the PEPO
//! (cases/pepo-mass-accel.toml at Δt = 1 ms) run for 1,000 s, 10⁶ rows — the CSV file
//! (`write_csv`) and the MCAP file (`write_mcap`), streamed to a temporary folder; and the
//! MCAP chunk compression choices (zstd levels, lz4, none; chunk sizes) on the same
//! messages, with the file size of each printed beside its time — our chunk writer (what
//! `write_mcap` uses) beside the `mcap` crate's; and the two encodings of
//! the state messages compared — JSON of shortest decimals (before) and CDR (now) — each
//! encoded and written to MCAP with the chosen compression.
//!
//! Run: `cargo bench --bench writers`. Results are recorded in benches/runs/ (dated, per machine).

use std::collections::BTreeMap;
use std::hint::black_box;
use std::io::Cursor;
use std::path::Path;
use std::time::Duration;

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, Throughput, criterion_group, criterion_main};
use rockslide::case::parse_case;
use rockslide::engine;
use rockslide::engine::predictor_corrector::variant as pc_variant;
use rockslide::formats::{
    CDR_LE_HEADER, CHUNKS, ChunkCompression, ChunkOptions, LoggedRun, McapWriter, TraceLog,
    mcap_bytes, write_csv, write_mcap,
};
use rockslide::trace::Trace;

/// The shipped PEPO case at `duration`, predictor-corrector only, Δt = 1 ms.
fn pepo_case(duration: f64) -> rockslide::case::Case {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/pepo-mass-accel.toml");
    let text = std::fs::read_to_string(&path).expect("shipped case");
    let head = &text[..text.find("[engines.").expect("engines table")];
    let text = format!(
        "{}\n[engines.predictor-corrector]\ndt = 0.001\n",
        head.replace("duration = 1.0", &format!("duration = {duration:?}"))
    );
    parse_case(&path, &text).expect("valid case")
}

/// The 10⁶-row trace of the predictor-corrector.
fn long_trace() -> Trace {
    let pc = engine::all()
        .into_iter()
        .find(|e| e.id() == "predictor-corrector")
        .expect("registered");
    pc.run(&pepo_case(1000.0), pc_variant::PAPER, 0.001)
        .expect("runs")
        .trace
}

/// A one-run trace log of `trace`.
fn log_of(trace: &Trace) -> TraceLog<'_> {
    TraceLog {
        runs: vec![LoggedRun {
            label: "predictor-corrector/paper".into(),
            trace,
            status: "completed".into(),
            stop: None,
            metadata: BTreeMap::new(),
        }],
        ..Default::default()
    }
}

/// Every message of an MCAP file as (log time, payload): the state and contact
/// messages, CDR.
fn payloads(bytes: &[u8]) -> Vec<(u64, Vec<u8>)> {
    mcap::MessageStream::new(bytes)
        .expect("readable")
        .map(|m| {
            let m = m.expect("message");
            (m.log_time, m.data.into_owned())
        })
        .collect()
}

/// The state messages of `trace` as JSON of shortest round-trip decimals (the encoding
/// before CDR), into `out` (cleared first).
fn json_state_messages(trace: &Trace, out: &mut Vec<(u64, Vec<u8>)>) {
    out.clear();
    let mut number = zmij::Buffer::new();
    let mut put = |buf: &mut Vec<u8>, x: f64| {
        if x.is_finite() {
            buf.extend_from_slice(number.format_finite(x).as_bytes());
        } else {
            buf.extend_from_slice(b"null");
        }
    };
    for i in 0..trace.len() {
        let mut buf = Vec::with_capacity(256);
        buf.extend_from_slice(b"{\"time\":");
        put(&mut buf, trace.time[i]);
        for (c, col) in trace.channels.iter().zip(&trace.columns) {
            buf.extend_from_slice(b",\"");
            buf.extend_from_slice(c.key.as_bytes());
            buf.extend_from_slice(b"\":");
            put(&mut buf, col[i]);
        }
        buf.push(b'}');
        out.push(((trace.time[i] * 1e9).round() as u64, buf));
    }
}

/// The state messages of `trace` as little-endian CDR (what `write_mcap` writes), into
/// `out` (cleared first).
fn cdr_state_messages(trace: &Trace, out: &mut Vec<(u64, Vec<u8>)>) {
    out.clear();
    for i in 0..trace.len() {
        let mut buf = Vec::with_capacity(4 + 8 * (1 + trace.columns.len()));
        buf.extend_from_slice(&CDR_LE_HEADER);
        buf.extend_from_slice(&trace.time[i].to_le_bytes());
        for col in &trace.columns {
            buf.extend_from_slice(&col[i].to_le_bytes());
        }
        out.push(((trace.time[i] * 1e9).round() as u64, buf));
    }
}

/// Rewrite `messages` on one channel with `options`; the file's bytes.
fn rewrite(messages: &[(u64, Vec<u8>)], options: mcap::WriteOptions) -> Vec<u8> {
    let mut w = options.create(Cursor::new(Vec::new())).expect("writer");
    let schema = w
        .add_schema("rockslide.State", "jsonschema", b"{}")
        .expect("schema");
    let channel = w
        .add_channel(schema, "/state", "json", &BTreeMap::new())
        .expect("channel");
    for (seq, (ns, data)) in messages.iter().enumerate() {
        let header = mcap::records::MessageHeader {
            channel_id: channel,
            sequence: seq as u32,
            log_time: *ns,
            publish_time: *ns,
        };
        w.write_to_known_channel(&header, data).expect("message");
    }
    w.finish().expect("finish");
    w.into_inner().into_inner()
}

/// Rewrite `messages` on one channel with our writer (`write_mcap`'s) and `chunks`.
fn rewrite_ours(messages: &[(u64, Vec<u8>)], chunks: ChunkOptions) -> Vec<u8> {
    let mut w = McapWriter::new(Vec::new(), chunks).expect("writer");
    let schema = w
        .add_schema("rockslide.State", "jsonschema", b"{}")
        .expect("schema");
    let channel = w
        .add_channel(schema, "/state", "json", &BTreeMap::new())
        .expect("channel");
    for (ns, data) in messages {
        w.message(channel, *ns, data).expect("message");
    }
    w.finish().expect("finish")
}

/// The chunks `write_mcap` wrote with the `mcap` crate's writer: zstd level 1 on the calling thread, 1 MiB.
fn writer_choice() -> mcap::WriteOptions {
    mcap::WriteOptions::new()
        .compression_threads(0)
        .compression_level(1)
}

/// The benchmark group of the writers on the 10⁶-row trace.
type Group<'a> = BenchmarkGroup<'a, WallTime>;

fn writers(c: &mut Criterion) {
    let trace = long_trace();
    let rows = trace.len() as u64;
    let out = tempfile::tempdir().expect("temporary folder");
    let mut group = c.benchmark_group("writers-pepo-pc-1e6-rows");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(10));
    group.throughput(Throughput::Elements(rows));
    number_formatting(&mut group, &trace);
    let log = log_of(&trace);
    trace_files(&mut group, &trace, &log, out.path());
    state_encodings(&mut group, &trace);
    let messages = payloads(&mcap_bytes(&log).expect("bytes"));
    let raw: usize = messages.iter().map(|(_, d)| d.len()).sum();
    eprintln!("mcap message payloads: {raw} B");
    our_compression(&mut group, &messages);
    crate_compression(&mut group, &messages);
    group.finish();
}

/// Shortest decimals of every finite value of the trace, by `ryu` and by `zmij`, and
/// whether they spell them alike.
fn number_formatting(group: &mut Group<'_>, trace: &Trace) {
    let values: Vec<f64> = trace
        .time
        .iter()
        .chain(trace.columns.iter().flatten())
        .copied()
        .filter(|x| x.is_finite())
        .collect();
    group.bench_function("format/ryu", |b| {
        b.iter(|| {
            let mut buf = ryu::Buffer::new();
            values
                .iter()
                .map(|&x| buf.format_finite(x).len())
                .sum::<usize>()
        })
    });
    group.bench_function("format/zmij", |b| {
        b.iter(|| {
            let mut buf = zmij::Buffer::new();
            values
                .iter()
                .map(|&x| buf.format_finite(x).len())
                .sum::<usize>()
        })
    });
    let same = values
        .iter()
        .all(|&x| ryu::Buffer::new().format_finite(x) == zmij::Buffer::new().format_finite(x));
    eprintln!(
        "ryu and zmij spell all {} values alike: {same}",
        values.len()
    );
}

/// The CSV file and the MCAP file written to `dir`, and their sizes.
fn trace_files(group: &mut Group<'_>, trace: &Trace, log: &TraceLog, dir: &Path) {
    let csv = dir.join("trace.csv");
    group.bench_function("csv", |b| {
        b.iter(|| write_csv(black_box(trace), &csv).expect("writes"))
    });
    let mcap = dir.join("trace.mcap");
    group.bench_function("mcap", |b| {
        b.iter(|| write_mcap(black_box(log), &mcap).expect("writes"))
    });
    let csv_size = std::fs::metadata(&csv).map_or(0, |m| m.len());
    let mcap_size = std::fs::metadata(&mcap).map_or(0, |m| m.len());
    eprintln!(
        "sizes: csv {csv_size} B, mcap {mcap_size} B for {} rows",
        trace.len()
    );
}

/// The state messages, JSON against CDR: encoding alone, then encoding and writing.
fn state_encodings(group: &mut Group<'_>, trace: &Trace) {
    let mut encoded = Vec::with_capacity(trace.len());
    for (label, encode) in [
        (
            "json",
            json_state_messages as fn(&Trace, &mut Vec<(u64, Vec<u8>)>),
        ),
        ("cdr", cdr_state_messages),
    ] {
        encode(trace, &mut encoded);
        let raw: usize = encoded.iter().map(|(_, d)| d.len()).sum();
        let size = rewrite(&encoded, writer_choice()).len();
        eprintln!("state messages as {label}: payloads {raw} B, file {size} B (zstd 1)");
        group.bench_function(format!("encode/{label}"), |b| {
            b.iter(|| encode(black_box(trace), &mut encoded))
        });
        group.bench_function(format!("encode+write/{label}"), |b| {
            b.iter(|| {
                encode(black_box(trace), &mut encoded);
                black_box(rewrite(&encoded, writer_choice()))
            })
        });
    }
}

/// Our chunk writer (each chunk compressed in one call) at several levels.
fn our_compression(group: &mut Group<'_>, messages: &[(u64, Vec<u8>)]) {
    let zstd = |level| ChunkOptions {
        compression: ChunkCompression::Zstd(level),
        ..CHUNKS
    };
    let ours: [(&str, ChunkOptions); 7] = [
        ("ours-zstd1-1MiB", zstd(1)),
        ("ours-zstd-1-1MiB", zstd(-1)),
        ("ours-zstd-3-1MiB", zstd(-3)),
        (
            "ours-lz4-1MiB",
            ChunkOptions {
                compression: ChunkCompression::Lz4(0),
                ..CHUNKS
            },
        ),
        (
            "ours-zstd-1-4MiB",
            ChunkOptions {
                chunk_bytes: 4 << 20,
                ..zstd(-1)
            },
        ),
        (
            "ours-none-1MiB",
            ChunkOptions {
                compression: ChunkCompression::None,
                ..CHUNKS
            },
        ),
        ("ours-chosen", CHUNKS),
    ];
    for (label, chunks) in ours {
        let size = rewrite_ours(messages, chunks).len();
        eprintln!("compression {label}: {size} B");
        group.bench_function(format!("compression/{label}"), |b| {
            b.iter(|| black_box(rewrite_ours(messages, chunks)))
        });
    }
}

/// The `mcap` crate's streaming writer at several levels, chunk sizes and threads.
fn crate_compression(group: &mut Group<'_>, messages: &[(u64, Vec<u8>)]) {
    let single = || mcap::WriteOptions::new().compression_threads(0);
    let choices: [(&str, mcap::WriteOptions); 7] = [
        ("zstd1-1MiB", single().compression_level(1)),
        (
            "zstd1-4MiB",
            single().compression_level(1).chunk_size(Some(4 << 20)),
        ),
        ("zstd3-1MiB", single().compression_level(3)),
        (
            "zstd1-1MiB-mt",
            mcap::WriteOptions::new().compression_level(1),
        ),
        (
            "lz4-1MiB",
            single().compression(Some(mcap::Compression::Lz4)),
        ),
        ("none-1MiB", single().compression(None)),
        (
            "none-4MiB",
            single().compression(None).chunk_size(Some(4 << 20)),
        ),
    ];
    for (label, options) in choices {
        let size = rewrite(messages, options.clone()).len();
        eprintln!("compression {label}: {size} B");
        group.bench_function(format!("compression/{label}"), |b| {
            b.iter(|| black_box(rewrite(messages, options.clone())))
        });
    }
}

criterion_group!(benches, writers);
criterion_main!(benches);

//! A streaming MCAP writer (<https://mcap.dev/spec>) of just what rockslide's files hold:
//! header, attachments, metadata, schemas and channels in the data section, messages in
//! zstd chunks with their message indexes, then the summary (schemas, channels,
//! statistics, chunk, attachment and metadata indexes), summary offsets and footer, with
//! every CRC the format has.
//!
//! Why not the `mcap` crate's writer: it feeds each message record into a streaming zstd
//! compressor in four pieces (opcode and length, header, data, index bookkeeping), and the
//! per-call cost of the streaming API was a third of the time spent compressing
//! (docs/performance.md §1). Here a chunk's records are appended to a plain buffer and the
//! whole chunk is compressed in one call when it is full; nothing is seeked back over, so
//! any `Write` will do.

use std::collections::BTreeMap;
use std::io::{self, Write};

const MAGIC: &[u8] = b"\x89MCAP0\r\n";

/// Record opcodes (MCAP specification, "Records").
mod op {
    pub const HEADER: u8 = 0x01;
    pub const FOOTER: u8 = 0x02;
    pub const SCHEMA: u8 = 0x03;
    pub const CHANNEL: u8 = 0x04;
    pub const MESSAGE: u8 = 0x05;
    pub const CHUNK: u8 = 0x06;
    pub const MESSAGE_INDEX: u8 = 0x07;
    pub const CHUNK_INDEX: u8 = 0x08;
    pub const ATTACHMENT: u8 = 0x09;
    pub const ATTACHMENT_INDEX: u8 = 0x0A;
    pub const STATISTICS: u8 = 0x0B;
    pub const METADATA: u8 = 0x0C;
    pub const METADATA_INDEX: u8 = 0x0D;
    pub const SUMMARY_OFFSET: u8 = 0x0E;
    pub const DATA_END: u8 = 0x0F;
}

/// How chunks are compressed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ChunkCompression {
    /// zstd at this level (negative: zstd's fast levels).
    Zstd(i32),
    /// LZ4 frames (MCAP's `lz4`), at this acceleration level (0: LZ4's default).
    Lz4(u32),
    /// Records stored as they are.
    None,
}

/// Chunk size and compression.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ChunkOptions {
    /// A chunk is closed once its uncompressed records reach this many bytes.
    pub chunk_bytes: usize,
    /// Compression of each chunk.
    pub compression: ChunkCompression,
}

/// Little-endian field encoders onto a byte buffer (records are built in memory, then
/// written whole).
trait Put {
    fn u16le(&mut self, x: u16);
    fn u32le(&mut self, x: u32);
    fn u64le(&mut self, x: u64);
    /// A string: u32 byte length, then the bytes.
    fn string(&mut self, s: &str);
    /// A map of strings: u32 byte length of the entries, then key and value strings.
    fn string_map(&mut self, m: &BTreeMap<String, String>);
}

impl Put for Vec<u8> {
    fn u16le(&mut self, x: u16) {
        self.extend_from_slice(&x.to_le_bytes());
    }
    fn u32le(&mut self, x: u32) {
        self.extend_from_slice(&x.to_le_bytes());
    }
    fn u64le(&mut self, x: u64) {
        self.extend_from_slice(&x.to_le_bytes());
    }
    fn string(&mut self, s: &str) {
        self.u32le(s.len() as u32);
        self.extend_from_slice(s.as_bytes());
    }
    fn string_map(&mut self, m: &BTreeMap<String, String>) {
        let len: usize = m.iter().map(|(k, v)| 8 + k.len() + v.len()).sum();
        self.u32le(len as u32);
        for (k, v) in m {
            self.string(k);
            self.string(v);
        }
    }
}

/// A record: opcode, u64 body length, body.
fn record(out: &mut Vec<u8>, opcode: u8, body: &[u8]) {
    out.push(opcode);
    out.u64le(body.len() as u64);
    out.extend_from_slice(body);
}

/// The sink with its byte count and the running CRC of the data section.
struct Sink<W: Write> {
    w: W,
    position: u64,
    crc: crc32fast::Hasher,
}

impl<W: Write> Sink<W> {
    fn write(&mut self, bytes: &[u8]) -> io::Result<()> {
        self.w.write_all(bytes)?;
        self.crc.update(bytes);
        self.position += bytes.len() as u64;
        Ok(())
    }
}

/// One schema or channel, kept for the summary.
struct Registered {
    body: Vec<u8>,
}

/// The open chunk: its records uncompressed, and per channel the (log time, offset) of
/// each of its messages.
struct OpenChunk {
    records: Vec<u8>,
    /// (log time, offset in `records`) of the chunk's messages, per channel id.
    index: Vec<Vec<(u64, u64)>>,
    start: u64,
    end: u64,
}

/// Streams an MCAP file into `W`.
pub struct McapWriter<W: Write> {
    sink: Sink<W>,
    options: ChunkOptions,
    zstd: Option<zstd::bulk::Compressor<'static>>,
    compressed: Vec<u8>,
    scratch: Vec<u8>,
    chunk: OpenChunk,
    schemas: Vec<Registered>,
    channels: Vec<Registered>,
    /// Sequence number of the last message and message count, per channel id.
    sequence: Vec<u32>,
    counts: Vec<u64>,
    message_bounds: Option<(u64, u64)>,
    chunk_indexes: Vec<Vec<u8>>,
    attachment_indexes: Vec<Vec<u8>>,
    metadata_indexes: Vec<Vec<u8>>,
}

impl<W: Write> McapWriter<W> {
    /// Start a file: magic and header record.
    pub fn new(w: W, options: ChunkOptions) -> io::Result<Self> {
        let zstd = match options.compression {
            ChunkCompression::Zstd(level) => Some(zstd::bulk::Compressor::new(level)?),
            ChunkCompression::Lz4(_) | ChunkCompression::None => None,
        };
        let mut me = Self {
            sink: Sink {
                w,
                position: 0,
                crc: crc32fast::Hasher::new(),
            },
            options,
            zstd,
            compressed: Vec::new(),
            scratch: Vec::with_capacity(256),
            chunk: OpenChunk {
                records: Vec::with_capacity(options.chunk_bytes + (64 << 10)),
                index: Vec::new(),
                start: u64::MAX,
                end: 0,
            },
            schemas: Vec::new(),
            channels: Vec::new(),
            sequence: vec![0],
            counts: vec![0],
            message_bounds: None,
            chunk_indexes: Vec::new(),
            attachment_indexes: Vec::new(),
            metadata_indexes: Vec::new(),
        };
        me.sink.write(MAGIC)?;
        let mut body = Vec::new();
        body.string("ros2"); // profile: ros2msg schemas, CDR messages (the state and 3D scene)
        body.string("rockslide");
        me.top_level(op::HEADER, &body)?;
        Ok(me)
    }

    /// Write a record outside chunks; returns its offset and length.
    fn top_level(&mut self, opcode: u8, body: &[u8]) -> io::Result<(u64, u64)> {
        let at = self.sink.position;
        self.scratch.clear();
        record(&mut self.scratch, opcode, body);
        let bytes = std::mem::take(&mut self.scratch);
        let result = self.sink.write(&bytes);
        self.scratch = bytes;
        result?;
        Ok((at, self.sink.position - at))
    }

    /// A schema record; returns its id (1, 2, ...).
    pub fn add_schema(&mut self, name: &str, encoding: &str, data: &[u8]) -> io::Result<u16> {
        let id = self.schemas.len() as u16 + 1;
        let mut body = Vec::with_capacity(14 + name.len() + encoding.len() + data.len());
        body.u16le(id);
        body.string(name);
        body.string(encoding);
        body.u32le(data.len() as u32);
        body.extend_from_slice(data);
        self.top_level(op::SCHEMA, &body)?;
        self.schemas.push(Registered { body });
        Ok(id)
    }

    /// A channel record; returns its id (1, 2, ...).
    pub fn add_channel(
        &mut self,
        schema_id: u16,
        topic: &str,
        message_encoding: &str,
        metadata: &BTreeMap<String, String>,
    ) -> io::Result<u16> {
        let id = self.channels.len() as u16 + 1;
        let mut body = Vec::new();
        body.u16le(id);
        body.u16le(schema_id);
        body.string(topic);
        body.string(message_encoding);
        body.string_map(metadata);
        self.top_level(op::CHANNEL, &body)?;
        self.channels.push(Registered { body });
        self.sequence.push(0);
        self.counts.push(0);
        self.chunk.index.push(Vec::new());
        Ok(id)
    }

    /// An attachment record (outside chunks) and its index.
    pub fn attach(&mut self, name: &str, media_type: &str, data: &[u8]) -> io::Result<()> {
        self.close_chunk()?;
        let mut body = Vec::with_capacity(40 + name.len() + media_type.len() + data.len());
        body.u64le(0); // log time
        body.u64le(0); // create time
        body.string(name);
        body.string(media_type);
        body.u64le(data.len() as u64);
        body.extend_from_slice(data);
        let crc = crc32fast::hash(&body);
        body.u32le(crc);
        let (offset, length) = self.top_level(op::ATTACHMENT, &body)?;
        let mut index = Vec::new();
        index.u64le(offset);
        index.u64le(length);
        index.u64le(0);
        index.u64le(0);
        index.u64le(data.len() as u64);
        index.string(name);
        index.string(media_type);
        self.attachment_indexes.push(index);
        Ok(())
    }

    /// A metadata record (outside chunks) and its index.
    pub fn metadata(&mut self, name: &str, metadata: &BTreeMap<String, String>) -> io::Result<()> {
        self.close_chunk()?;
        let mut body = Vec::new();
        body.string(name);
        body.string_map(metadata);
        let (offset, length) = self.top_level(op::METADATA, &body)?;
        let mut index = Vec::new();
        index.u64le(offset);
        index.u64le(length);
        index.string(name);
        self.metadata_indexes.push(index);
        Ok(())
    }

    /// A message on `channel_id` at `log_time` (= publish time), numbered per channel from
    /// 1; the chunk is compressed and written once it is full. `channel_id` must be one
    /// [`Self::add_channel`] returned (an id it did not return panics: a programming error).
    pub fn message(&mut self, channel_id: u16, log_time: u64, data: &[u8]) -> io::Result<()> {
        self.message_with(channel_id, log_time, |r| r.extend_from_slice(data))
    }

    /// [`Self::message`] whose data `encode` appends straight to the open chunk (the
    /// message's record is patched with the length it wrote): no copy of the data from a
    /// buffer of its own. The same bytes as [`Self::message`] with what `encode` appends.
    pub fn message_with(
        &mut self,
        channel_id: u16,
        log_time: u64,
        encode: impl FnOnce(&mut Vec<u8>),
    ) -> io::Result<()> {
        let ch = usize::from(channel_id);
        self.sequence[ch] += 1;
        self.counts[ch] += 1;
        let chunk = &mut self.chunk;
        let offset = chunk.records.len() as u64;
        chunk.index[ch - 1].push((log_time, offset));
        chunk.start = chunk.start.min(log_time);
        chunk.end = chunk.end.max(log_time);
        let r = &mut chunk.records;
        r.push(op::MESSAGE);
        let length_at = r.len();
        r.u64le(0); // the body's length, once the data is in
        r.u16le(channel_id);
        r.u32le(self.sequence[ch]);
        r.u64le(log_time);
        r.u64le(log_time);
        let body_start = length_at + 8;
        encode(r);
        let body_length = (r.len() - body_start) as u64;
        r[length_at..body_start].copy_from_slice(&body_length.to_le_bytes());
        self.message_bounds = Some(match self.message_bounds {
            None => (log_time, log_time),
            Some((a, b)) => (a.min(log_time), b.max(log_time)),
        });
        if self.chunk.records.len() >= self.options.chunk_bytes {
            self.close_chunk()?;
        }
        Ok(())
    }

    /// Compress and write the open chunk, then its message indexes; remember its index.
    fn close_chunk(&mut self) -> io::Result<()> {
        if self.chunk.records.is_empty() {
            return Ok(());
        }
        let uncompressed = &self.chunk.records;
        let (compression, stored): (&str, &[u8]) = match &mut self.zstd {
            Some(z) => {
                self.compressed.clear();
                self.compressed
                    .reserve(zstd::zstd_safe::compress_bound(uncompressed.len()));
                z.compress_to_buffer(uncompressed, &mut self.compressed)?;
                ("zstd", &self.compressed)
            }
            None => match self.options.compression {
                ChunkCompression::Lz4(level) => {
                    self.compressed.clear();
                    let mut e = lz4::EncoderBuilder::new()
                        .level(level)
                        .block_size(lz4::BlockSize::Max4MB)
                        .checksum(lz4::ContentChecksum::NoChecksum)
                        .block_checksum(lz4::liblz4::BlockChecksum::NoBlockChecksum)
                        .build(std::mem::take(&mut self.compressed))?;
                    e.write_all(uncompressed)?;
                    let (out, done) = e.finish();
                    done?;
                    self.compressed = out;
                    ("lz4", &self.compressed)
                }
                _ => ("", uncompressed),
            },
        };
        let mut head = Vec::with_capacity(64);
        head.push(op::CHUNK);
        head.u64le(8 + 8 + 8 + 4 + 4 + compression.len() as u64 + 8 + stored.len() as u64);
        head.u64le(self.chunk.start);
        head.u64le(self.chunk.end);
        head.u64le(uncompressed.len() as u64);
        head.u32le(crc32fast::hash(uncompressed));
        head.string(compression);
        head.u64le(stored.len() as u64);
        let chunk_start = self.sink.position;
        self.sink.write(&head)?;
        self.sink.write(stored)?;
        let chunk_length = self.sink.position - chunk_start;
        let (compressed_size, uncompressed_size) = (stored.len() as u64, uncompressed.len() as u64);

        let index_start = self.sink.position;
        let mut offsets = Vec::new();
        for (i, entries) in self.chunk.index.iter_mut().enumerate() {
            if entries.is_empty() {
                continue;
            }
            let mut body = Vec::with_capacity(6 + 16 * entries.len());
            body.u16le(i as u16 + 1);
            body.u32le(16 * entries.len() as u32);
            for &(t, at) in entries.iter() {
                body.u64le(t);
                body.u64le(at);
            }
            offsets.push((i as u16 + 1, self.sink.position));
            self.scratch.clear();
            record(&mut self.scratch, op::MESSAGE_INDEX, &body);
            self.sink.write(&self.scratch)?;
            entries.clear();
        }
        let mut index = Vec::new();
        index.u64le(self.chunk.start);
        index.u64le(self.chunk.end);
        index.u64le(chunk_start);
        index.u64le(chunk_length);
        index.u32le(10 * offsets.len() as u32);
        for (id, at) in offsets {
            index.u16le(id);
            index.u64le(at);
        }
        index.u64le(self.sink.position - index_start);
        index.string(compression);
        index.u64le(compressed_size);
        index.u64le(uncompressed_size);
        self.chunk_indexes.push(index);
        self.chunk.records.clear();
        self.chunk.start = u64::MAX;
        self.chunk.end = 0;
        Ok(())
    }

    /// Close the last chunk, write the data end, the summary, its offsets, the footer and
    /// the closing magic; returns the sink.
    pub fn finish(mut self) -> io::Result<W> {
        self.close_chunk()?;
        let mut body = Vec::new();
        body.u32le(self.sink.crc.clone().finalize());
        self.top_level(op::DATA_END, &body)?;

        let summary_start = self.sink.position;
        let mut summary = Vec::new();
        let mut groups = Vec::new();
        let mut group =
            |summary: &mut Vec<u8>, opcode: u8, bodies: &mut dyn Iterator<Item = &[u8]>| {
                let start = summary.len();
                for b in bodies {
                    record(summary, opcode, b);
                }
                if summary.len() > start {
                    groups.push((
                        opcode,
                        summary_start + start as u64,
                        (summary.len() - start) as u64,
                    ));
                }
            };
        group(
            &mut summary,
            op::SCHEMA,
            &mut self.schemas.iter().map(|s| &s.body[..]),
        );
        group(
            &mut summary,
            op::CHANNEL,
            &mut self.channels.iter().map(|c| &c.body[..]),
        );
        let stats = self.statistics();
        group(
            &mut summary,
            op::STATISTICS,
            &mut std::iter::once(&stats[..]),
        );
        group(
            &mut summary,
            op::CHUNK_INDEX,
            &mut self.chunk_indexes.iter().map(|b| &b[..]),
        );
        group(
            &mut summary,
            op::ATTACHMENT_INDEX,
            &mut self.attachment_indexes.iter().map(|b| &b[..]),
        );
        group(
            &mut summary,
            op::METADATA_INDEX,
            &mut self.metadata_indexes.iter().map(|b| &b[..]),
        );
        let offsets_start = summary_start + summary.len() as u64;
        for (opcode, start, length) in groups {
            let mut body = Vec::with_capacity(17);
            body.push(opcode);
            body.u64le(start);
            body.u64le(length);
            record(&mut summary, op::SUMMARY_OFFSET, &body);
        }
        summary.push(op::FOOTER);
        summary.u64le(20);
        summary.u64le(summary_start);
        summary.u64le(offsets_start);
        let crc = crc32fast::hash(&summary);
        summary.u32le(crc);
        summary.extend_from_slice(MAGIC);
        self.sink.w.write_all(&summary)?;
        self.sink.w.flush()?;
        Ok(self.sink.w)
    }

    /// The statistics record's body.
    fn statistics(&self) -> Vec<u8> {
        let (start, end) = self.message_bounds.unwrap_or((0, 0));
        let mut body = Vec::new();
        body.u64le(self.counts.iter().sum());
        body.u16le(self.schemas.len() as u16);
        body.u32le(self.channels.len() as u32);
        body.u32le(self.attachment_indexes.len() as u32);
        body.u32le(self.metadata_indexes.len() as u32);
        body.u32le(self.chunk_indexes.len() as u32);
        body.u64le(start);
        body.u64le(end);
        let with_messages: Vec<(usize, u64)> = (1..self.counts.len())
            .map(|i| (i, self.counts[i]))
            .filter(|&(_, n)| n > 0)
            .collect();
        body.u32le(10 * with_messages.len() as u32);
        for (id, n) in with_messages {
            body.u16le(id as u16);
            body.u64le(n);
        }
        body
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Messages of every length from 0 to 40 bytes, appended straight into the chunk by
    /// `message_with` (in two pieces, as the state messages are), give the file `message`
    /// gives with each whole: the length patched in is the data's, and the `mcap` crate
    /// reads each message back with its bytes.
    #[test]
    fn a_message_encoded_into_the_chunk_is_the_message_given_whole() {
        let data = |i: usize| {
            (0..i as u8)
                .map(|b| b.wrapping_mul(37))
                .collect::<Vec<u8>>()
        };
        let file = |encoded: bool| {
            let options = ChunkOptions {
                chunk_bytes: 256,
                compression: ChunkCompression::None,
            };
            let mut w = McapWriter::new(Vec::new(), options).unwrap();
            let s = w
                .add_schema("rockslide/S", "ros2msg", b"uint8[] x")
                .unwrap();
            let c = w.add_channel(s, "/c", "cdr", &BTreeMap::new()).unwrap();
            for i in 0..=40 {
                let d = data(i);
                match encoded {
                    true => w.message_with(c, 10 * i as u64, |r| {
                        r.extend_from_slice(&d[..i / 2]);
                        r.extend_from_slice(&d[i / 2..]);
                    }),
                    false => w.message(c, 10 * i as u64, &d),
                }
                .unwrap();
            }
            w.finish().unwrap()
        };
        let bytes = file(true);
        assert_eq!(bytes, file(false));
        let read: Vec<_> = mcap::MessageStream::new(&bytes)
            .unwrap()
            .map(|m| m.unwrap().data.to_vec())
            .collect();
        assert_eq!(read, (0..=40).map(data).collect::<Vec<_>>());
    }

    /// 300 messages on two channels in chunks of ~1 KiB, zstd, lz4 or none: the `mcap`
    /// crate's linear reader (CRCs checked) and its indexed reader (summary, chunk
    /// indexes, message indexes, each message sought through its index) find every message
    /// with its sequence, time and bytes.
    #[test]
    fn indexed_and_linear_readers_find_every_message() {
        for compression in [
            ChunkCompression::Zstd(-1),
            ChunkCompression::Lz4(0),
            ChunkCompression::None,
        ] {
            let options = ChunkOptions {
                chunk_bytes: 1 << 10,
                compression,
            };
            let mut w = McapWriter::new(Vec::new(), options).unwrap();
            w.attach("case.toml", "application/toml", b"x = 1").unwrap();
            let meta = BTreeMap::from([("k".to_string(), "v".to_string())]);
            w.metadata("rockslide", &meta).unwrap();
            let s = w
                .add_schema("rockslide/S", "ros2msg", b"float64 x")
                .unwrap();
            let a = w.add_channel(s, "/a", "cdr", &meta).unwrap();
            let b = w.add_channel(s, "/b", "cdr", &BTreeMap::new()).unwrap();
            let payload = |i: u64| (i as f64 * 0.1).to_le_bytes();
            for i in 0..300u64 {
                w.message(if i % 3 == 0 { b } else { a }, 1000 * i, &payload(i))
                    .unwrap();
            }
            let bytes = w.finish().unwrap();

            let options = mcap::read::Options::ValidateChunkCrcs.into();
            let linear: Vec<_> = mcap::MessageStream::new_with_options(&bytes, options)
                .unwrap()
                .map(|m| m.unwrap())
                .collect();
            assert_eq!(linear.len(), 300);
            for (i, m) in linear.iter().enumerate() {
                let i = i as u64;
                assert_eq!(m.log_time, 1000 * i);
                assert_eq!(m.data.as_ref(), &payload(i));
                let n = if i % 3 == 0 { i / 3 + 1 } else { i - i / 3 };
                assert_eq!(u64::from(m.sequence), n, "message {i}");
            }

            let summary = mcap::read::Summary::read(&bytes).unwrap().unwrap();
            let stats = summary.stats.as_ref().unwrap();
            assert_eq!(stats.message_count, 300);
            assert_eq!(stats.channel_message_counts[&a], 200);
            assert_eq!(
                (stats.message_start_time, stats.message_end_time),
                (0, 299_000)
            );
            assert_eq!(summary.attachment_indexes.len(), 1);
            assert_eq!(summary.metadata_indexes.len(), 1);
            assert!(summary.chunk_indexes.len() > 10);
            let mut found = 0;
            for chunk in &summary.chunk_indexes {
                for (channel, entries) in summary.read_message_indexes(&bytes, chunk).unwrap() {
                    for e in &entries {
                        let m = summary.seek_message(&bytes, chunk, e).unwrap();
                        assert_eq!(m.channel.topic, channel.topic);
                        assert_eq!(m.log_time, e.log_time);
                        assert_eq!(m.data.as_ref(), &payload(e.log_time / 1000));
                        found += 1;
                    }
                }
            }
            assert_eq!(found, 300);
            let meta = mcap::read::metadata(&bytes, &summary.metadata_indexes[0]).unwrap();
            assert_eq!(meta.metadata["k"], "v");
            let att = mcap::read::attachment(&bytes, &summary.attachment_indexes[0]).unwrap();
            assert_eq!(att.data.as_ref(), b"x = 1");
        }
    }
}

//! Reading an MCAP trace back (`rockslide trace-info`, external participants, tests):
//! the framing and every length checked before the `mcap` crate parses, chunks
//! decompressed within their declared sizes, each state channel's messages (CDR, or JSON
//! in older files) into a [`Trace`] with its contact block, metadata and attachments.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use serde_json::Value;

use rockslide_core::error::{Error, InputError, InputErrors};
use rockslide_core::trace::{CONTACT_FIELDS, ContactBlock, ContactState, Quantity, Trace, q};

use super::{JSON_STATE_SCHEMA, STATE_SCHEMA};
use crate::cdr;
use crate::contacts;
use crate::scene3d;

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

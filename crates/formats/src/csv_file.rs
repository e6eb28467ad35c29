//! CSV traces: a header `time [s],force [N],...` (key and SI unit of each column), one row
//! per recorded step, full f64 precision so a trace read back is bit-identical.

use std::io::Write;
use std::path::Path;

use rockslide_core::error::{Error, InputError, InputErrors};
use rockslide_core::io::write_atomically_with;
use rockslide_core::trace::{Trace, q};

/// Write `trace` to `path` atomically, streamed in blocks: no per-row allocation and
/// nothing of the file held in memory beyond one block. The blocks go to the file itself,
/// not through the atomic writer's buffer (which stays empty): one copy of every byte
/// less.
pub fn write_csv(trace: &Trace, path: &Path) -> Result<(), Error> {
    write_atomically_with(path, |w| {
        write_csv_to(trace, w.get_mut()).map_err(|e| Error::io(path, e))
    })
}

/// The CSV text of `trace` into `w`: the header through `csv::Writer` (quoted where a
/// unit needs it), then rows of shortest round-trip decimals, which never need quoting.
pub fn write_csv_to(trace: &Trace, w: &mut impl Write) -> std::io::Result<()> {
    {
        let mut header = csv::Writer::from_writer(&mut *w);
        header.write_field("time [s]")?;
        for c in &trace.channels {
            header.write_field(format!("{} [{}]", c.key, c.unit))?;
        }
        header.write_record(None::<&[u8]>)?;
        header.flush()?;
    }
    let mut rows = DecimalRows::new(1 + trace.columns.len());
    for i in 0..trace.len() {
        rows.value(0, trace.time[i]);
        for (j, c) in trace.columns.iter().enumerate() {
            rows.value(j + 1, c[i]);
        }
        rows.end_row(w)?;
    }
    rows.flush(w)
}

/// Longest shortest-decimal spelling of an f64 (`-2.2250738585072014e-308` is 24 bytes).
const MAX_DECIMAL: usize = 32;

/// Rows of comma-separated shortest decimals, built in a block of memory written out in
/// large pieces (one write per [`DecimalRows::BLOCK`] bytes, not one per value). Each
/// column remembers its last value and its spelling: a value equal bit for bit to the
/// previous one in its column (a constant normal force, a slide that stays put while
/// sticking, zero forces after a pulse) is copied instead of formatted again. Spellings
/// move as whole [`MAX_DECIMAL`]-byte blocks (the block has that much slack past its
/// cursor), so a copy is a few fixed moves rather than a `memcpy` call per value. The bytes
/// are exactly those of formatting every value.
pub(crate) struct DecimalRows {
    block: Box<[u8]>,
    /// Bytes of `block` filled.
    at: usize,
    /// Per column: last value's bits, its spelling and the spelling's length.
    last: Vec<(u64, [u8; MAX_DECIMAL], usize)>,
    number: zmij::Buffer,
}

impl DecimalRows {
    /// Bytes gathered before a write.
    pub(crate) const BLOCK: usize = 64 << 10;

    /// Rows of `columns` values.
    pub(crate) fn new(columns: usize) -> Self {
        // length 0: no spelling yet, the first value of a column is always formatted
        let unset = (0, [0u8; MAX_DECIMAL], 0);
        // room for a whole row past BLOCK: every value and its comma, and the newline
        let slack = (columns + 1) * (MAX_DECIMAL + 1) + 1;
        Self {
            block: vec![0u8; Self::BLOCK + slack].into_boxed_slice(),
            at: 0,
            last: vec![unset; columns],
            number: zmij::Buffer::new(),
        }
    }

    /// Value of column `col` of the current row (columns in order, from 0).
    #[inline]
    pub(crate) fn value(&mut self, col: usize, x: f64) {
        if col > 0 {
            self.block[self.at] = b',';
            self.at += 1;
        }
        let at = self.at;
        let (bits, spelled, len) = &mut self.last[col];
        if *bits != x.to_bits() || *len == 0 {
            let s = shortest(&mut self.number, x).as_bytes();
            put_short(spelled, s);
            *len = s.len();
            *bits = x.to_bits();
        }
        self.block[at..at + MAX_DECIMAL].copy_from_slice(spelled);
        self.at += *len;
    }

    /// End the current row; writes the block out once it is full.
    #[inline]
    pub(crate) fn end_row(&mut self, w: &mut impl Write) -> std::io::Result<()> {
        self.block[self.at] = b'\n';
        self.at += 1;
        if self.at >= Self::BLOCK {
            self.flush(w)?;
        }
        Ok(())
    }

    /// Write out what is gathered.
    pub(crate) fn flush(&mut self, w: &mut impl Write) -> std::io::Result<()> {
        w.write_all(&self.block[..self.at])?;
        self.at = 0;
        Ok(())
    }
}

/// `s` (at most [`MAX_DECIMAL`] bytes) to the start of `to` in two fixed-size moves that
/// overlap (16, 8, 4 bytes, or bytewise below 4) instead of a `memcpy` call of variable
/// length: a spelling is 3 to 24 bytes, and the call cost more than the copy. The bytes of
/// `to` past `s.len()` are left as they were.
#[inline]
fn put_short(to: &mut [u8; MAX_DECIMAL], s: &[u8]) {
    let n = s.len();
    if n >= 16 {
        to[..16].copy_from_slice(&s[..16]);
        to[n - 16..n].copy_from_slice(&s[n - 16..]);
    } else if n >= 8 {
        to[..8].copy_from_slice(&s[..8]);
        to[n - 8..n].copy_from_slice(&s[n - 8..]);
    } else if n >= 4 {
        to[..4].copy_from_slice(&s[..4]);
        to[n - 4..n].copy_from_slice(&s[n - 4..]);
    } else {
        for (t, &b) in to.iter_mut().zip(s) {
            *t = b;
        }
    }
}

/// Shortest decimal that reads back to the same f64 (zmij, spelled as Ryū would), without
/// allocating; `NaN`, `inf` and `-inf` spelled as Rust parses them back.
pub(crate) fn shortest(buf: &mut zmij::Buffer, x: f64) -> &str {
    if x.is_finite() {
        buf.format_finite(x)
    } else if x.is_nan() {
        "NaN"
    } else if x > 0.0 {
        "inf"
    } else {
        "-inf"
    }
}

/// Read a CSV trace written by [`write_csv`].
pub fn read_csv(path: &Path) -> Result<Trace, InputErrors> {
    let bad = |line: usize, reason: String| InputError::new(path, "", reason).at(line, 1);
    let mut r = csv::Reader::from_path(path)
        .map_err(|e| InputError::new(path, "", format!("cannot read: {e}")))?;
    let headers = r
        .headers()
        .map_err(|e| bad(1, format!("bad header: {e}")))?
        .clone();
    let mut channels = Vec::new();
    for (i, h) in headers.iter().enumerate().skip(1) {
        let key = h.split(" [").next().unwrap_or(h);
        let qty = q::by_key(key)
            .ok_or_else(|| bad(1, format!("column {}: unknown quantity \"{key}\"", i + 1)))?;
        channels.push(qty);
    }
    let mut trace = Trace::with_channels(&channels, 0);
    let mut values = vec![0.0; channels.len()];
    for (n, rec) in r.records().enumerate() {
        let line = n + 2;
        let rec = rec.map_err(|e| bad(line, e.to_string()))?;
        let parse = |s: &str| {
            s.trim()
                .parse::<f64>()
                .map_err(|_| bad(line, format!("\"{s}\" is not a number")))
        };
        let t = parse(rec.get(0).unwrap_or(""))?;
        for (j, v) in values.iter_mut().enumerate() {
            *v = parse(rec.get(j + 1).unwrap_or(""))?;
        }
        trace.push(t, &values);
    }
    Ok(trace)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values whose spellings have every length from 3 (`0.0`, `NaN`) to 24 bytes, with runs of
    /// the same bits (taken from the cache), `-0.0` after `0.0` (equal, not the same bits)
    /// and the non-finite values.
    fn values() -> Vec<f64> {
        let mut v = vec![0.0, 0.0, -0.0, -0.0, 1.0, 5e-324, -2.2250738585072014e-308];
        for digits in 1..=17 {
            // 0.1, 0.12, ..., 17 significant digits, and their negatives with exponents
            let x: f64 = format!("0.{}", &"12345678901234567"[..digits])
                .parse()
                .unwrap();
            v.extend([x, x, -x * 1e-300, 7.0 * x, 7.0 * x, x * 1e300]);
        }
        v.extend([
            f64::NAN,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            9.81e6,
            9.81e6,
        ]);
        v.extend([1.2345678901, 1e16, -1e16]);
        v
    }

    #[test]
    fn rows_are_each_value_formatted_afresh_whatever_repeats_or_its_length() {
        let values = values();
        let lengths: std::collections::BTreeSet<usize> = values
            .iter()
            .map(|&x| shortest(&mut zmij::Buffer::new(), x).len())
            .collect();
        assert_eq!(
            lengths,
            (3..=24).collect(),
            "every spelling length is exercised"
        );
        for columns in [1, 3] {
            let mut rows = DecimalRows::new(columns);
            let mut written = Vec::new();
            let mut expected = String::new();
            for row in values.chunks(columns) {
                for (j, &x) in row.iter().enumerate() {
                    rows.value(j, x);
                    let sep = if j > 0 { "," } else { "" };
                    expected += sep;
                    expected += shortest(&mut zmij::Buffer::new(), x);
                }
                rows.end_row(&mut written).unwrap();
                expected.push('\n');
            }
            rows.flush(&mut written).unwrap();
            assert_eq!(String::from_utf8(written).unwrap(), expected);
        }
    }

    #[test]
    fn every_spelling_reads_back_to_the_same_bits() {
        let mut rows = DecimalRows::new(1);
        let mut written = Vec::new();
        for &x in &values() {
            rows.value(0, x);
            rows.end_row(&mut written).unwrap();
        }
        rows.flush(&mut written).unwrap();
        let text = String::from_utf8(written).unwrap();
        for (line, &x) in text.lines().zip(&values()) {
            let back: f64 = line.parse().unwrap();
            assert!(
                back.to_bits() == x.to_bits() || (x.is_nan() && back.is_nan()),
                "{line}"
            );
        }
    }
}

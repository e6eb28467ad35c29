//! CSV traces: a header `time [s],force [N],...` (key and SI unit of each column), one row
//! per recorded step, full f64 precision so a trace read back is bit-identical.

use std::io::Write;
use std::path::Path;

use super::{Trace, q};
use crate::error::{Error, InputError, InputErrors};
use crate::io::write_atomically_with;

/// Write `trace` to `path` atomically, streamed through a large buffer: no per-row
/// allocation and nothing of the file held in memory beyond the buffer.
pub fn write_csv(trace: &Trace, path: &Path) -> Result<(), Error> {
    write_atomically_with(path, |w| {
        write_csv_to(trace, w).map_err(|e| Error::io(path, e))
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
    let mut number = zmij::Buffer::new();
    for i in 0..trace.len() {
        w.write_all(shortest(&mut number, trace.time[i]).as_bytes())?;
        for c in &trace.columns {
            w.write_all(b",")?;
            w.write_all(shortest(&mut number, c[i]).as_bytes())?;
        }
        w.write_all(b"\n")?;
    }
    Ok(())
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

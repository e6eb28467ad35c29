//! `rockslide newmark <record> --ky <g>`: Newmark's rigid block on one record — yield
//! acceleration and PGA in g, the record run as recorded ("normal") and inverted
//! ("inverse"), and the mean of the two |sliding|. One-way (downslope) sliding by default,
//! as SLAMMER's rigid-block analysis; `--two-way` for a block on a level frictional base.
//!
//! Sliding follows the case reports' convention, not SLAMMER's: block minus ground, in mm,
//! positive when the block moves in +x relative to the ground. The exact block
//! ([`NewmarkSummary`]) is driven by the ground acceleration and returns SLAMMER's u
//! (positive where the ground accelerates past +ky), so sliding = −u; a one-way block
//! therefore slides only in −x with the record as given.

use std::path::PathBuf;

use rockslide_core::case::record::{AccelUnit, STANDARD_GRAVITY, read_record};
use rockslide_core::error::{Error, InputError, InputErrors};
use rockslide_core::io::write_atomically;
use rockslide_core::response::sig;
use rockslide_reference::newmark_record::{NewmarkSummary, Sliding};

/// Arguments of the command.
#[derive(Debug, Clone, PartialEq)]
pub struct NewmarkArgs {
    /// The record (`.AT2` or two-column CSV).
    pub record: PathBuf,
    /// Yield accelerations, g.
    pub ky: Vec<f64>,
    /// Unit of a CSV record's acceleration column.
    pub unit: Option<String>,
    /// Scale the record to this PGA first, g.
    pub pga: Option<f64>,
    /// Slide both ways (level base) instead of SLAMMER's one way.
    pub two_way: bool,
    /// Also write the table as CSV here.
    pub csv: Option<PathBuf>,
}

/// The sliding (block minus ground, positive in +x, the case reports' convention) of the
/// exact block's displacement u, which is SLAMMER's (positive where the ground accelerates
/// past +ky): sliding = −u.
pub fn sliding_of(u: f64) -> f64 {
    -u
}

/// Columns of the printed table: sliding in mm (block minus ground) with 4 significant
/// digits, as the case reports.
const TABLE_HEADER: &str = "| record | ky [g] | polarity | sliding [mm] | slip episodes | total slid [mm] | first onset [s] | last stop [s] |\n\
     |---|---:|---|---:|---:|---:|---:|---:|\n";

/// The three rows (normal, inverse, mean |sliding|) of one yield acceleration.
fn table_rows(s: &NewmarkSummary, label: &str) -> String {
    let ky = s.ky / STANDARD_GRAVITY;
    let span = |s: Option<(f64, f64)>| {
        s.map_or("– | –".to_string(), |(a, b)| format!("{a:.4} | {b:.4}"))
    };
    let mut t = String::new();
    for (pol, u, n, total, sp) in [
        ("normal", s.normal, s.episodes.0, s.total_slid.0, s.span.0),
        ("inverse", s.inverse, s.episodes.1, s.total_slid.1, s.span.1),
    ] {
        t.push_str(&format!(
            "| {label} | {ky:.4} | {pol} | {} | {n} | {} | {} |\n",
            sig(sliding_of(u) * 1e3),
            sig(total * 1e3),
            span(sp)
        ));
    }
    t.push_str(&format!(
        "| {label} | {ky:.4} | mean abs | {} | | | | |\n",
        sig(s.mean() * 1e3)
    ));
    t
}

/// The record the arguments name, read in its unit and scaled to `--pga` when asked; the
/// yield accelerations and the PGA checked positive.
fn checked_record(a: &NewmarkArgs) -> Result<rockslide_core::case::record::Record, Error> {
    let unit = match a.unit.as_deref() {
        None => None,
        Some(u) => Some(AccelUnit::parse(u).ok_or_else(|| {
            InputErrors::from(InputError::new(
                &a.record,
                "--unit",
                format!("\"{u}\" is not one of \"g\", \"m/s2\", \"cm/s2\""),
            ))
        })?),
    };
    let mut rec = read_record(&a.record, unit)?;
    for &ky in &a.ky {
        if !(ky.is_finite() && ky > 0.0) {
            return Err(InputErrors::from(InputError::new(
                &a.record,
                "--ky",
                format!("is {ky}, but must be positive, in g"),
            ))
            .into());
        }
    }
    if let Some(pga) = a.pga {
        if !(pga.is_finite() && pga > 0.0) {
            return Err(InputErrors::from(InputError::new(
                &a.record,
                "--pga",
                format!("is {pga}, but must be positive, in g"),
            ))
            .into());
        }
        rec.scale_to_pga(pga * STANDARD_GRAVITY, 1.0);
    }
    Ok(rec)
}

/// The table's heading: the sliding mode, the record (samples, step, PGA) and the sign
/// convention.
fn heading(a: &NewmarkArgs, rec: &rockslide_core::case::record::Record, name: &str) -> String {
    format!(
        "Newmark rigid block ({}), record {name}: {} samples × {} s, PGA {:.4} g{}\n\
         Sliding: block minus ground, mm, positive in +x (the case reports' convention; SLAMMER's u = −sliding)\n\n",
        if a.two_way {
            "two-way sliding"
        } else {
            "one-way sliding, as SLAMMER's rigid block"
        },
        rec.samples.len(),
        rec.dt,
        rec.pga() / STANDARD_GRAVITY,
        if rec.note.is_empty() {
            String::new()
        } else {
            format!(" ({})", rec.note)
        }
    )
}

/// The CSV file's header.
const CSV_HEADER: [&str; 9] = [
    "record",
    "ky_g",
    "polarity",
    "sliding_mm",
    "sliding_m",
    "slip_episodes",
    "total_slid_m",
    "slip_start_s",
    "slip_end_s",
];

/// The CSV rows of one yield acceleration: normal, inverse, mean abs.
fn csv_rows(
    csv: &mut csv::Writer<Vec<u8>>,
    name: &str,
    ky: f64,
    s: &NewmarkSummary,
) -> Result<(), csv::Error> {
    let opt = |x: Option<f64>| x.map_or(String::new(), |v| v.to_string());
    for (pol, d, episodes, total, span) in [
        (
            "normal",
            s.normal,
            Some(s.episodes.0),
            Some(s.total_slid.0),
            s.span.0,
        ),
        (
            "inverse",
            s.inverse,
            Some(s.episodes.1),
            Some(s.total_slid.1),
            s.span.1,
        ),
        ("mean abs", -s.mean(), None, None, None),
    ] {
        let d = sliding_of(d);
        csv.write_record([
            name.to_string(),
            ky.to_string(),
            pol.to_string(),
            (d * 1e3).to_string(),
            d.to_string(),
            episodes.map_or(String::new(), |n| n.to_string()),
            opt(total),
            opt(span.map(|s| s.0)),
            opt(span.map(|s| s.1)),
        ])?;
    }
    Ok(())
}

/// Run the command: print a Markdown table (and write CSV when asked).
pub fn newmark_command(a: &NewmarkArgs) -> Result<String, Error> {
    let rec = checked_record(a)?;
    let sliding = if a.two_way {
        Sliding::TwoWay
    } else {
        Sliding::OneWay
    };
    let name = a
        .record
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let mut md = heading(a, &rec, &name);
    let csv_error = |e: csv::Error| Error::Other(format!("newmark CSV: {e}"));
    let mut csv = csv::Writer::from_writer(Vec::new());
    csv.write_record(CSV_HEADER).map_err(csv_error)?;
    for (i, &ky) in a.ky.iter().enumerate() {
        let s = NewmarkSummary::of(rec.dt, &rec.samples, ky * STANDARD_GRAVITY, sliding, 0.0)
            .map_err(|why| Error::Other(format!("{name}: rigid block at ky {ky} g: {why}")))?;
        if i == 0 {
            md.push_str(TABLE_HEADER);
        }
        md.push_str(&table_rows(&s, &name));
        csv_rows(&mut csv, &name, ky, &s).map_err(csv_error)?;
    }
    if let Some(path) = &a.csv {
        let bytes = csv
            .into_inner()
            .map_err(|e| Error::Other(format!("newmark CSV: {e}")))?;
        write_atomically(path, &bytes)?;
    }
    Ok(md)
}

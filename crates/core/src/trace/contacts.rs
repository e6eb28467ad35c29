//! The per-contact block of a run's trace: for each contact of the scene (the
//! oscillator's base, each support of a rocking body, a rigid block's base), at every
//! recorded row, its normal force N, tangential force T, accumulated slip and normal gap,
//! in SI units. The physical invariants read it (friction bound, stick/slip, dissipation
//! and penetration per contact); it is written as `<run>-contacts.csv` beside the run's
//! CSV and in the run's MCAP state messages, after its fields (`/<engine>/<variant>/state`,
//! Foxglove paths `.base.normal`, `.s1.slip`, …).
//!
//! Sign conventions: N > 0 in compression (a compression-only contact never pulls);
//! T is the contact's tangential force signed as the trace's `resistance`: positive when
//! it resists positive relative displacement (minus the ground's force on the structure
//! along +x), so that friction dissipates when T·Δslip ≥ 0; the slip is the contact's own
//! accumulated tangential slip on the ground, m; the gap is the contact's normal
//! separation from the ground, m, negative when it penetrates. A penalty contact states
//! its normal compliance (m/N, the penetration it is allowed per newton of N; 0 for a
//! rigid contact), so that penetration beyond the model is `−gap − compliance·N`.
//!
//! Rows are stored flat (row × contact × field) in one vector preallocated for the run,
//! so that recording never allocates.

use std::io::Write;
use std::path::Path;

use super::Trace;
use super::csv_file::DecimalRows;
use crate::error::{Error, InputError, InputErrors};
use crate::io::write_atomically_with;

/// The recorded fields of a contact: (key, SI unit, meaning).
pub const CONTACT_FIELDS: [(&str, &str, &str); 4] = [
    (
        "normal",
        "N",
        "Normal force of the contact, positive in compression.",
    ),
    (
        "tangential",
        "N",
        "Tangential (friction) force, positive resisting positive displacement (as resistance).",
    ),
    (
        "slip",
        "m",
        "Accumulated tangential slip of the contact on the ground.",
    ),
    (
        "gap",
        "m",
        "Normal separation from the ground, negative when penetrating.",
    ),
];

/// Schema name prefix of the per-run contact channels of files written before the
/// contacts joined the state messages (still read).
pub const CONTACTS_SCHEMA: &str = "rockslide/Contacts";

/// The prefix contact schemas had when their messages were JSON (still read).
pub(crate) const JSON_CONTACTS_SCHEMA: &str = "rockslide.Contacts";

/// One contact at one instant.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactState {
    /// Normal force, N (compression positive).
    pub normal: f64,
    /// Tangential force, N, signed as the resistance (resisting +x positive).
    pub tangential: f64,
    /// Accumulated slip, m.
    pub slip: f64,
    /// Normal gap, m (negative: penetration).
    pub gap: f64,
}

impl ContactState {
    /// The state as the fields a row records, in [`CONTACT_FIELDS`]' order.
    #[inline(always)]
    pub fn fields(&self) -> [f64; CONTACT_FIELDS.len()] {
        [self.normal, self.tangential, self.slip, self.gap]
    }

    /// The state from a row's fields, in [`CONTACT_FIELDS`]' order.
    #[inline(always)]
    pub fn from_fields([normal, tangential, slip, gap]: [f64; CONTACT_FIELDS.len()]) -> Self {
        Self {
            normal,
            tangential,
            slip,
            gap,
        }
    }
}

/// A plan (3D) contact's slip increment as the contact block records it: the slip `ds`
/// projected on the direction of the friction force `t` (zero without a force). Summed,
/// the contact's slip along its force, so that |T|·Δslip is the friction work T·Δs the
/// dissipation invariant judges — |s| of the accumulated slip vector would shrink when the
/// slip turns back. The recording convention of the output format, not physics: every
/// engine with plan contacts records its slip through it.
pub fn plan_slip_increment(t: [f64; 2], ds: [f64; 2]) -> f64 {
    let size = t[0].hypot(t[1]);
    if size > 0.0 {
        (t[0] * ds[0] + t[1] * ds[1]) / size
    } else {
        0.0
    }
}

/// The contacts of one run over time.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ContactBlock {
    /// Contact names (`base`, `s1` … `sn` from −b to +b), in column order.
    pub names: Vec<String>,
    /// Normal compliance of each contact, m/N (0: rigid contact).
    pub compliance: Vec<f64>,
    /// Time of each row, s (the run's trace rows).
    pub time: Vec<f64>,
    /// Values, row-major: row × contact × [`CONTACT_FIELDS`].
    pub values: Vec<f64>,
}

impl ContactBlock {
    /// The rows `rows` of this block (indices into its time), in that order; an empty
    /// block stays empty.
    pub fn select_rows(&self, rows: &[usize]) -> ContactBlock {
        if self.is_empty() {
            return self.clone();
        }
        let width = self.names.len() * CONTACT_FIELDS.len();
        ContactBlock {
            names: self.names.clone(),
            compliance: self.compliance.clone(),
            time: rows.iter().map(|&i| self.time[i]).collect(),
            values: rows
                .iter()
                .flat_map(|&i| self.values[i * width..(i + 1) * width].iter().copied())
                .collect(),
        }
    }

    /// An empty block for `names` (with their normal compliances, m/N) with room for
    /// `rows` rows, so recording never reallocates.
    pub fn with_contacts(names: &[&str], compliance: &[f64], rows: usize) -> Self {
        debug_assert_eq!(names.len(), compliance.len());
        Self {
            names: names.iter().map(|n| n.to_string()).collect(),
            compliance: compliance.to_vec(),
            time: Vec::with_capacity(rows),
            values: Vec::with_capacity(rows * names.len() * CONTACT_FIELDS.len()),
        }
    }

    /// The block of a scene's supports, named as every engine names them: `base` for
    /// one contact, `s1` … `sn` from −b to +b for several; `compliance` is each support's
    /// normal compliance, m/N.
    pub fn for_supports(n: usize, compliance: f64, rows: usize) -> Self {
        let names: Vec<String> = if n == 1 {
            vec!["base".to_string()]
        } else {
            (1..=n).map(|i| format!("s{i}")).collect()
        };
        let refs: Vec<&str> = names.iter().map(String::as_str).collect();
        Self::with_contacts(&refs, &vec![compliance; n], rows)
    }

    /// Append one row; `states` in contact order. The row's values come from an
    /// iterator of known length (four fields a contact), so the vector checks its
    /// capacity once a row rather than once a contact (≈ 105 instructions a row of ten
    /// contacts instead of ≈ 180).
    #[inline]
    pub fn push(&mut self, t: f64, states: &[ContactState]) {
        debug_assert_eq!(states.len(), self.names.len());
        self.time.push(t);
        self.values
            .extend(states.iter().flat_map(ContactState::fields));
    }

    /// Append one row given flat: `values` holds every contact's fields in order
    /// (contact × [`CONTACT_FIELDS`]).
    #[inline]
    pub fn push_values(&mut self, t: f64, values: &[f64]) {
        debug_assert_eq!(values.len(), self.names.len() * CONTACT_FIELDS.len());
        self.time.push(t);
        self.values.extend_from_slice(values);
    }

    /// Whether this block only repeats `trace`'s own columns: one contact, a row per trace
    /// row, its T the trace's `resistance` and its slip its `slide` bit for bit, its N and
    /// gap constant (the predictor-corrector's one contact: N = M·g, gap = −N/Kz, both
    /// given by the case). Its CSV file would hold nothing the run's CSV and the case do
    /// not, so it is not written; the MCAP state messages still carry it.
    pub fn repeats(&self, trace: &Trace) -> bool {
        let (Some(resistance), Some(slide)) = (trace.column("resistance"), trace.column("slide"))
        else {
            return false;
        };
        if self.count() != 1 || self.len() != trace.len() || self.is_empty() {
            return false;
        }
        let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
        let first = self.at(0, 0);
        (0..self.len()).all(|i| {
            let c = self.at(i, 0);
            same(self.time[i], trace.time[i])
                && same(c.tangential, resistance[i])
                && same(c.slip, slide[i])
                && same(c.normal, first.normal)
                && same(c.gap, first.gap)
        })
    }

    /// Number of contacts.
    pub fn count(&self) -> usize {
        self.names.len()
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// Whether no row was recorded (or the run has no contact block).
    pub fn is_empty(&self) -> bool {
        self.time.is_empty() || self.names.is_empty()
    }

    /// Contact `c` at row `i`.
    pub fn at(&self, i: usize, c: usize) -> ContactState {
        let k = (i * self.count() + c) * CONTACT_FIELDS.len();
        let v = &self.values[k..k + CONTACT_FIELDS.len()];
        ContactState {
            normal: v[0],
            tangential: v[1],
            slip: v[2],
            gap: v[3],
        }
    }

    /// The CSV column names: `<contact>.<field> [<unit>]` after `time [s]`.
    pub fn header(&self) -> Vec<String> {
        let mut h = vec!["time [s]".to_string()];
        for n in &self.names {
            for (key, unit, _) in CONTACT_FIELDS {
                h.push(format!("{n}.{key} [{unit}]"));
            }
        }
        h
    }
}

/// Write `block` to `path` atomically (full round-trip precision, as the run's CSV),
/// streamed: the header through `csv::Writer` (quoting), then rows of shortest decimals
/// written straight into the buffer, no per-row allocation.
pub fn write_contacts_csv(block: &ContactBlock, path: &Path) -> Result<(), Error> {
    write_atomically_with(path, |w| {
        write_contacts_csv_to(block, w).map_err(|e| Error::io(path, e))
    })
}

fn write_contacts_csv_to(block: &ContactBlock, w: &mut impl Write) -> std::io::Result<()> {
    {
        let mut header = csv::Writer::from_writer(&mut *w);
        header.write_record(block.header())?;
        header.flush()?;
    }
    let width = block.count() * CONTACT_FIELDS.len();
    let mut rows = DecimalRows::new(1 + width);
    for (i, t) in block.time.iter().enumerate() {
        rows.value(0, *t);
        for (j, v) in block.values[i * width..(i + 1) * width].iter().enumerate() {
            rows.value(j + 1, *v);
        }
        rows.end_row(w)?;
    }
    rows.flush(w)
}

/// Read a contact CSV written by [`write_contacts_csv`] (compliances are not in the CSV:
/// read back as 0).
pub fn read_contacts_csv(path: &Path) -> Result<ContactBlock, InputErrors> {
    let bad = |line: usize, reason: String| InputError::new(path, "", reason).at(line, 1);
    let mut r = csv::Reader::from_path(path)
        .map_err(|e| InputError::new(path, "", format!("cannot read: {e}")))?;
    let headers = r
        .headers()
        .map_err(|e| bad(1, format!("bad header: {e}")))?
        .clone();
    let columns = headers.len().saturating_sub(1);
    if columns % CONTACT_FIELDS.len() != 0 {
        return Err(bad(
            1,
            format!("{columns} columns after time: not 4 per contact"),
        )
        .into());
    }
    let mut names = Vec::new();
    for (j, h) in headers.iter().skip(1).enumerate() {
        let (name, rest) = h.rsplit_once('.').unwrap_or(("", h));
        let (key, unit, _) = CONTACT_FIELDS[j % CONTACT_FIELDS.len()];
        if name.is_empty() || rest != format!("{key} [{unit}]") {
            return Err(bad(
                1,
                format!(
                    "column {}: expected <contact>.{key} [{unit}], found \"{h}\"",
                    j + 2
                ),
            )
            .into());
        }
        if j % CONTACT_FIELDS.len() == 0 {
            names.push(name.to_string());
        }
    }
    let mut block = ContactBlock {
        compliance: vec![0.0; names.len()],
        names,
        ..ContactBlock::default()
    };
    for (n, rec) in r.records().enumerate() {
        let line = n + 2;
        let rec = rec.map_err(|e| bad(line, e.to_string()))?;
        for (j, s) in rec.iter().enumerate() {
            let v = s
                .trim()
                .parse::<f64>()
                .map_err(|_| bad(line, format!("\"{s}\" is not a number")))?;
            if j == 0 {
                block.time.push(v);
            } else {
                block.values.push(v);
            }
        }
    }
    Ok(block)
}

/// The schema name a run's contact messages had in files written before the contacts
/// joined the state messages: `rockslide/Contacts<Label>`, the label in CamelCase (a
/// ROS 2 message name, as [`super::state_schema_name`]). Such files are still read.
pub fn contacts_schema_name(label: &str) -> String {
    format!("{CONTACTS_SCHEMA}{}", super::cdr::camel_case(label))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn block() -> ContactBlock {
        let mut b = ContactBlock::with_contacts(&["s1", "s2"], &[1e-6, 0.0], 2);
        let s = |n: f64| ContactState {
            normal: n,
            tangential: -0.5 * n,
            slip: 1e-3,
            gap: -1e-6 * n,
        };
        b.push(0.0, &[s(1.0), s(2.0)]);
        b.push(0.1, &[s(3.0), s(f64::NAN)]);
        b
    }

    #[test]
    fn rows_are_read_back_per_contact() {
        let b = block();
        assert_eq!((b.count(), b.len()), (2, 2));
        assert_eq!(b.at(1, 0).normal, 3.0);
        assert_eq!(b.at(0, 1).tangential, -1.0);
        assert!(b.at(1, 1).normal.is_nan());
    }

    #[test]
    fn a_block_repeats_a_trace_only_when_every_field_is_its_column_or_constant() {
        use crate::trace::q;
        let mut trace = Trace::with_channels(&[&q::RESISTANCE, &q::SLIDE], 3);
        trace.contacts = ContactBlock::with_contacts(&["base"], &[1e-9], 3);
        let c = |t: f64, s: f64| ContactState {
            normal: 9.81,
            tangential: t,
            slip: s,
            gap: -9.81e-9,
        };
        for (i, (t, s)) in [(0.0, 0.0), (-0.0, 1e-3), (2.5, 2e-3)]
            .into_iter()
            .enumerate()
        {
            trace.push(i as f64, &[t, s]);
            trace.contacts.push(i as f64, &[c(t, s)]);
        }
        assert!(trace.contacts.repeats(&trace));
        // T differs from the resistance in its sign bit alone: a new column, written
        let mut other = trace.clone();
        other.columns[0][1] = 0.0;
        assert!(!other.contacts.repeats(&other));
        // a normal force that changes: written
        let mut other = trace.clone();
        other.contacts.values[2 * 4] = 9.8;
        assert!(!other.contacts.repeats(&other));
        // several contacts, or a trace without the columns: written
        assert!(!block().repeats(&trace));
        let mut bare = Trace::with_channels(&[&q::SLIDE], 3);
        bare.contacts = trace.contacts.clone();
        assert!(!trace.contacts.repeats(&bare));
    }

    #[test]
    fn the_csv_round_trips_bit_for_bit() {
        let dir = std::env::temp_dir().join(format!("rs-contacts-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("c.csv");
        let b = block();
        write_contacts_csv(&b, &path).unwrap();
        let back = read_contacts_csv(&path).unwrap();
        assert_eq!(back.names, b.names);
        assert_eq!(back.time, b.time);
        for (x, y) in back.values.iter().zip(&b.values) {
            assert!(x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()));
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

//! The per-contact block of a run's trace: for each contact of the scene (the
//! oscillator's base, each support of a rocking body, a rigid block's base), at every
//! recorded row, its normal force N, tangential force T, accumulated slip and normal gap,
//! in SI units. The physical invariants read it (friction bound, stick/slip, dissipation
//! and penetration per contact); the file formats write it as `<run>-contacts.csv` beside
//! the run's CSV and in the run's MCAP state messages, after its fields
//! (`/<engine>/<variant>/state`, Foxglove paths `.base.normal`, `.s1.slip`, …).
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trace::Trace;

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
}

//! A recorded excitation (`record = "…"`): its unit, polarity, target PGA and column
//! checked, the record read (relative to the case file, its own errors located both in
//! the case and in the record), converted to m/s² and scaled.

use std::path::Path;

use super::super::record::{AccelUnit, STANDARD_GRAVITY, read_record_column};
use super::super::scene::quoted;
use super::super::signal::Signal;
use super::validator::{Rule, SignalKeys, Validator};
use crate::error::InputError;

impl Validator<'_> {
    /// The `record` branch: read the file (relative to the case file), convert to m/s²,
    /// scale to the stated PGA and polarity. See [`crate::case::record`] for the conventions.
    pub(super) fn record_signal(
        &mut self,
        e: &SignalKeys,
        p: &str,
        record: &str,
        case_path: &Path,
    ) -> Option<Signal> {
        let keys = self.record_keys(e, p)?;
        self.read_record(&keys, p, record, case_path)
    }

    /// The keys beside `record`, checked; `None` (the record is not read) for an unknown
    /// unit or a bad column.
    fn record_keys(&mut self, e: &SignalKeys, p: &str) -> Option<RecordKeys> {
        for (f, p) in [
            (&format!("{p}.shape"), e.shape.is_some()),
            (&format!("{p}.amplitude"), e.amplitude.is_some()),
            (&format!("{p}.omega"), e.omega.is_some()),
            (&format!("{p}.cycles"), e.cycles.is_some()),
        ] {
            if p {
                self.fail(
                    f,
                    "does not apply to a recorded excitation (`record` is given)",
                );
            }
        }
        let unit = match e.record_unit {
            None => None,
            Some(u) => match AccelUnit::parse(u) {
                Some(u) => Some(u),
                None => {
                    self.fail(
                        &format!("{p}.record_unit"),
                        format!(
                            "is \"{u}\", but must be one of {}",
                            quoted(AccelUnit::NAMES)
                        ),
                    );
                    return None;
                }
            },
        };
        let polarity = match e.polarity {
            None => 1.0,
            Some(x) if x == 1.0 || x == -1.0 => x,
            Some(x) => {
                self.fail(
                    &format!("{p}.polarity"),
                    format!("is {x}, but must be 1 (as recorded) or -1 (inverted)"),
                );
                1.0
            }
        };
        let target = match e.scale_to_pga_g {
            None => None,
            x => Some(
                self.number(&format!("{p}.scale_to_pga_g"), x, Rule::positive("g"))
                    * STANDARD_GRAVITY,
            ),
        };
        if let (Some(t), Some(g)) = (target, e.scale_to_pga_g) {
            if g.is_finite() && !t.is_finite() {
                self.fail(
                    &format!("{p}.scale_to_pga_g"),
                    format!("is {g} g, which is beyond the largest number in m/s²"),
                );
            }
        }
        let column = match e.record_column {
            None => None,
            Some(c) if c >= 1 => Some(c as usize),
            Some(c) => {
                self.fail(
                    &format!("{p}.record_column"),
                    format!("is {c}, but must be at least 1 (the first acceleration column after the time column)"),
                );
                return None;
            }
        };
        Some(RecordKeys {
            unit,
            polarity,
            target,
            column,
        })
    }

    /// The record read with `keys`, its errors located at `<p>.record` and in the file;
    /// scaled, and labelled with what was done to it.
    fn read_record(
        &mut self,
        keys: &RecordKeys,
        p: &str,
        record: &str,
        case_path: &Path,
    ) -> Option<Signal> {
        let RecordKeys {
            unit,
            polarity,
            target,
            column,
        } = *keys;
        let dir = case_path.parent().unwrap_or(Path::new(""));
        let path = dir.join(record);
        let field = format!("{p}.record");
        let mut rec = match read_record_column(&path, unit, column) {
            Ok(r) => r,
            Err(errs) => {
                // The record's own errors, located at the case's field and in the record.
                for err in errs.0 {
                    self.errors.push(err.named_by(self.loc.error(&field, "")));
                }
                return None;
            }
        };
        let pga = rec.pga();
        if pga == 0.0 {
            let err = InputError::new(&path, "", "every sample is zero: nothing moves the ground");
            self.errors.push(err.named_by(self.loc.error(&field, "")));
            return None;
        }
        let scaling = match target {
            Some(t) if t.is_finite() && t > 0.0 => {
                let f = rec.scale_to_pga(t, polarity);
                format!(
                    ", scaled ×{f:.6} to PGA {:.6} g ({t:.6} m/s²)",
                    t / STANDARD_GRAVITY
                )
            }
            _ => {
                rec.scale(polarity);
                format!(
                    ", PGA {pga:.4} m/s² ({:.4} g) as recorded",
                    pga / STANDARD_GRAVITY
                )
            }
        };
        let name = Path::new(record)
            .file_name()
            .map_or_else(|| record.to_string(), |n| n.to_string_lossy().into_owned());
        let mut label = format!(
            "{name}: {} samples × {} s in {}{scaling}, polarity {:+}",
            rec.samples.len(),
            rec.dt,
            rec.unit.name(),
            polarity
        );
        if !rec.note.is_empty() {
            label.push_str(&format!(" ({})", rec.note));
        }
        Some(Signal::Record {
            dt: rec.dt,
            samples: rec.samples.into(),
            label,
        })
    }
}

/// The checked keys of a recorded excitation.
#[derive(Clone, Copy)]
struct RecordKeys {
    /// The record's unit, when stated (else read from the file).
    unit: Option<AccelUnit>,
    /// 1 as recorded, −1 inverted.
    polarity: f64,
    /// The PGA to scale to, m/s².
    target: Option<f64>,
    /// The acceleration column (1-based after the time column), when stated.
    column: Option<usize>,
}

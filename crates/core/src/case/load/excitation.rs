//! `[excitation]`: its kind (none, mass acceleration, ground displacement, ground
//! acceleration) and its signal, a sine pulse or a record (see `record_signal`); the
//! signal keys are shared with the vertical and second (y) components.

use std::path::Path;

use super::super::raw::RawExcitation;
use super::super::record::STANDARD_GRAVITY;
use super::super::scene::Excitation;
use super::super::signal::Signal;
use super::validator::{Rule, SignalKeys, Validator};

impl Validator<'_> {
    pub(super) fn excitation(&mut self, e: &RawExcitation, case_path: &Path) -> Option<Excitation> {
        self.old_pga_key(e.scale_to_pga.as_ref(), "excitation.scale_to_pga");
        if e.kind == "none" {
            self.nothing_beside_none(e);
            return Some(Excitation::None);
        }
        let signal = self.signal(&SignalKeys::from(e), "excitation", case_path)?;
        if e.record.is_some() && e.kind == "ground-displacement" {
            self.fail(
                "excitation.kind",
                "a record is an acceleration history: use kind = \"ground-acceleration\" (or \"mass-acceleration\")",
            );
            return None;
        }
        match e.kind.as_str() {
            "mass-acceleration" => Some(Excitation::MassAcceleration(signal)),
            "ground-displacement" => {
                if let Signal::SinePulse { cycles, .. } = signal {
                    if ((cycles * 2.0).round() - cycles * 2.0).abs() > 1e-12 {
                        self.fail(
                            "excitation.cycles",
                            "must be a whole number of half cycles for a ground displacement (else the ground would jump)",
                        );
                    }
                }
                Some(Excitation::GroundDisplacement(signal))
            }
            "ground-acceleration" => Some(Excitation::GroundAcceleration(signal)),
            other => {
                self.fail(
                    "excitation.kind",
                    format!("is \"{other}\", but must be one of \"none\", \"mass-acceleration\", \"ground-displacement\", \"ground-acceleration\""),
                );
                None
            }
        }
    }

    /// `scale_to_pga` (m/s²) was renamed `scale_to_pga_g` (g, as `rockslide newmark --pga`):
    /// the old key is refused with the new one's name and value, never read in m/s².
    pub(super) fn old_pga_key(&mut self, old: Option<&toml::Value>, field: &str) {
        let Some(old) = old else {
            return;
        };
        let hint = match old
            .as_float()
            .or_else(|| old.as_integer().map(|i| i as f64))
        {
            Some(x) => format!(
                " (scale_to_pga = {x} m/s² is scale_to_pga_g = {:.6} g)",
                x / STANDARD_GRAVITY
            ),
            None => String::new(),
        };
        self.fail(
            field,
            format!("is no longer read: the target PGA is given in g as `scale_to_pga_g`{hint}"),
        );
    }

    /// `kind = "none"` takes no signal: any signal key beside it is an error, not ignored.
    pub(super) fn nothing_beside_none(&mut self, e: &RawExcitation) {
        for (f, given) in [
            ("excitation.shape", e.shape.is_some()),
            ("excitation.amplitude", e.amplitude.is_some()),
            ("excitation.omega", e.omega.is_some()),
            ("excitation.cycles", e.cycles.is_some()),
            ("excitation.record", e.record.is_some()),
            ("excitation.record_unit", e.record_unit.is_some()),
            ("excitation.record_column", e.record_column.is_some()),
            ("excitation.scale_to_pga_g", e.scale_to_pga_g.is_some()),
            ("excitation.polarity", e.polarity.is_some()),
        ] {
            if given {
                self.fail(f, "does not apply to kind = \"none\" (no excitation)");
            }
        }
    }

    pub(super) fn signal(&mut self, e: &SignalKeys, p: &str, case_path: &Path) -> Option<Signal> {
        if let Some(record) = e.record {
            return self.record_signal(e, p, record, case_path);
        }
        for (f, p) in [
            (&format!("{p}.record_unit"), e.record_unit.is_some()),
            (&format!("{p}.record_column"), e.record_column.is_some()),
            (&format!("{p}.scale_to_pga_g"), e.scale_to_pga_g.is_some()),
            (&format!("{p}.polarity"), e.polarity.is_some()),
        ] {
            if p {
                self.fail(f, "applies only to a recorded excitation (`record`)");
            }
        }
        match e.shape {
            Some("sine-pulse") => {
                let amplitude = self.number(&format!("{p}.amplitude"), e.amplitude, Rule::finite());
                let omega = self.number(&format!("{p}.omega"), e.omega, Rule::positive("rad/s"));
                let cycles =
                    self.number(&format!("{p}.cycles"), e.cycles, Rule::positive("cycles"));
                Some(Signal::SinePulse {
                    amplitude,
                    omega,
                    cycles,
                })
            }
            Some(other) => {
                self.fail(
                    &format!("{p}.shape"),
                    format!("is \"{other}\", but must be \"sine-pulse\" (or give `record`)"),
                );
                None
            }
            None => {
                self.fail(
                    &format!("{p}.shape"),
                    "is required: \"sine-pulse\" (or give `record`)",
                );
                None
            }
        }
    }
}

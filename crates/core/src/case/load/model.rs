//! `[model]`: the oscillator, the rocking body or the rigid block, with its contact (and
//! the double contact of a two-stage support).

use super::super::raw::{RawContact, RawDouble, RawModel};
use super::super::scene::{Contact, DoubleContact, Model, Oscillator, RigidBlock, RockingBody};
use super::validator::{Rule, Validator};
use crate::case::limits::MAX_SUPPORTS;

impl Validator<'_> {
    pub(super) fn model(&mut self, m: &RawModel) -> Option<Model> {
        let mass = self.number("model.mass", m.mass, Rule::positive("kg"));
        let gravity = self.number("model.gravity", m.gravity, Rule::non_negative("m/s²"));
        match m.kind.as_str() {
            "oscillator" => self.oscillator(m, mass, gravity),
            "rocking-body" => self.rocking_body(m, mass, gravity),
            "rigid-block" => self.rigid_block(m, mass, gravity),
            other => {
                self.fail(
                    "model.kind",
                    format!("is \"{other}\", but must be one of \"oscillator\", \"rocking-body\", \"rigid-block\""),
                );
                None
            }
        }
    }

    /// The oscillator: a point mass on its contact (a double contact in series when given).
    fn oscillator(&mut self, m: &RawModel, mass: f64, gravity: f64) -> Option<Model> {
        for (f, p) in [
            ("model.cm_height", m.cm_height.is_some()),
            ("model.half_width", m.half_width.is_some()),
            ("model.supports", m.supports.is_some()),
            ("model.rotational_inertia", m.rotational_inertia.is_some()),
            ("model.half_height", m.half_height.is_some()),
            ("model.mu", m.mu.is_some()),
            ("model.initial_tilt", m.initial_tilt.is_some()),
        ] {
            self.forbid(f, p, "oscillator");
        }
        let damping_ratio = match m.damping_ratio {
            None => 0.0,
            x => self.number("model.damping_ratio", x, Rule::fraction()),
        };
        let contact = self.contact("model.contact", m.contact.as_ref())?;
        let double = m.double.as_ref().map(|d| self.double("model.double", d));
        Some(Model::Oscillator(Oscillator {
            mass,
            gravity,
            damping_ratio,
            contact,
            double,
        }))
    }

    /// The rocking body: a rigid body on `supports` contacts across its base.
    fn rocking_body(&mut self, m: &RawModel, mass: f64, gravity: f64) -> Option<Model> {
        for (f, p) in [
            ("model.mu", m.mu.is_some()),
            ("model.initial_tilt", m.initial_tilt.is_some()),
            ("model.damping_ratio", m.damping_ratio.is_some()),
            ("model.half_height", m.half_height.is_some()),
        ] {
            self.forbid(f, p, "rocking-body");
        }
        let cm_height = self.number("model.cm_height", m.cm_height, Rule::extent("m"));
        let half_width = self.number("model.half_width", m.half_width, Rule::extent("m"));
        let supports = match m.supports {
            Some(n) if n > MAX_SUPPORTS as i64 => {
                self.fail(
                    "model.supports",
                    format!(
                        "is {n}, but must be at most {MAX_SUPPORTS} (each support is a contact \
                         the engines model and record at every step)"
                    ),
                );
                2
            }
            Some(n) if n >= 2 => n as usize,
            Some(n) => {
                self.fail("model.supports", format!("is {n}, but must be at least 2"));
                2
            }
            None => {
                self.fail(
                    "model.supports",
                    "is required (number of supports, at least 2)",
                );
                2
            }
        };
        let rotational_inertia = match m.rotational_inertia {
            None => 0.0,
            x => self.number("model.rotational_inertia", x, Rule::non_negative("kg·m²")),
        };
        let contact = self.contact("model.contact", m.contact.as_ref())?;
        let double = m.double.as_ref().map(|d| self.double("model.double", d));
        Some(Model::RockingBody(RockingBody {
            mass,
            gravity,
            cm_height,
            half_width,
            supports,
            rotational_inertia,
            contact,
            double,
        }))
    }

    /// The rigid block on rigid ground: half sizes, friction and an initial tilt.
    fn rigid_block(&mut self, m: &RawModel, mass: f64, gravity: f64) -> Option<Model> {
        for (f, p) in [
            ("model.cm_height", m.cm_height.is_some()),
            ("model.supports", m.supports.is_some()),
            ("model.rotational_inertia", m.rotational_inertia.is_some()),
            ("model.contact", m.contact.is_some()),
            ("model.double", m.double.is_some()),
            ("model.damping_ratio", m.damping_ratio.is_some()),
        ] {
            self.forbid(f, p, "rigid-block");
        }
        let half_width = self.number("model.half_width", m.half_width, Rule::extent("m"));
        let half_height = self.number("model.half_height", m.half_height, Rule::extent("m"));
        let mu = self.number("model.mu", m.mu, Rule::non_negative(""));
        let initial_tilt = match m.initial_tilt {
            None => 0.0,
            x => self.number("model.initial_tilt", x, Rule::range(-1.5, 1.5, "rad")),
        };
        Some(Model::RigidBlock(RigidBlock {
            mass,
            gravity,
            half_width,
            half_height,
            mu,
            initial_tilt,
        }))
    }

    pub(super) fn contact(&mut self, field: &str, c: Option<&RawContact>) -> Option<Contact> {
        let Some(c) = c else {
            self.fail(field, "is required: a table with kx (N/m), kz (N/m) and mu");
            return None;
        };
        self.number(&format!("{field}.kx"), Some(c.kx), Rule::positive("N/m"));
        self.number(&format!("{field}.kz"), Some(c.kz), Rule::positive("N/m"));
        self.number(&format!("{field}.mu"), Some(c.mu), Rule::friction());
        Some(Contact {
            kx: c.kx,
            kz: c.kz,
            mu: c.mu,
        })
    }

    pub(super) fn double(&mut self, field: &str, d: &RawDouble) -> DoubleContact {
        for (k, x) in [
            ("kx1", d.kx1),
            ("kz1", d.kz1),
            ("kx2", d.kx2),
            ("kz2", d.kz2),
        ] {
            self.number(&format!("{field}.{k}"), Some(x), Rule::positive("N/m"));
        }
        self.number(&format!("{field}.mu1"), Some(d.mu1), Rule::friction());
        self.number(&format!("{field}.mu2"), Some(d.mu2), Rule::friction());
        DoubleContact {
            lower: Contact {
                kx: d.kx1,
                kz: d.kz1,
                mu: d.mu1,
            },
            upper: Contact {
                kx: d.kx2,
                kz: d.kz2,
                mu: d.mu2,
            },
        }
    }
}

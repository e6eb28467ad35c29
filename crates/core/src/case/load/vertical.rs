//! `[excitation.vertical]`: a vertical ground acceleration a_v(t) and how the normal force
//! follows it.

use std::path::Path;

use super::super::raw::{RawExcitation, RawVertical};
use super::super::scene::{Model, NormalForce, Vertical};
use super::validator::{SignalKeys, Validator};

impl Validator<'_> {
    /// `[excitation.vertical]`: a vertical ground acceleration a_v(t) (positive upward),
    /// a sine pulse or a record (its own file and scale), and how N follows it. A scene
    /// without gravity has no normal force for it to change: an error.
    pub(super) fn vertical(
        &mut self,
        raw: &RawVertical,
        horizontal: &RawExcitation,
        model: Option<&Model>,
        case_path: &Path,
    ) -> Option<Vertical> {
        const P: &str = "excitation.vertical";
        self.old_pga_key(
            raw.scale_to_pga.as_ref(),
            "excitation.vertical.scale_to_pga",
        );
        let signal = self.signal(&SignalKeys::from(raw), P, case_path);
        let (gravity, kind) = match model? {
            Model::Oscillator(o) => (o.gravity, "oscillator"),
            Model::RockingBody(r) => (r.gravity, "rocking-body"),
            Model::RigidBlock(b) => (b.gravity, "rigid-block"),
        };
        if gravity.is_finite() && gravity <= 0.0 {
            self.fail(
                P,
                "needs gravity: a vertical ground motion changes the normal force M·(g + a_v), and model.gravity is 0",
            );
        }
        if horizontal.kind == "ground-displacement" {
            self.fail(
                P,
                "goes with kind = \"none\", \"mass-acceleration\" or \"ground-acceleration\" (a ground-displacement pulse has no vertical counterpart here)",
            );
        }
        let normal_force = match (raw.normal_force.as_deref(), kind) {
            (None, "rigid-block") => NormalForce::QuasiStatic,
            (None, _) | (Some("dynamic"), "oscillator" | "rocking-body") => NormalForce::Dynamic,
            (Some("quasi-static"), "oscillator") => NormalForce::QuasiStatic,
            (Some(other @ ("dynamic" | "quasi-static")), kind) => {
                self.fail(
                    &format!("{P}.normal_force"),
                    format!(
                        "\"{other}\" does not apply to a model of kind \"{kind}\" (a rigid block on rigid ground always has N = M·(g + a_v); a rocking body's supports follow their own Kz)"
                    ),
                );
                return None;
            }
            (Some(other), _) => {
                self.fail(
                    &format!("{P}.normal_force"),
                    format!(
                        "is \"{other}\", but must be \"dynamic\" (the contact's Kz and the mass oscillate, default) or \"quasi-static\" (rigid vertical contact, N = M·(g + a_v))"
                    ),
                );
                return None;
            }
        };
        Some(Vertical {
            signal: signal?,
            normal_force,
        })
    }
}

//! Bidirectional (3D) scenes: `azimuth_deg`, the second component `[excitation.y]`, the
//! depth along y of a body and its three rotational inertias.

use std::path::Path;

use super::super::raw::{RawExcitation, RawModel, RawSecond};
use super::super::scene::Model;
use super::super::signal::Signal;
use super::super::spatial::{Depth, Spatial};
use super::validator::{Rule, SignalKeys, Validator};
use crate::case::limits::{MAX_SUPPORT_GRID, MAX_SUPPORT_ROWS};

/// Whether the case gives any key of a bidirectional scene.
fn gives_spatial_keys(m: &RawModel, e: &RawExcitation) -> bool {
    e.azimuth_deg.is_some()
        || e.y.is_some()
        || m.half_depth.is_some()
        || m.support_rows.is_some()
        || m.rotational_inertia_x.is_some()
        || m.rotational_inertia_y.is_some()
        || m.rotational_inertia_z.is_some()
}

impl Validator<'_> {
    /// The plan-motion part of a scene: `None` when the case gives none of its keys and
    /// no station drives y (a planar scene); else the azimuth, the second component (a
    /// station's y, `station_y`, when it drives y) (same kind as the first;
    /// a record is its own file with its own scale), the depth along y of a body (required
    /// for a rocking body or rigid block in a 3D scene) and the inertias when given.
    pub(super) fn spatial(
        &mut self,
        m: &RawModel,
        e: &RawExcitation,
        model: Option<&Model>,
        station_y: Option<Signal>,
        case_path: &Path,
    ) -> Option<Spatial> {
        if !gives_spatial_keys(m, e) && station_y.is_none() {
            return None;
        }
        let azimuth_deg = match e.azimuth_deg {
            None => 0.0,
            x => self.number(
                "excitation.azimuth_deg",
                x,
                Rule::range(-360.0, 360.0, "degrees from +x toward +y"),
            ),
        };
        if e.kind == "none" {
            for (f, given) in [
                ("excitation.azimuth_deg", e.azimuth_deg.is_some()),
                ("excitation.y", e.y.is_some()),
            ] {
                if given {
                    self.fail(
                        f,
                        "does not apply to kind = \"none\" (no horizontal excitation)",
                    );
                }
            }
        }
        let second = match station_y {
            Some(y) => Some(y),
            None => e.y.as_ref().and_then(|y| self.second(y, e, case_path)),
        };
        let depth = self.depth(m, model?);
        let inertia = self.inertias(m, model?);
        Some(Spatial {
            azimuth_deg,
            second,
            depth,
            inertia,
        })
    }

    /// `[excitation.y]`: a signal of the first component's kind.
    pub(super) fn second(
        &mut self,
        y: &RawSecond,
        e: &RawExcitation,
        case_path: &Path,
    ) -> Option<Signal> {
        const P: &str = "excitation.y";
        let signal = self.signal(&SignalKeys::from(y), P, case_path)?;
        if y.record.is_some() && e.kind == "ground-displacement" {
            self.fail(
                P,
                "a record is an acceleration history: the first component must be kind = \"ground-acceleration\" (or \"mass-acceleration\")",
            );
            return None;
        }
        if let (Signal::SinePulse { cycles, .. }, "ground-displacement") =
            (&signal, e.kind.as_str())
            && ((cycles * 2.0).round() - cycles * 2.0).abs() > 1e-12
        {
            self.fail(
                "excitation.y.cycles",
                "must be a whole number of half cycles for a ground displacement (else the ground would jump)",
            );
        }
        Some(signal)
    }

    /// `half_depth` and `support_rows`: required for a body in a 3D scene, refused for the
    /// oscillator (a point mass); a rigid block has no supports.
    pub(super) fn depth(&mut self, m: &RawModel, model: &Model) -> Option<Depth> {
        match model {
            Model::Oscillator(_) => {
                self.forbid("model.half_depth", m.half_depth.is_some(), "oscillator");
                self.forbid("model.support_rows", m.support_rows.is_some(), "oscillator");
                None
            }
            Model::RockingBody(_) => {
                let half_depth = self.number(
                    "model.half_depth",
                    m.half_depth,
                    Rule::extent("m (half-depth of the base along y, needed in a 3D scene)"),
                );
                let supports = match model {
                    Model::RockingBody(r) => r.supports,
                    _ => 1,
                };
                let support_rows = match m.support_rows {
                    Some(n) if n > MAX_SUPPORT_ROWS as i64 => {
                        self.fail(
                            "model.support_rows",
                            format!("is {n}, but must be at most {MAX_SUPPORT_ROWS}"),
                        );
                        1
                    }
                    Some(n) if n as u64 * supports as u64 > MAX_SUPPORT_GRID => {
                        self.fail(
                            "model.support_rows",
                            format!(
                                "is {n}: {n} rows of {supports} supports make {} supports, but \
                                 a base may have at most {MAX_SUPPORT_GRID}",
                                n as u64 * supports as u64
                            ),
                        );
                        1
                    }
                    Some(n) if n >= 1 => n as usize,
                    Some(n) => {
                        self.fail(
                            "model.support_rows",
                            format!("is {n}, but must be at least 1"),
                        );
                        1
                    }
                    None => {
                        self.fail(
                            "model.support_rows",
                            "is required in a 3D scene (rows of supports along y, at least 1)",
                        );
                        1
                    }
                };
                Some(Depth {
                    half_depth,
                    support_rows,
                })
            }
            Model::RigidBlock(_) => {
                self.forbid(
                    "model.support_rows",
                    m.support_rows.is_some(),
                    "rigid-block",
                );
                let half_depth = self.number(
                    "model.half_depth",
                    m.half_depth,
                    Rule::extent("m (half-depth of the base along y, needed in a 3D scene)"),
                );
                Some(Depth {
                    half_depth,
                    support_rows: 1,
                })
            }
        }
    }

    /// `rotational_inertia_{x,y,z}` (kg·m², about the centre of mass): all three or none;
    /// beside the planar `rotational_inertia` (which is the one about y) only if equal.
    pub(super) fn inertias(&mut self, m: &RawModel, model: &Model) -> Option<[f64; 3]> {
        let given = [
            ("model.rotational_inertia_x", m.rotational_inertia_x),
            ("model.rotational_inertia_y", m.rotational_inertia_y),
            ("model.rotational_inertia_z", m.rotational_inertia_z),
        ];
        if let Model::Oscillator(_) = model {
            for (f, x) in given {
                self.forbid(f, x.is_some(), "oscillator");
            }
            return None;
        }
        if given.iter().all(|(_, x)| x.is_none()) {
            return None;
        }
        let mut out = [0.0; 3];
        for (i, (f, x)) in given.into_iter().enumerate() {
            match x {
                None => self.fail(
                    f,
                    "is required with the other rotational inertias (give x, y and z, kg·m²)",
                ),
                x => out[i] = self.number(f, x, Rule::non_negative("kg·m²")),
            }
        }
        if let (Some(planar), Some(iy)) = (m.rotational_inertia, m.rotational_inertia_y)
            && planar != iy
        {
            self.fail(
                "model.rotational_inertia",
                format!("is {planar}, but rotational_inertia_y is {iy}: they are the same inertia (about y); give one"),
            );
        }
        Some(out)
    }
}

//! The element interface the time loop drives, in either dimension, and the plane
//! element: a CONTA178-like node-to-node contact with a fixed normal (the ground's
//! vertical). The 3D cone contact (`space::ConeContact`) is the same element with a
//! circular friction cone, behind the same trait.
//!
//! An element computes its force and tangent for a *trial* relative displacement,
//! always starting from its *committed* state (so Newton iterations inside a step never
//! accumulate history); the time loop commits the trial once the step has converged, or
//! restores the committed state when it abandons a step. Pattern after cpmech/pmsim's
//! element trait and the return-mapping algorithms of Simo & Hughes, *Computational
//! Inelasticity* (1998), §1.2 (1-D elastoplastic return mapping; here the yield limit is
//! μ times the element's own normal force).
//!
//! Sign conventions: the relative displacement is δ = u_upper − u_lower (x horizontal,
//! z vertical up); the element's force is the internal (resisting) force on the upper
//! point, −force on the lower point. A gap δz > 0 is open.

use nalgebra::{Matrix2, Vector2};

/// What the time loop asks of an element, in the dimension of its relative displacement
/// (`Vector2` in the plane, `Vector3` in space).
pub trait Element {
    /// The relative displacement δ and the force on the upper point.
    type Vector;
    /// The tangent ∂force/∂δ.
    type Tangent;
    /// Force on the upper point and tangent ∂force/∂δ at the trial relative displacement
    /// `delta`, computed from the committed state (the trial state is kept).
    fn trial(&mut self, delta: Self::Vector) -> (Self::Vector, Self::Tangent);
    /// Accept the last trial state.
    fn commit(&mut self);
    /// Forget the trial state (back to the committed one).
    fn restore(&mut self);
}

/// Contact status of an element.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// Gap open: no force.
    Open,
    /// Closed, tangential force elastic.
    Stick,
    /// Closed, tangential force at μ·N, slipping.
    Slip,
}

/// The state that history depends on, plus what the last evaluation found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactState {
    /// Accumulated slip (the shift of the tangential spring's origin), m.
    pub slip: f64,
    /// Relative displacement δ of the evaluation, m.
    pub delta: Vector2<f64>,
    /// Force on the upper point, N: (tangential T, vertical −N).
    pub force: Vector2<f64>,
    /// Status.
    pub status: Status,
}

/// CONTA178-like contact: compression-only normal penalty `kz` (unless `bonded`),
/// elastic tangential penalty `kx` capped at μ·N by return mapping, no force when open.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact178 {
    /// Tangential (sticking) stiffness, N/m.
    pub kx: f64,
    /// Normal stiffness, N/m.
    pub kz: f64,
    /// Friction coefficient (`f64::INFINITY`: never slips).
    pub mu: f64,
    /// Carries tension too and sticks when not compressed (used for element 2 of the
    /// double arrangement, see `model`), so a massless node never floats free.
    pub bonded: bool,
    committed: ContactState,
    trial: ContactState,
}

impl ContactState {
    /// A closed, unstressed element's state: no slip, no displacement, no force.
    pub const AT_REST: ContactState = ContactState {
        slip: 0.0,
        delta: Vector2::new(0.0, 0.0),
        force: Vector2::new(0.0, 0.0),
        status: Status::Stick,
    };
}

impl Contact178 {
    /// A closed, unstressed element.
    pub fn new(kx: f64, kz: f64, mu: f64, bonded: bool) -> Self {
        let s = ContactState::AT_REST;
        Self {
            kx,
            kz,
            mu,
            bonded,
            committed: s,
            trial: s,
        }
    }

    /// The committed state.
    pub fn state(&self) -> &ContactState {
        &self.committed
    }

    /// The state of the last trial (what `commit` would accept).
    pub fn trial_state(&self) -> &ContactState {
        &self.trial
    }

    /// Start from `state` (committed and trial), e.g. a series equivalent taking over the
    /// state of the element whose slip it carries.
    pub fn set_committed(&mut self, state: ContactState) {
        self.committed = state;
        self.trial = state;
    }

    /// Set the committed state only, for an element that is never trialled: a condensed
    /// support's elements 1 and 2, whose states are rebuilt from their series equivalent
    /// at every converged step (`Model::commit_step`) and only read after. Its trial
    /// state is left as it was (`restore` would copy the committed one over it).
    pub(crate) fn set_state(&mut self, state: ContactState) {
        self.committed = state;
    }

    /// Normal compression N ≥ 0 of the committed state (tension for bonded elements is
    /// returned negative), N.
    pub fn normal(&self) -> f64 {
        -self.committed.force.y
    }

    /// Tangential force T on the upper point of the committed state, N.
    pub fn tangential(&self) -> f64 {
        self.committed.force.x
    }
}

impl Contact178 {
    /// [`Element::trial`] of an element known not to be bonded (a contact with the ground:
    /// the single arrangement's elements and the series equivalents). The same
    /// operations on the same path with the bonded element's tests left out, so the same
    /// bits.
    #[inline(always)]
    pub(crate) fn trial_contact(&mut self, d: Vector2<f64>) -> (Vector2<f64>, Matrix2<f64>) {
        debug_assert!(!self.bonded);
        self.trial_as(d, false)
    }

    /// The return mapping at trial displacement `d`, bonded or not as `bonded` says.
    #[inline(always)]
    fn trial_as(&mut self, d: Vector2<f64>, bonded: bool) -> (Vector2<f64>, Matrix2<f64>) {
        let (kx, kz) = (self.kx, self.kz);
        let s_n = self.committed.slip;
        if !bonded && d.y > 0.0 {
            // Open: no force; the tangential origin follows the point, so a contact that
            // closes again starts unstressed (CONTA178 re-establishes sticking on contact).
            self.trial = ContactState {
                slip: d.x,
                delta: d,
                force: Vector2::zeros(),
                status: Status::Open,
            };
            return (Vector2::zeros(), Matrix2::zeros());
        }
        let n = -kz * d.y; // normal compression, N = −kz·δz
        let t_trial = kx * (d.x - s_n); // elastic predictor
        let cap = self.mu * n.max(0.0); // Coulomb limit μ·N of this element
        let stick = self.mu.is_infinite() || t_trial.abs() <= cap || (bonded && n <= 0.0);
        if stick {
            self.trial = ContactState {
                slip: s_n,
                delta: d,
                force: Vector2::new(t_trial, -n),
                status: Status::Stick,
            };
            (Vector2::new(t_trial, -n), Matrix2::new(kx, 0.0, 0.0, kz))
        } else {
            // Return mapping: T = sign(T_trial)·μN, slip = δx − T/kx.
            let sg = t_trial.signum();
            let t = sg * cap;
            self.trial = ContactState {
                slip: d.x - t / kx,
                delta: d,
                force: Vector2::new(t, -n),
                status: Status::Slip,
            };
            // Consistent tangent: ∂T/∂δx = 0, ∂T/∂δz = −sg·μ·kz (unsymmetric).
            (
                Vector2::new(t, -n),
                Matrix2::new(0.0, -sg * self.mu * kz, 0.0, kz),
            )
        }
    }
}

impl Element for Contact178 {
    type Vector = Vector2<f64>;
    type Tangent = Matrix2<f64>;

    #[inline]
    fn trial(&mut self, d: Vector2<f64>) -> (Vector2<f64>, Matrix2<f64>) {
        self.trial_as(d, self.bonded)
    }

    #[inline]
    fn commit(&mut self) {
        self.committed = self.trial;
    }

    fn restore(&mut self) {
        self.trial = self.committed;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sticks_then_slips_at_mu_times_its_own_normal_force() {
        let mut c = Contact178::new(1000.0, 4000.0, 0.5, false);
        // Compressed by 1 mm: N = 4 N, limit 2 N.
        let (f, k) = c.trial(Vector2::new(0.001, -0.001));
        assert_eq!(f, Vector2::new(1.0, -4.0));
        assert_eq!(k, Matrix2::new(1000.0, 0.0, 0.0, 4000.0));
        let (f, k) = c.trial(Vector2::new(0.005, -0.001));
        assert_eq!(f.x, 2.0);
        assert!((c.trial.slip - 0.003).abs() < 1e-15);
        assert_eq!(k[(0, 1)], -0.5 * 4000.0);
        c.commit();
        // Unloading from the shifted origin: δx = 0.004 gives T = kx(0.004 − 0.003) = 1.
        let (f, _) = c.trial(Vector2::new(0.004, -0.001));
        assert!((f.x - 1.0).abs() < 1e-12);
        c.restore();
        assert!((c.state().slip - 0.003).abs() < 1e-15);
    }

    #[test]
    fn open_contact_carries_nothing_and_resets_its_origin() {
        let mut c = Contact178::new(1000.0, 4000.0, 0.5, false);
        let (f, k) = c.trial(Vector2::new(0.01, 0.002));
        assert_eq!(f, Vector2::zeros());
        assert_eq!(k, Matrix2::zeros());
        c.commit();
        assert_eq!(c.state().slip, 0.01);
        assert_eq!(c.state().status, Status::Open);
    }

    #[test]
    fn bonded_infinite_friction_is_linear_both_ways() {
        let mut c = Contact178::new(10.0, 20.0, f64::INFINITY, true);
        let (f, _) = c.trial(Vector2::new(1.0, 0.5));
        assert_eq!(f, Vector2::new(10.0, 10.0));
    }
}

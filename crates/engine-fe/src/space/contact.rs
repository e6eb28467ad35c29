//! The 3D contact element: CONTA178-like with a fixed vertical normal, a compression-only
//! normal penalty and an isotropic tangential penalty capped on the circular friction
//! cone |T| ≤ μ·N by radial return (Simo & Hughes, *Computational Inelasticity* (1998),
//! §2.3 applied to the friction cone; Wriggers, *Computational Contact Mechanics* (2006),
//! §5.2).
//!
//! Relative displacement δ = u_upper − u_lower = (δt, δz) with δt the horizontal pair.
//!   N = kz·max(−δz, 0);  trial T* = kt·(δt − p)  (p: accumulated slip, the spring origin)
//!   stick (|T*| ≤ μN): T = T*, tangent diag(kt, kt, kz);
//!   slip: n = T*/|T*|, T = μN·n, p ← δt − T/kt, consistent tangent
//!     ∂T/∂δt = μN/|T*|·kt·(I − n⊗n),  ∂T/∂δz = −μ·kz·n  (unsymmetric).
//! Open (δz > 0): no force, the origin follows the point. The force returned is the
//! element's internal force on the upper point, (T, −N) — the 2D element's convention.
//! With δy = 0 and no y slip every operation reduces to the 2D element's (`element.rs`),
//! bit for bit: |T*| = √(T*x²) = |T*x| exactly and 1 − n_x² = 0 exactly.

use nalgebra::{Matrix3, Vector2, Vector3};

use crate::element::{Element, Status};

/// History and the last evaluation of a cone contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConeState {
    /// Accumulated slip (the tangential spring's origin), m.
    pub slip: Vector2<f64>,
    /// Relative displacement of the evaluation, m.
    pub delta: Vector3<f64>,
    /// Internal force on the upper point (Tx, Ty, −N), N.
    pub force: Vector3<f64>,
    /// Status.
    pub status: Status,
}

/// A contact with a circular friction cone (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConeContact {
    /// Tangential stiffness (both horizontal directions), N/m.
    pub kt: f64,
    /// Normal stiffness, N/m.
    pub kz: f64,
    /// Friction coefficient (`f64::INFINITY`: never slips).
    pub mu: f64,
    /// Carries tension too and sticks when not compressed (element 2 of the double
    /// arrangement, as in 2D).
    pub bonded: bool,
    committed: ConeState,
    trial: ConeState,
    /// The last slipping trial's μN/|T*|·kt and direction n = T*/|T*| (`slip_tangent`).
    slip_tangent: (f64, Vector2<f64>),
}

impl ConeContact {
    /// A closed, unstressed element.
    pub fn new(kt: f64, kz: f64, mu: f64, bonded: bool) -> Self {
        let s = ConeState {
            slip: Vector2::zeros(),
            delta: Vector3::zeros(),
            force: Vector3::zeros(),
            status: Status::Stick,
        };
        Self {
            kt,
            kz,
            mu,
            bonded,
            committed: s,
            trial: s,
            slip_tangent: (0.0, Vector2::zeros()),
        }
    }

    /// The committed state.
    pub fn state(&self) -> &ConeState {
        &self.committed
    }

    /// The state of the last trial (what `commit` would accept).
    pub fn trial_state(&self) -> &ConeState {
        &self.trial
    }

    /// Start from `state` (committed and trial): a series equivalent taking over the state
    /// of the element whose slip it carries, or an element set from its equivalent.
    pub fn set_committed(&mut self, state: ConeState) {
        self.committed = state;
        self.trial = state;
    }

    /// Normal compression N of the committed state (negative: tension of a bonded one), N.
    pub fn normal(&self) -> f64 {
        -self.committed.force.z
    }

    /// Tangential force (Tx, Ty) on the upper point of the committed state, N.
    pub fn tangential(&self) -> Vector2<f64> {
        self.committed.force.xy()
    }

    /// The last trial's tangent when it slipped, as D = diag(ρ, ρ, kz) − (n, 0)·wᵀ with
    /// ρ = μN/|T*|·kt, n = T*/|T*| and w = (ρ·n, μ·kz): returns (ρ, n). Meaningful only
    /// after a trial whose status is `Slip`.
    pub fn slip_tangent(&self) -> (f64, Vector2<f64>) {
        self.slip_tangent
    }
}

impl Element for ConeContact {
    type Vector = Vector3<f64>;
    type Tangent = Matrix3<f64>;

    #[inline]
    fn trial(&mut self, d: Vector3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
        let (kt, kz) = (self.kt, self.kz);
        let p = self.committed.slip;
        let dt = d.xy();
        if !self.bonded && d.z > 0.0 {
            self.trial = ConeState {
                slip: dt,
                delta: d,
                force: Vector3::zeros(),
                status: Status::Open,
            };
            return (Vector3::zeros(), Matrix3::zeros());
        }
        let n = -kz * d.z;
        let t_trial = (dt - p) * kt;
        let cap = self.mu * n.max(0.0);
        let size = t_trial.norm();
        let stick = self.mu.is_infinite() || size <= cap || (self.bonded && n <= 0.0);
        if stick {
            let force = Vector3::new(t_trial.x, t_trial.y, -n);
            self.trial = ConeState {
                slip: p,
                delta: d,
                force,
                status: Status::Stick,
            };
            return (
                force,
                Matrix3::new(kt, 0.0, 0.0, 0.0, kt, 0.0, 0.0, 0.0, kz),
            );
        }
        // Radial return onto the cone.
        let dir = t_trial / size;
        let t = dir * cap;
        let force = Vector3::new(t.x, t.y, -n);
        self.trial = ConeState {
            slip: dt - t / kt,
            delta: d,
            force,
            status: Status::Slip,
        };
        let ratio = cap / size * kt;
        self.slip_tangent = (ratio, dir);
        let (nx, ny) = (dir.x, dir.y);
        let (zx, zy) = (-self.mu * kz * nx, -self.mu * kz * ny);
        let tangent = Matrix3::new(
            ratio * (1.0 - nx * nx),
            -ratio * nx * ny,
            zx,
            -ratio * ny * nx,
            ratio * (1.0 - ny * ny),
            zy,
            0.0,
            0.0,
            kz,
        );
        (force, tangent)
    }

    /// Accept the last trial state.
    #[inline]
    fn commit(&mut self) {
        self.committed = self.trial;
    }

    /// Forget the trial state.
    fn restore(&mut self) {
        self.trial = self.committed;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radial_return_lands_on_the_cone_along_the_trial_force() {
        let mut c = ConeContact::new(1000.0, 4000.0, 0.5, false);
        // N = 4 N, cap 2 N; trial T* = 1000·(0.003, 0.004) = (3, 4), |T*| = 5.
        let (f, _) = c.trial(Vector3::new(0.003, 0.004, -0.001));
        assert!((f.x - 1.2).abs() < 1e-15 && (f.y - 1.6).abs() < 1e-15);
        assert_eq!(f.z, -4.0);
        // p = δt − T/kt = (0.003 − 0.0012, 0.004 − 0.0016)
        assert!((c.trial.slip - Vector2::new(0.0018, 0.0024)).norm() < 1e-18);
        c.commit();
        assert_eq!(c.state().status, Status::Slip);
    }

    #[test]
    fn the_tangent_is_the_derivative_of_the_return_mapping() {
        // Central differences of the force against the consistent tangent, in slip.
        let c0 = ConeContact::new(1000.0, 4000.0, 0.5, false);
        let d = Vector3::new(0.003, -0.004, -0.001);
        let (_, k) = c0.clone().trial(d);
        let h = 1e-9;
        let mut worst: f64 = 0.0;
        for j in 0..3 {
            let mut dp = d;
            dp[j] += h;
            let mut dm = d;
            dm[j] -= h;
            let fd = (c0.clone().trial(dp).0 - c0.clone().trial(dm).0) / (2.0 * h);
            worst = worst.max((fd - k.column(j)).norm());
        }
        // Measured 2.6e-7 against entries of order 1e3 (difference quotient round-off).
        assert!(worst < 1e-5, "{worst}");
    }

    #[test]
    fn reduces_to_the_two_dimensional_element_in_plane() {
        use crate::element::Contact178;
        let mut c2 = Contact178::new(1000.0, 4000.0, 0.5, false);
        let mut c3 = ConeContact::new(1000.0, 4000.0, 0.5, false);
        for (x, z) in [
            (0.001, -0.001),
            (0.007, -0.001),
            (-0.002, -0.0015),
            (0.01, 0.002),
        ] {
            let (f2, k2) = c2.trial(nalgebra::Vector2::new(x, z));
            let (f3, k3) = c3.trial(Vector3::new(x, 0.0, z));
            assert_eq!((f3.x, f3.y, f3.z), (f2.x, 0.0, f2.y));
            assert_eq!(
                (k3[(0, 0)], k3[(0, 2)], k3[(2, 0)], k3[(2, 2)]),
                (k2[(0, 0)], k2[(0, 1)], k2[(1, 0)], k2[(1, 1)])
            );
            c2.commit();
            c3.commit();
            assert_eq!(c3.state().slip, Vector2::new(c2.state().slip, 0.0));
        }
    }
}

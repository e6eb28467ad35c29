//! The normal force under vertical ground motion, stepped the way the paper's spreadsheet
//! would step it: one more column pair beside the horizontal one. With the contact's
//! vertical stiffness Kz (`normal_force = "dynamic"`) the compression δ of the base
//! contact is a second oscillator, M·δ'' = M·(g + a_v(t)) − N, N = Kz·max(δ, 0)
//! (compression only), integrated by the same average-acceleration predictor and corrector
//! (paper Eqs 3–5, one predicting and one correcting pass) from static equilibrium
//! δ = M·g/Kz. With a rigid vertical contact (`"quasi-static"`) N = M·max(g + a_v(t), 0).
//! Either way the horizontal pass of the same step uses Ru = μ·N of this pass.

use rockslide_core::case::{NormalForce, Oscillator, Signal, Vertical};

/// The vertical state of the base contact, stepped pass by pass with the horizontal one.
pub struct NormalStepper<'a> {
    signal: &'a Signal,
    mode: NormalForce,
    m: f64,
    g: f64,
    kz: f64,
    /// Committed compression, its rate and acceleration (end of the previous step).
    committed: (f64, f64, f64),
    /// This pass's compression, rate, acceleration and normal force.
    trial: (f64, f64, f64, f64),
}

impl<'a> NormalStepper<'a> {
    /// At static equilibrium, N = M·g.
    pub fn new(osc: &Oscillator, vertical: &'a Vertical) -> Self {
        let (m, g, kz) = (osc.mass, osc.gravity, osc.contact.kz);
        let d0 = m * g / kz;
        let a0 = g + vertical.signal.value(0.0) - kz * d0 / m;
        let (d0, n0) = match vertical.normal_force {
            NormalForce::Dynamic => (d0, m * g),
            NormalForce::QuasiStatic => {
                let n0 = m * (g + vertical.signal.value(0.0)).max(0.0);
                (n0 / kz, n0)
            }
        };
        NormalStepper {
            signal: &vertical.signal,
            mode: vertical.normal_force,
            m,
            g,
            kz,
            committed: (d0, 0.0, a0),
            trial: (d0, 0.0, a0, n0),
        }
    }

    /// One pass at the step ending at `t`: the predicting pass (`correcting = false`)
    /// starts from a_t = a_{t−1}; the correcting pass from the predicting pass's a_t. After
    /// the correcting pass the step is committed.
    pub fn pass(&mut self, t: f64, dt: f64, correcting: bool) {
        let ge = self.g + self.signal.value(t);
        match self.mode {
            NormalForce::QuasiStatic => {
                let n = self.m * ge.max(0.0);
                self.trial = (n / self.kz, 0.0, 0.0, n);
            }
            NormalForce::Dynamic => {
                let (d_prev, v_prev, a_prev) = self.committed;
                let a_guess = if correcting { self.trial.2 } else { a_prev };
                let v = v_prev + 0.5 * (a_guess + a_prev) * dt; // Eq 3
                let d = d_prev + 0.5 * (v + v_prev) * dt; // Eq 4
                let n = self.kz * d.max(0.0); // compression only
                let a = ge - n / self.m; // Eq 5 for the vertical mass
                self.trial = (d, v, a, n);
            }
        }
        if correcting {
            self.committed = (self.trial.0, self.trial.1, self.trial.2);
        }
    }

    /// Normal force of the latest pass, N.
    pub fn normal(&self) -> f64 {
        self.trial.3
    }

    /// Gap of the base contact, m (−compression).
    pub fn gap(&self) -> f64 {
        -self.trial.0
    }

    /// The setting in words, for the run's settings table.
    pub fn describe(&self) -> String {
        match self.mode {
            NormalForce::Dynamic => "μ·N(t), N = Kz·δ from M·δ'' + Kz·δ = M·(g + a_v), stepped by the same predictor-corrector (compression only)".into(),
            NormalForce::QuasiStatic => "μ·N(t), N = M·(g + a_v) (rigid vertical contact)".into(),
        }
    }
}

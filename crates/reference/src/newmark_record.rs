//! Newmark's rigid sliding block (Newmark 1965) driven by a sampled acceleration record —
//! the computation USGS SLAMMER (Jibson, Rathje, Jibson & Lee 2013) calls "rigid-block
//! analysis", written independently of every engine.
//!
//! The block sits on the ground with a yield acceleration ky (= μ·g on a level frictional
//! base). While stuck it moves with the ground; it slips once the ground acceleration
//! exceeds ky, and then its sliding velocity relative to the ground obeys
//! `dv/dt = a(t) − σ·ky` (σ = direction of sliding) until v returns to zero.
//!
//! The ground acceleration is taken linear between samples (as [`rockslide_core::case::Signal`]
//! does), and each step is integrated *exactly* for that piecewise-linear input: onset
//! times are located where a(t) crosses ky, stop times where the quadratic v(t) reaches
//! zero. SLAMMER integrates the same equation by the trapezoidal rule sample to sample;
//! both converge to the same displacement as the sampling is refined.
//!
//! Conventions (SLAMMER's): displacement u is positive in the direction the ground
//! *accelerates* when it exceeds +ky (the "downslope" direction of a slope, the block
//! lagging behind the ground); reported in cm as well as m; a record is run with both
//! polarities (as recorded and inverted) because its sign is arbitrary. The block's
//! sliding relative to the ground in rockslide's convention (mass minus ground, as the
//! PEPO's xp) is −u.

use rockslide_core::case::record::STANDARD_GRAVITY;

/// Whether the block may slide both ways (level frictional base) or only one way (SLAMMER's
/// downslope rigid block, yield in the other direction taken as infinite).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sliding {
    /// Slides only with u increasing (SLAMMER's rigid-block convention).
    OneWay,
    /// Slides either way with the same ky (a block on a level frictional base).
    TwoWay,
}

/// The history of one rigid-block run, at the record's samples.
#[derive(Debug, Clone, PartialEq)]
pub struct NewmarkRun {
    /// Sample interval, s.
    pub dt: f64,
    /// Sliding velocity relative to the ground, m/s (SLAMMER sign convention).
    pub vel: Vec<f64>,
    /// Accumulated sliding displacement u, m (SLAMMER sign convention).
    pub disp: Vec<f64>,
    /// Number of separate sliding episodes (deterministic counter).
    pub episodes: usize,
}

impl NewmarkRun {
    /// Final displacement, m.
    pub fn residual(&self) -> f64 {
        self.disp.last().copied().unwrap_or(0.0)
    }
    /// Largest |displacement| over the run, m.
    pub fn peak(&self) -> f64 {
        self.disp.iter().fold(0.0_f64, |m, d| m.max(d.abs()))
    }
}

/// Run the rigid block under `acc` (m/s², samples every `dt` s, linear in between, then
/// held at zero for `tail` extra seconds so a block still sliding at the record's end comes
/// to rest), yield acceleration `ky` (m/s², ≥ 0).
pub fn rigid_block(dt: f64, acc: &[f64], ky: f64, sliding: Sliding, tail: f64) -> NewmarkRun {
    let extra = (tail / dt).ceil().max(0.0) as usize;
    let n = acc.len() + extra;
    let a_at = |i: usize| acc.get(i).copied().unwrap_or(0.0);
    let mut vel = Vec::with_capacity(n);
    let mut disp = Vec::with_capacity(n);
    let (mut v, mut u) = (0.0_f64, 0.0_f64);
    let mut sigma = 0.0_f64; // direction of the current slide, 0 when stuck
    let mut episodes = 0;
    if n > 0 {
        vel.push(0.0);
        disp.push(0.0);
    }
    for i in 1..n {
        let (a0, a1) = (a_at(i - 1), a_at(i));
        let mut s = 0.0; // time already used within this step
        // At most a few events per step: onset, stop (and a renewed onset after a stop).
        for _ in 0..4 {
            if s >= dt {
                break;
            }
            let (b0, b1) = (lerp(a0, a1, s / dt), a1);
            let h = dt - s;
            if sigma == 0.0 {
                // Stuck: find where the ground acceleration first exceeds the yield level.
                let Some((dir, f)) = onset(b0, b1, ky, sliding) else {
                    break;
                };
                sigma = dir;
                episodes += 1;
                s += f * h;
                continue;
            }
            // Sliding in direction σ: r(τ) = a(τ) − σ·ky, linear over the rest of the step.
            let (r0, r1) = (b0 - sigma * ky, b1 - sigma * ky);
            let dr = (r1 - r0) / h;
            // v(τ) = v + r0·τ + dr·τ²/2; stop at the first τ in (0, h] where σ·v(τ) ≤ 0.
            match first_zero(v, r0, dr, h, sigma) {
                Some(tau) => {
                    u += v * tau + r0 * tau * tau / 2.0 + dr * tau * tau * tau / 6.0;
                    v = 0.0;
                    sigma = 0.0;
                    s += tau.max(1e-12 * dt);
                }
                None => {
                    u += v * h + r0 * h * h / 2.0 + dr * h * h * h / 6.0;
                    v += r0 * h + dr * h * h / 2.0;
                    s = dt;
                }
            }
        }
        vel.push(v);
        disp.push(u);
    }
    NewmarkRun {
        dt,
        vel,
        disp,
        episodes,
    }
}

fn lerp(a: f64, b: f64, f: f64) -> f64 {
    a + (b - a) * f
}

/// Direction and fraction of the interval at which a linear a(τ) from `b0` to `b1` first
/// exceeds the yield level (strictly, and heading further out), if it does.
fn onset(b0: f64, b1: f64, ky: f64, sliding: Sliding) -> Option<(f64, f64)> {
    let mut best: Option<(f64, f64)> = None;
    let dirs: &[f64] = match sliding {
        Sliding::OneWay => &[1.0],
        Sliding::TwoWay => &[1.0, -1.0],
    };
    for &d in dirs {
        let (c0, c1) = (d * b0 - ky, d * b1 - ky); // > 0: beyond yield in direction d
        let f = if c0 > 0.0 {
            0.0 // beyond yield at the start of the interval: slips at once
        } else if c1 > 0.0 {
            c0 / (c0 - c1)
        } else {
            continue;
        };
        if best.is_none_or(|(_, g)| f < g) {
            best = Some((d, f));
        }
    }
    best
}

/// First τ in (0, h] at which σ·(v + r0·τ + dr·τ²/2) reaches 0 from above.
fn first_zero(v: f64, r0: f64, dr: f64, h: f64, sigma: f64) -> Option<f64> {
    let end = sigma * (v + r0 * h + dr * h * h / 2.0);
    // Roots of (dr/2)τ² + r0τ + v = 0, smallest positive one within (0, h].
    let mut roots = [f64::NAN; 2];
    if dr.abs() < 1e-300 || (dr * h * h).abs() < 1e-12 * (r0 * h).abs() {
        if r0 != 0.0 {
            roots[0] = -v / r0;
        }
    } else {
        let disc = r0 * r0 - 2.0 * dr * v;
        if disc >= 0.0 {
            // Stable quadratic roots (Numerical Recipes §5.6): q / (dr/2) and v / q.
            let sgn = if r0 >= 0.0 { 1.0 } else { -1.0 };
            let q = -0.5 * (r0 + sgn * disc.sqrt());
            if q != 0.0 {
                roots[0] = q / (dr / 2.0);
                roots[1] = v / q;
            }
        }
    }
    let mut first: Option<f64> = None;
    for t in roots {
        if t.is_finite() && t > 0.0 && t <= h {
            first = Some(first.map_or(t, |f: f64| f.min(t)));
        }
    }
    if first.is_none() && end <= 0.0 {
        return Some(h); // rounding: it ends at or past zero within the step
    }
    first
}

/// A record's SLAMMER-style rigid-block summary: both polarities, m and cm.
#[derive(Debug, Clone, PartialEq)]
pub struct NewmarkSummary {
    /// Yield acceleration, m/s².
    pub ky: f64,
    /// Residual displacement with the record as given, m.
    pub normal: f64,
    /// Residual displacement with the record inverted, m.
    pub inverse: f64,
    /// Sliding episodes (normal, inverse).
    pub episodes: (usize, usize),
}

impl NewmarkSummary {
    /// Run a record both ways.
    pub fn of(dt: f64, acc: &[f64], ky: f64, sliding: Sliding, tail: f64) -> Self {
        let inverted: Vec<f64> = acc.iter().map(|a| -a).collect();
        let n = rigid_block(dt, acc, ky, sliding, tail);
        let i = rigid_block(dt, &inverted, ky, sliding, tail);
        Self {
            ky,
            normal: n.residual(),
            inverse: i.residual(),
            episodes: (n.episodes, i.episodes),
        }
    }
    /// Mean of the two polarities' |displacement|, m (SLAMMER's "average").
    pub fn mean(&self) -> f64 {
        (self.normal.abs() + self.inverse.abs()) / 2.0
    }
    /// Table in SLAMMER's units: ky in g, displacements in cm (and m).
    pub fn table(&self, label: &str) -> String {
        let cm = |m: f64| m * 100.0;
        format!(
            "| record | ky [g] | polarity | displacement [cm] | displacement [m] |\n|---|---:|---|---:|---:|\n\
             | {label} | {ky:.4} | normal | {n:.3} | {nm:.5} |\n\
             | {label} | {ky:.4} | inverse | {i:.3} | {im:.5} |\n\
             | {label} | {ky:.4} | mean | {a:.3} | {am:.5} |\n",
            ky = self.ky / STANDARD_GRAVITY,
            n = cm(self.normal),
            nm = self.normal,
            i = cm(self.inverse),
            im = self.inverse,
            a = cm(self.mean()),
            am = self.mean(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn below_yield_nothing_slides() {
        let acc: Vec<f64> = (0..100).map(|i| 0.9 * (i as f64 * 0.3).sin()).collect();
        let r = rigid_block(0.01, &acc, 1.0, Sliding::TwoWay, 1.0);
        assert_eq!(r.residual(), 0.0);
        assert_eq!(r.episodes, 0);
    }

    #[test]
    fn constant_acceleration_from_rest_is_exact() {
        // a = 3, ky = 1 throughout 1 s: v = 2t, u = t² (exact for linear input).
        let acc = vec![3.0; 101];
        let r = rigid_block(0.01, &acc, 1.0, Sliding::OneWay, 0.0);
        assert!((r.disp[100] - 1.0).abs() < 1e-12, "{}", r.disp[100]);
        assert!((r.vel[100] - 2.0).abs() < 1e-12);
    }
}

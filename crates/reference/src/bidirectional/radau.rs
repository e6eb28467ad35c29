//! The three-stage Radau IIA method (order 5, L-stable, stiffly accurate: the last stage
//! is the step's end) for the sliding block, u̇ = d(t) − a_f(t)·e, ṡ = u, with the stage
//! velocities written in polar form Uᵢ = ρᵢ·e(θᵢ) and the friction along e(θᵢ).
//!
//! The sliding direction relaxes toward the drive at the rate a_f/|u|: stiff near rest,
//! where an explicit stage is unstable and an L-stable implicit one damps the relaxation as
//! the exact flow does. In Cartesian unknowns the stage equations carry u/|u|, which is
//! not smooth at u = 0, and Newton's method fails near rest (it jumps across the origin);
//! in (ρ, θ) they are smooth everywhere, the Jacobian of θ's column is (ρᵢ + h·aᵢᵢ·a_f)·e⊥
//! — regular at ρ = 0 — and ρ < 0 continues the motion past a stop with the friction still
//! along e(θ), so the stop is the smooth root ρ = 0 of the last stage's speed. Coefficients:
//! Hairer & Wanner, *Solving Ordinary Differential Equations II*, IV.5, table 5.6.

/// √6.
const S6: f64 = 2.449_489_742_783_178;

/// The nodes c₁ = (4 − √6)/10, c₂ = (4 + √6)/10, c₃ = 1.
const C: [f64; 3] = [(4.0 - S6) / 10.0, (4.0 + S6) / 10.0, 1.0];

/// The Butcher matrix; its last row is the weights b.
const A: [[f64; 3]; 3] = [
    [
        (88.0 - 7.0 * S6) / 360.0,
        (296.0 - 169.0 * S6) / 1800.0,
        (-2.0 + 3.0 * S6) / 225.0,
    ],
    [
        (296.0 + 169.0 * S6) / 1800.0,
        (88.0 + 7.0 * S6) / 360.0,
        (-2.0 - 3.0 * S6) / 225.0,
    ],
    [(16.0 - S6) / 36.0, (16.0 + S6) / 36.0, 1.0 / 9.0],
];

/// Most Newton iterations on the stage equations before a step is declared unsolvable.
const NEWTON_ITERATIONS: usize = 50;

/// The drive d(t) (m/s²) and the friction limit a_f(t) (m/s²) along a step.
pub type Law<'a> = dyn Fn(f64) -> ([f64; 2], f64) + 'a;

/// The result of one step.
#[derive(Debug, Clone, Copy)]
pub struct Step {
    /// The stage speeds ρᵢ at t + cᵢ·h (negative: past a stop); the last is the end's.
    pub speed: [f64; 3],
    /// The stage directions θᵢ, rad.
    pub angle: [f64; 3],
    /// The position at the step's end.
    pub pos: [f64; 2],
}

impl Step {
    /// The velocity at the step's end.
    pub fn velocity(&self) -> [f64; 2] {
        let (s, c) = self.angle[2].sin_cos();
        [self.speed[2] * c, self.speed[2] * s]
    }
}

/// One step of length `h` from (t, s) at speed `speed` ≥ 0 along `angle` (the drive's
/// direction at rest), or `None` when Newton's method does not converge.
pub fn step(law: &Law, t: f64, s: [f64; 2], speed: f64, angle: f64, h: f64) -> Option<Step> {
    let u = {
        let (sn, cs) = angle.sin_cos();
        [speed * cs, speed * sn]
    };
    let stages = [0, 1, 2].map(|j| law(t + C[j] * h));
    let (d0, af0) = law(t);
    let scale = speed + h * (af0 + d0[0].hypot(d0[1]));
    let (sn, cs) = angle.sin_cos();
    let ahead = d0[0] * cs + d0[1] * sn - af0;
    let mut rho = C.map(|c| speed + c * h * ahead);
    let mut theta = [angle; 3];
    for _ in 0..NEWTON_ITERATIONS {
        let e = theta.map(|th| {
            let (sn, cs) = th.sin_cos();
            [cs, sn]
        });
        let mut m = [[0.0; 6]; 6];
        let mut r = [0.0; 6];
        for i in 0..3 {
            for k in 0..2 {
                let mut sum = 0.0;
                for j in 0..3 {
                    let (d, af) = stages[j];
                    sum += A[i][j] * (d[k] - af * e[j][k]);
                    // ∂/∂θⱼ of −h·aᵢⱼ·(d − a_f·e(θⱼ)) = h·aᵢⱼ·a_f·e⊥(θⱼ)
                    let perp = if k == 0 { -e[j][1] } else { e[j][0] };
                    m[2 * i + k][2 * j + 1] = h * A[i][j] * af * perp;
                }
                let perp = if k == 0 { -e[i][1] } else { e[i][0] };
                m[2 * i + k][2 * i] = e[i][k];
                m[2 * i + k][2 * i + 1] += rho[i] * perp;
                r[2 * i + k] = -(rho[i] * e[i][k] - u[k] - h * sum);
            }
        }
        let dx = solve6(m, r)?;
        let mut change = 0.0_f64;
        for i in 0..3 {
            rho[i] += dx[2 * i];
            theta[i] += dx[2 * i + 1];
            change = change
                .max(dx[2 * i].abs())
                .max((rho[i].abs() + h * stages[i].1) * dx[2 * i + 1].abs());
        }
        if !(rho.iter().chain(&theta).all(|x| x.is_finite())) {
            return None;
        }
        if change <= 16.0 * f64::EPSILON * scale {
            let mut pos = s;
            for j in 0..3 {
                let (sn, cs) = theta[j].sin_cos();
                pos[0] += h * A[2][j] * rho[j] * cs;
                pos[1] += h * A[2][j] * rho[j] * sn;
            }
            return Some(Step {
                speed: rho,
                angle: theta,
                pos,
            });
        }
    }
    None
}

/// Solve M·x = r (6×6) by Gaussian elimination with partial pivoting; `None` if singular.
fn solve6(mut m: [[f64; 6]; 6], mut r: [f64; 6]) -> Option<[f64; 6]> {
    for col in 0..6 {
        let pivot = (col..6).max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))?;
        if m[pivot][col] == 0.0 || !m[pivot][col].is_finite() {
            return None;
        }
        m.swap(col, pivot);
        r.swap(col, pivot);
        let pivot_row = m[col];
        for row in col + 1..6 {
            let factor = m[row][col] / pivot_row[col];
            for (x, p) in m[row][col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= factor * p;
            }
            r[row] -= factor * r[col];
        }
    }
    let mut x = [0.0; 6];
    for row in (0..6).rev() {
        let mut sum = r[row];
        for k in row + 1..6 {
            sum -= m[row][k] * x[k];
        }
        x[row] = sum / m[row][row];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A constant drive (1.5, 0) against a_f = 1 from rest: the block slides along +x at
    /// u = 0.5·t, s = 0.25·t² — exact for the method (a quadratic position).
    #[test]
    fn constant_drive_from_rest_is_exact() {
        let law = |_t: f64| ([1.5, 0.0], 1.0);
        let st = step(&law, 0.0, [0.0, 0.0], 0.0, 0.0, 0.1).unwrap();
        assert!(
            (st.pos[0] - 0.0025).abs() < 1e-18 && st.pos[1].abs() < 1e-18,
            "{st:?}"
        );
        assert!((st.speed[2] - 0.05).abs() < 1e-17, "{st:?}");
    }

    /// A block sliding along +x at 1 m/s with a constant sideways drive (0, 0.5), a_f = 1:
    /// no closed form; the step's fifth order shows as the error of n steps against 2n
    /// falling 32-fold.
    #[test]
    fn fifth_order_while_sliding() {
        let law = |_t: f64| ([0.0, 0.5], 1.0);
        let run = |n: usize| {
            let h = 0.5 / n as f64;
            let (mut s, mut v, mut th) = ([0.0, 0.0], 1.0, 0.0);
            for i in 0..n {
                let st = step(&law, i as f64 * h, s, v, th, h).unwrap();
                (s, v, th) = (st.pos, st.speed[2], st.angle[2]);
            }
            s
        };
        let (a, b, c) = (run(8), run(16), run(256));
        let e = |p: [f64; 2]| (p[0] - c[0]).hypot(p[1] - c[1]);
        let order = (e(a) / e(b)).log2();
        assert!(order > 4.7 && order < 5.5, "{order}");
    }
}

//! LU factors with partial pivoting of the Newton matrices, on the stack: nalgebra's
//! `LU` algorithm written out for a fixed size — the first largest |pivot| of the column,
//! the multipliers times the pivot's reciprocal, the same updates in the same order — so
//! the factors and solutions are nalgebra's bit for bit (unit tests) at a fraction of the
//! instructions.
//!
//! - [`Lu3`]: the plane model's 3×3 body system (X, Z, θ).
//! - [`Lu2`]: its live 2×2 block when θ is locked (the sliding oscillator's scalar step),
//!   `Lu3` on [[a, b, 0], [c, d, 0], [0, 0, 1]] operation for operation.
//! - [`Lu6`]: the 3D model's 6×6 body system (X, Θ).

use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

/// LU factors of a 3×3 matrix with partial pivoting, `lu[row][column]`: nalgebra's `LU`
/// algorithm written out for 3×3 — the first largest |pivot| of the column, the
/// multipliers times the pivot's reciprocal, the same updates in the same order — so the
/// factors and solutions are the same bits (unit test) at a fraction of the instructions.
#[derive(Debug, Clone, Copy, Default)]
pub struct Lu3 {
    lu: [[f64; 3]; 3],
    /// Row swapped with row `i` at step `i`.
    swaps: [usize; 3],
}

impl Lu3 {
    /// Factor `m`.
    pub fn new(m: &Matrix3<f64>) -> Self {
        let mut a = [
            [m[(0, 0)], m[(0, 1)], m[(0, 2)]],
            [m[(1, 0)], m[(1, 1)], m[(1, 2)]],
            [m[(2, 0)], m[(2, 1)], m[(2, 2)]],
        ];
        let mut swaps = [0, 1, 2];
        eliminate::<3, 0>(&mut a, &mut swaps);
        eliminate::<3, 1>(&mut a, &mut swaps);
        eliminate::<3, 2>(&mut a, &mut swaps);
        Self { lu: a, swaps }
    }

    /// Solve `m·x = b`; `None` if `m` is singular.
    pub fn solve(&self, b: &Vector3<f64>) -> Option<Vector3<f64>> {
        let mut x = [b.x, b.y, b.z];
        for (i, &p) in self.swaps.iter().enumerate() {
            if p != i {
                x.swap(i, p);
            }
        }
        let a = &self.lu;
        for i in 0..2 {
            let c = x[i];
            for j in i + 1..3 {
                x[j] += -c * a[j][i];
            }
        }
        for i in (0..3).rev() {
            if a[i][i] == 0.0 {
                return None;
            }
            let c = x[i] / a[i][i];
            x[i] = c;
            for j in 0..i {
                x[j] += -c * a[j][i];
            }
        }
        Some(Vector3::new(x[0], x[1], x[2]))
    }
}

/// LU factors with partial pivoting of the Newton matrix's live block [[a, b], [c, d]]:
/// `Lu3` on [[a, b, 0], [c, d, 0], [0, 0, 1]] operation for operation (row 1 the pivot
/// only when strictly larger; the multiplier times the pivot's reciprocal), so the
/// solutions are the same bits. Kept with the matrix it factors, reused while the next
/// matrix is the same bit for bit.
#[derive(Debug, Clone, Copy)]
pub struct Lu2 {
    matrix: [f64; 4],
    swap: bool,
    u00: f64,
    u01: f64,
    l10: f64,
    u11: f64,
}

impl Lu2 {
    pub(crate) fn new(matrix: [f64; 4]) -> Self {
        let [a, b, c, d] = matrix;
        let swap = c.abs() > a.abs();
        let ((u00, u01), (r0, r1)) = if swap {
            ((c, d), (a, b))
        } else {
            ((a, b), (c, d))
        };
        let (l10, u11) = if u00 == 0.0 {
            (r0, r1)
        } else {
            let l = r0 * (1.0 / u00);
            (l, r1 + -u01 * l)
        };
        Self {
            matrix,
            swap,
            u00,
            u01,
            l10,
            u11,
        }
    }

    pub(crate) fn same_matrix(&self, m: &[f64; 4]) -> bool {
        self.matrix
            .iter()
            .zip(m)
            .all(|(x, y)| x.to_bits() == y.to_bits())
    }

    /// Solve for the right-hand side (b0, b1); `None` if the matrix is singular.
    pub(crate) fn solve(&self, b0: f64, b1: f64) -> Option<(f64, f64)> {
        if self.u00 == 0.0 || self.u11 == 0.0 {
            return None;
        }
        let (y0, y1) = if self.swap { (b1, b0) } else { (b0, b1) };
        let y1 = y1 + -y0 * self.l10;
        let x1 = y1 / self.u11;
        let x0 = (y0 + -x1 * self.u01) / self.u00;
        Some((x0, x1))
    }
}

/// The matrix order.
const N6: usize = 6;

/// Column `I`'s step of the factorisation of the N × N `a` (nalgebra's): the first
/// largest |pivot| of the column (none if it is zero), rows swapped (a row swapped with
/// itself is left alone: the same factors), the multipliers times the pivot's reciprocal
/// and the updates of the rows below. With `I` a constant every loop unrolls.
#[inline(always)]
fn eliminate<const N: usize, const I: usize>(a: &mut [[f64; N]; N], swaps: &mut [usize; N]) {
    swaps[I] = I;
    let mut piv = I;
    let mut max = a[I][I].abs();
    for (j, row) in a.iter().enumerate().skip(I + 1) {
        let v = row[I].abs();
        if v > max {
            max = v;
            piv = j;
        }
    }
    let diag = a[piv][I];
    if diag == 0.0 {
        return;
    }
    swaps[I] = piv;
    if piv != I {
        a.swap(I, piv);
    }
    let inv = 1.0 / diag;
    let pivot_row = a[I];
    for row in a.iter_mut().skip(I + 1) {
        let c = row[I] * inv;
        row[I] = c;
        for k in I + 1..N {
            row[k] += -pivot_row[k] * c;
        }
    }
}

/// LU factors, `lu[row][column]`, and the row swapped with row `i` at step `i`.
#[derive(Debug, Clone, Copy, Default)]
pub struct Lu6 {
    lu: [[f64; N6]; N6],
    swaps: [usize; N6],
}

impl Lu6 {
    /// Factor `m`.
    pub fn new(m: &Matrix6<f64>) -> Self {
        let mut lu = Self::default();
        lu.refactor(m);
        lu
    }

    /// Factor `m` in place of these factors (no copy of the factors).
    pub fn refactor(&mut self, m: &Matrix6<f64>) {
        let s = m.as_slice(); // column-major
        let Self { lu: a, swaps } = self;
        for (i, row) in a.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = s[j * N6 + i];
            }
        }
        eliminate::<N6, 0>(a, swaps);
        eliminate::<N6, 1>(a, swaps);
        eliminate::<N6, 2>(a, swaps);
        eliminate::<N6, 3>(a, swaps);
        eliminate::<N6, 4>(a, swaps);
        eliminate::<N6, 5>(a, swaps);
    }

    /// Solve `m·x = b`; `None` if `m` is singular.
    pub fn solve(&self, b: &Vector6<f64>) -> Option<Vector6<f64>> {
        let mut x: [f64; N6] = std::array::from_fn(|i| b[i]);
        for (i, &p) in self.swaps.iter().enumerate() {
            x.swap(i, p);
        }
        let a = &self.lu;
        for i in 0..N6 - 1 {
            let c = x[i];
            for j in i + 1..N6 {
                x[j] += -c * a[j][i];
            }
        }
        for i in (0..N6).rev() {
            if a[i][i] == 0.0 {
                return None;
            }
            let c = x[i] / a[i][i];
            x[i] = c;
            for j in 0..i {
                x[j] += -c * a[j][i];
            }
        }
        Some(Vector6::from_column_slice(&x))
    }
}

/// Test matrix entries: a xorshift sequence from `seed`, uniform mantissas over 24 orders
/// of magnitude (10⁻¹² … 10¹²), and exact zeros when the state is a multiple of
/// `zero_every` — the entries the LU tests compare bit for bit.
#[cfg(test)]
pub(crate) fn values_over_24_decades(mut seed: u64, zero_every: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        let mantissa = (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        let exponent = ((seed >> 3) % 25) as i32 - 12;
        if seed % zero_every == 0 {
            0.0
        } else {
            mantissa * 10f64.powi(exponent)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Lu3` against nalgebra's `LU` on matrices of every pivoting pattern (entries over
    /// 24 orders of magnitude, zeros, singular ones): the same solution bits.
    #[test]
    fn lu3_is_nalgebras_lu_bit_for_bit() {
        let mut next = values_over_24_decades(0x2545_f491_4f6c_dd1d, 11);
        let mut singular = 0;
        for case in 0..20_000 {
            let mut m = Matrix3::from_fn(|_, _| next());
            if case % 97 == 0 {
                m.set_row(2, &(m.row(0) * 2.0)); // singular
            }
            let b = Vector3::new(next(), next(), next());
            let ours = Lu3::new(&m).solve(&b);
            let theirs = m.lu().solve(&b);
            singular += usize::from(theirs.is_none());
            match (ours, theirs) {
                (Some(x), Some(y)) => assert!(
                    x.iter()
                        .zip(y.iter())
                        .all(|(u, v)| u.to_bits() == v.to_bits()),
                    "{m} {b}: {x} against {y}"
                ),
                (None, None) => {}
                _ => panic!("{m}: {ours:?} against {theirs:?}"),
            }
        }
        assert!(singular > 0);
    }

    /// `Lu2` against `Lu3` on [[a, b, 0], [c, d, 0], [0, 0, 1]] (entries over 24 orders of
    /// magnitude, zeros, both pivot orders, singular blocks): the same solution bits, and
    /// singular exactly when `Lu3` finds it singular.
    #[test]
    fn lu2_is_lu3_on_a_locked_theta_bit_for_bit() {
        let mut next = values_over_24_decades(0x9e37_79b9_7f4a_7c15, 7);
        let (mut singular, mut swapped) = (0, 0);
        for case in 0..20_000 {
            let [a, b, mut c, mut d] = [next(), next(), next(), next()];
            if case % 53 == 0 {
                (c, d) = (2.0 * a, 2.0 * b); // singular
            }
            let (r0, r1) = (next(), next());
            let lu = Lu2::new([a, b, c, d]);
            swapped += usize::from(lu.swap);
            let ours = lu.solve(r0, r1);
            let m = Matrix3::new(a, b, 0.0, c, d, 0.0, 0.0, 0.0, 1.0);
            let theirs = Lu3::new(&m).solve(&Vector3::new(r0, r1, 0.0));
            singular += usize::from(theirs.is_none());
            match (ours, theirs) {
                (Some((x0, x1)), Some(y)) => assert!(
                    x0.to_bits() == y.x.to_bits() && x1.to_bits() == y.y.to_bits(),
                    "{m}: ({x0}, {x1}) against {y}"
                ),
                (None, None) => {}
                _ => panic!("{m}: {ours:?} against {theirs:?}"),
            }
        }
        assert!(singular > 0 && swapped > 0);
    }

    /// A deterministic pseudo-random sequence in [−1, 1) (a 64-bit LCG).
    fn numbers(seed: u64) -> impl FnMut() -> f64 {
        let mut s = seed;
        move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    #[test]
    fn lu6_is_nalgebras_lu_bit_for_bit() {
        let mut next = numbers(7);
        let mut solved = 0;
        let mut reused = Lu6::default();
        for case in 0..20_000 {
            // Every pivoting pattern, exact zeros (the locked rotation's rows and columns,
            // sticking contacts' diagonal tangents) and scales from 1 to 1e12.
            let mut m = Matrix6::from_fn(|_, _| next() * 10f64.powi(case % 13));
            if case % 3 == 0 {
                for i in 3..6 {
                    for j in 0..6 {
                        m[(i, j)] = 0.0;
                        m[(j, i)] = 0.0;
                    }
                    m[(i, i)] = 1.0;
                }
            }
            if case % 5 == 0 {
                m[(1, 0)] = 0.0;
                m[(0, 1)] = 0.0;
            }
            let b = Vector6::from_fn(|_, _| next());
            // Factored in place of the last case's factors, as the solver reuses them.
            reused.refactor(&m);
            let ours = reused.solve(&b);
            let theirs = m.lu().solve(&b);
            match (ours, theirs) {
                (Some(x), Some(y)) => {
                    assert!(
                        x.iter().zip(&y).all(|(p, q)| p.to_bits() == q.to_bits()),
                        "case {case}: {x} against {y}"
                    );
                    solved += 1;
                }
                (None, None) => {}
                _ => panic!("case {case}: one is singular, the other not"),
            }
        }
        assert_eq!(solved, 20_000);
    }

    #[test]
    fn a_singular_matrix_has_no_solution() {
        let mut m = Matrix6::identity();
        m[(4, 4)] = 0.0;
        assert!(Lu6::new(&m).solve(&Vector6::repeat(1.0)).is_none());
    }
}

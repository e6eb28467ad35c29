//! LU factors of the 3D model's 6×6 Newton matrix with partial pivoting: nalgebra's `LU`
//! algorithm written out for a fixed size (as the 2D `Lu3`) — the first largest |pivot| of
//! the column, the multipliers times the pivot's reciprocal, the same updates in the same
//! order — so the factors and solutions are nalgebra's bit for bit (unit test), on the
//! stack, at a fraction of the instructions.

use nalgebra::{Matrix6, Vector6};

/// The matrix order.
const N: usize = 6;

/// LU factors, `lu[row][column]`, and the row swapped with row `i` at step `i`.
#[derive(Debug, Clone, Copy)]
pub struct Lu6 {
    lu: [[f64; N]; N],
    swaps: [usize; N],
}

impl Lu6 {
    /// Factor `m`.
    pub fn new(m: &Matrix6<f64>) -> Self {
        let s = m.as_slice(); // column-major
        let mut a = [[0.0; N]; N];
        for (i, row) in a.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = s[j * N + i];
            }
        }
        let mut swaps = [0; N];
        for i in 0..N {
            swaps[i] = i;
            let mut piv = i;
            let mut max = a[i][i].abs();
            for (j, row) in a.iter().enumerate().skip(i + 1) {
                let v = row[i].abs();
                if v > max {
                    max = v;
                    piv = j;
                }
            }
            let diag = a[piv][i];
            if diag == 0.0 {
                continue;
            }
            swaps[i] = piv;
            if piv != i {
                a.swap(i, piv);
            }
            let inv = 1.0 / diag;
            let pivot_row = a[i];
            // Constant trip counts (the compiler unrolls them); only k > i changes.
            for row in a.iter_mut().skip(i + 1) {
                let c = row[i] * inv;
                row[i] = c;
                for k in 0..N {
                    if k > i {
                        row[k] += -pivot_row[k] * c;
                    }
                }
            }
        }
        Self { lu: a, swaps }
    }

    /// Solve `m·x = b`; `None` if `m` is singular.
    pub fn solve(&self, b: &Vector6<f64>) -> Option<Vector6<f64>> {
        let mut x: [f64; N] = std::array::from_fn(|i| b[i]);
        for (i, &p) in self.swaps.iter().enumerate() {
            x.swap(i, p);
        }
        let a = &self.lu;
        for i in 0..N - 1 {
            let c = x[i];
            for j in i + 1..N {
                x[j] += -c * a[j][i];
            }
        }
        for i in (0..N).rev() {
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

#[cfg(test)]
mod tests {
    use super::*;

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
            let ours = Lu6::new(&m).solve(&b);
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

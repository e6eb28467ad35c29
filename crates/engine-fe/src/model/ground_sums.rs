//! The 3D assembly's sums over the elements joining the ground to the body (the single
//! arrangement, or condensed double supports), taken in the ground frame and turned into
//! the body frame once: the force's ([`SpaceForceSums`]), and the tangent's
//! ([`SpaceSums`]), where a sticking element adds its moments of its offset, a slipping
//! one the same and a rank-one correction (an open one is left out by the assembly's
//! loop).

use nalgebra::{Matrix6, Vector2, Vector6};

/// 3×3 matrices as rows of plain scalars.
pub(crate) type M3 = [[f64; 3]; 3];

/// a·b.
#[inline]
fn mul(a: &M3, b: &M3) -> M3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j])
    })
}

/// aᵀ·b.
#[inline]
fn tr_mul(a: &M3, b: &M3) -> M3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| a[0][i] * b[0][j] + a[1][i] * b[1][j] + a[2][i] * b[2][j])
    })
}

/// The ground-frame force sums of one assembly over the supports that touch
/// (`Model::assemble`), with c = R·d each support's offset turned into the ground frame:
/// Σf and Σc × f.
#[derive(Debug, Default, Clone, Copy)]
pub struct SpaceForceSums {
    f: [f64; 3],
    c_cross_f: [f64; 3],
}

impl SpaceForceSums {
    /// Add the force `f` of the support at ground offset `c` = R·d.
    #[inline]
    pub(crate) fn add(&mut self, f: &[f64; 3], c: &[f64; 3]) {
        for (sum, fi) in self.f.iter_mut().zip(f) {
            *sum += fi;
        }
        self.c_cross_f[0] += c[1] * f[2] - c[2] * f[1];
        self.c_cross_f[1] += c[2] * f[0] - c[0] * f[2];
        self.c_cross_f[2] += c[0] * f[1] - c[1] * f[0];
    }

    /// The body's internal force: the force and the body-frame moment Rᵀ·Σc × f.
    pub(crate) fn write(&self, rm: &M3, p: &mut Vector6<f64>) {
        let m = &self.c_cross_f;
        let moment: [f64; 3] =
            std::array::from_fn(|j| rm[0][j] * m[0] + rm[1][j] * m[1] + rm[2][j] * m[2]);
        *p = Vector6::new(
            self.f[0], self.f[1], self.f[2], moment[0], moment[1], moment[2],
        );
    }
}

/// The ground-frame tangent sums of one assembly over the supports that touch: the
/// geometric terms Σf·dᵀ and Σc·f, and ΣD, ΣD·ĉ, Σĉ·D, Σĉ·D·ĉ — the sticking supports
/// (D = diag(a, a, b)) through moments of c, the slipping ones through the same moments
/// and a rank-one correction.
#[derive(Debug, Default, Clone)]
pub struct SpaceSums {
    f_dt: M3,
    c_dot_f: f64,
    d: M3,
    d_c: M3,
    c_d: M3,
    c_d_c: M3,
    /// Σa·c and Σb·c over the sticking supports.
    ac: [f64; 3],
    bc: [f64; 3],
    /// Σa·(c1², c2², c3², c1c3, c2c3) and Σb·(c1², c2², c1c2) over the sticking supports.
    a_moments: [f64; 5],
    b_moments: [f64; 3],
}

impl SpaceSums {
    /// Add the geometric terms of the force `f` of the support at body offset `d`,
    /// ground offset `c` = R·d.
    #[inline]
    pub(crate) fn add_geometric(&mut self, f: &[f64; 3], d: &[f64; 3], c: &[f64; 3]) {
        for (row, fi) in self.f_dt.iter_mut().zip(f) {
            for (x, dj) in row.iter_mut().zip(d) {
                *x += fi * dj;
            }
        }
        self.c_dot_f += c[0] * f[0] + c[1] * f[1] + c[2] * f[2];
    }

    /// Add a sticking support's tangent D = diag(a, a, b) through the moments of c.
    #[inline]
    pub(crate) fn add_sticking(&mut self, a: f64, b: f64, c: &[f64; 3]) {
        self.d[0][0] += a;
        self.d[1][1] += a;
        self.d[2][2] += b;
        for ((ac, bc), ci) in self.ac.iter_mut().zip(&mut self.bc).zip(c) {
            *ac += a * ci;
            *bc += b * ci;
        }
        let (c11, c22, c33) = (c[0] * c[0], c[1] * c[1], c[2] * c[2]);
        let m = &mut self.a_moments;
        m[0] += a * c11;
        m[1] += a * c22;
        m[2] += a * c33;
        m[3] += a * (c[0] * c[2]);
        m[4] += a * (c[1] * c[2]);
        let m = &mut self.b_moments;
        m[0] += b * c11;
        m[1] += b * c22;
        m[2] += b * (c[0] * c[1]);
    }

    /// Add a slipping support's tangent D = diag(ρ, ρ, b) − v·wᵀ (v = (n, 0),
    /// w = (ρ·n, μ·kz), `Tangential::slip_tangent`): its diagonal part as a sticking
    /// support's, and the rank-one part through D·ĉ = diag·ĉ + v·(c × w)ᵀ,
    /// ĉ·D = ĉ·diag − (c × v)·wᵀ, ĉ·D·ĉ = ĉ·diag·ĉ + (c × v)·(c × w)ᵀ.
    #[inline]
    pub(crate) fn add_slipping(
        &mut self,
        rho: f64,
        b: f64,
        n: &Vector2<f64>,
        mu_kz: f64,
        c: &[f64; 3],
    ) {
        self.add_sticking(rho, b, c);
        let v = [n.x, n.y, 0.0];
        let w = [rho * n.x, rho * n.y, mu_kz];
        let cross = |u: &[f64; 3]| {
            [
                c[1] * u[2] - c[2] * u[1],
                c[2] * u[0] - c[0] * u[2],
                c[0] * u[1] - c[1] * u[0],
            ]
        };
        let (cv, cw) = (cross(&v), cross(&w));
        // Rows 0 and 1 only: v = (n, 0).
        for ((d, d_c), vi) in self.d.iter_mut().zip(&mut self.d_c).zip(&v).take(2) {
            for ((x, y), (wj, cwj)) in d.iter_mut().zip(d_c).zip(w.iter().zip(&cw)) {
                *x -= vi * wj;
                *y += vi * cwj;
            }
        }
        for ((c_d, c_d_c), cvi) in self.c_d.iter_mut().zip(&mut self.c_d_c).zip(&cv) {
            for ((x, y), (wj, cwj)) in c_d.iter_mut().zip(c_d_c).zip(w.iter().zip(&cw)) {
                *x -= cvi * wj;
                *y += cvi * cwj;
            }
        }
    }

    /// Fold the sticking supports' moments into ΣD·ĉ, Σĉ·D, Σĉ·D·ĉ: for D = diag(a, a, b),
    /// D·ĉ = [[0, −a·c3, a·c2], [a·c3, 0, −a·c1], [−b·c2, b·c1, 0]], ĉ·D = −(D·ĉ)ᵀ and
    /// ĉ·D·ĉ = [[−a·c3² − b·c2², b·c1c2, a·c1c3], [·, −a·c3² − b·c1², a·c2c3],
    /// [·, ·, −a·(c1² + c2²)]] (symmetric).
    fn fold_sticking(&mut self) {
        let (a, b) = (self.ac, self.bc);
        let d_c = [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-b[1], b[0], 0.0]];
        let [a11, a22, a33, a13, a23] = self.a_moments;
        let [b11, b22, b12] = self.b_moments;
        let c_d_c = [
            [-a33 - b22, b12, a13],
            [b12, -a33 - b11, a23],
            [a13, a23, -(a11 + a22)],
        ];
        for i in 0..3 {
            for j in 0..3 {
                self.d_c[i][j] += d_c[i][j];
                self.c_d[i][j] -= d_c[j][i];
                self.c_d_c[i][j] += c_d_c[i][j];
            }
        }
    }

    /// The tangent of the internal force with respect to (X, W), once
    /// every touching support's tangent is added: with G = −R·d̂ = −ĉ·R,
    /// [[ΣD, −ΣD·ĉ·R], [Rᵀ·Σĉ·D, −Rᵀ·Σĉ·D·ĉ·R + Rᵀ·Σf·dᵀ − (Σc·f)·I]].
    pub(crate) fn write_tangent(&mut self, rm: &M3, k: &mut Matrix6<f64>) {
        self.fold_sticking();
        let k01 = mul(&self.d_c, rm);
        let k10 = tr_mul(rm, &self.c_d);
        let rt_cdc_r = tr_mul(rm, &mul(&self.c_d_c, rm));
        let rt_fdt = tr_mul(rm, &self.f_dt);
        for i in 0..3 {
            for j in 0..3 {
                k[(i, j)] = self.d[i][j];
                k[(i, 3 + j)] = -k01[i][j];
                k[(3 + i, j)] = k10[i][j];
                k[(3 + i, 3 + j)] = rt_fdt[i][j] - rt_cdc_r[i][j];
            }
            k[(3 + i, 3 + i)] -= self.c_dot_f;
        }
    }
}

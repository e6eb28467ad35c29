//! The model's own eigenfrequencies about its static equilibrium under gravity (all
//! supports sticking): the tangent condensed onto the body, with the body's mass matrix
//! diag(M, M, I), and with θ condensed out as well (the paper's model: no rotational
//! inertia). The paper designs the RPEPO for ωX = 10π and ωZ = 20π.

use nalgebra::{Matrix2, Matrix3, SymmetricEigen, Vector3};

use super::model::{Assembly, Model, Plane};
use super::stepper::preload;

/// Eigenfrequencies of a model, rad/s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Modes {
    /// Horizontal(-rocking) mode with θ condensed out (no rotational inertia).
    pub omega_x: f64,
    /// Vertical mode with θ condensed out.
    pub omega_z: f64,
    /// With the rotational inertia: the three modes, ascending (only with rotation).
    pub with_inertia: Option<[f64; 3]>,
}

/// Eigenfrequencies of `model` about its static equilibrium.
pub fn eigenfrequencies(model: &Model<Plane>) -> Result<Modes, String> {
    let mut m = model.clone();
    let (q, mut un) = preload(&mut m)?;
    let mut a = Assembly::new(&m);
    m.assemble(&q, &q, &mut un, &(0.0, 0.0, 0.0), &mut a);
    if a.singular {
        return Err("singular node block".into());
    }
    let k = a.kbb;
    let k = (k + k.transpose()) * 0.5; // sticking tangents are symmetric; remove round-off
    let mass = m.body.mass;
    let k2 = if m.body.rotation {
        let kt = k[(2, 2)];
        Matrix2::new(
            k[(0, 0)] - k[(0, 2)] * k[(2, 0)] / kt,
            k[(0, 1)] - k[(0, 2)] * k[(2, 1)] / kt,
            k[(1, 0)] - k[(1, 2)] * k[(2, 0)] / kt,
            k[(1, 1)] - k[(1, 2)] * k[(2, 1)] / kt,
        )
    } else {
        k.fixed_view::<2, 2>(0, 0).into_owned()
    };
    let e2 = SymmetricEigen::new(k2 / mass);
    // Label each mode by its dominant component.
    let (mut wx, mut wz) = (f64::NAN, f64::NAN);
    for i in 0..2 {
        let w = e2.eigenvalues[i].max(0.0).sqrt();
        if e2.eigenvectors[(0, i)].abs() >= e2.eigenvectors[(1, i)].abs() {
            wx = w;
        } else {
            wz = w;
        }
    }
    let with_inertia = if m.body.rotation && m.body.inertia > 0.0 {
        let h = Vector3::new(mass, mass, m.body.inertia).map(|x| 1.0 / x.sqrt());
        let hm = Matrix3::from_diagonal(&h);
        let e3 = SymmetricEigen::new(hm * k * hm);
        let mut w: Vec<f64> = e3.eigenvalues.iter().map(|l| l.max(0.0).sqrt()).collect();
        w.sort_by(f64::total_cmp);
        Some([w[0], w[1], w[2]])
    } else {
        None
    };
    Ok(Modes {
        omega_x: wx,
        omega_z: wz,
        with_inertia,
    })
}

//! The rigid body the 3D model is built from: its mass, inertia tensor and support
//! points, as the PEPO (a translating mass on one contact), a block on an nx × ny grid of
//! supports, or the plane rocking body extended to a symmetric two-row grid.

use nalgebra::{Matrix3, Vector3};

use crate::model::{Body, Model, Space};
use rockslide_core::case::{Contact, DoubleContact, Oscillator, RockingBody};

/// A rigid body on supports, as the 3D model is built from it.
#[derive(Debug, Clone, PartialEq)]
pub struct SpaceBody {
    /// Mass, kg.
    pub mass: f64,
    /// Gravity, m/s² (along −z).
    pub gravity: f64,
    /// Inertia tensor about the centre of mass in the body frame (ground axes at rest),
    /// kg·m² (unused when the rotation is locked).
    pub inertia: Matrix3<f64>,
    /// Whether the body rotates (false: the PEPO, a translating mass).
    pub rotation: bool,
    /// Support points in the body frame, relative to the centre of mass, m.
    pub supports: Vec<Vector3<f64>>,
    /// Each support as one element (kx is the tangential stiffness in both directions).
    pub contact: Contact,
    /// Each support as two elements in series, if so.
    pub double: Option<DoubleContact>,
    /// Horizontal viscous damping relative to the ground (both directions), N·s/m.
    pub damping: f64,
}

/// A rigid block on an nx × ny grid of supports under its base (the RPEPO extended).
#[derive(Debug, Clone, PartialEq)]
pub struct BlockGrid {
    /// Mass, kg.
    pub mass: f64,
    /// Gravity, m/s².
    pub gravity: f64,
    /// Height of the centre of mass above the base centre O, m.
    pub cm_height: f64,
    /// Half-length of the base along x, m.
    pub half_length: f64,
    /// Half-width of the base along y, m.
    pub half_width: f64,
    /// Supports along x (≥ 1).
    pub nx: usize,
    /// Supports along y (≥ 1).
    pub ny: usize,
    /// Inertia tensor about the centre of mass, kg·m².
    pub inertia: Matrix3<f64>,
    /// Single element per support.
    pub contact: Contact,
    /// Double arrangement, if any.
    pub double: Option<DoubleContact>,
}

/// Equally spaced abscissae from −half to +half (0 for one), the 2D model's formula.
fn positions(n: usize, half: f64) -> impl Iterator<Item = f64> {
    (0..n).map(move |i| {
        if n == 1 {
            0.0
        } else {
            -half + 2.0 * half * i as f64 / (n - 1) as f64
        }
    })
}

impl SpaceBody {
    /// The PEPO as a 3D oscillator: a translating mass on one contact.
    pub fn oscillator(o: &Oscillator, double: bool) -> Self {
        Self {
            mass: o.mass,
            gravity: o.gravity,
            inertia: Matrix3::zeros(),
            rotation: false,
            supports: vec![Vector3::zeros()],
            contact: o.contact,
            double: if double { o.double } else { None },
            damping: o.damping(),
        }
    }

    /// A block on a grid of supports (x fastest, then y).
    pub fn block(g: &BlockGrid, double: bool) -> Self {
        let mut supports = Vec::with_capacity(g.nx * g.ny);
        for y in positions(g.ny, g.half_width) {
            for x in positions(g.nx, g.half_length) {
                supports.push(Vector3::new(x, y, -g.cm_height));
            }
        }
        Self {
            mass: g.mass,
            gravity: g.gravity,
            inertia: g.inertia,
            rotation: true,
            supports,
            contact: g.contact,
            double: if double { g.double } else { None },
            damping: 0.0,
        }
    }

    /// The 2D rocking body in 3D: a symmetric two-row grid, each 2D support split into two
    /// at y = ±`half_width` carrying half its stiffnesses, and an isotropic inertia
    /// `inertia`. In its plane it is the 2D structure (the same sums of forces, each half
    /// element at half the force); out of plane it stands (a single row of supports
    /// would be a knife edge, free to tip sideways).
    pub fn from_rocking(r: &RockingBody, inertia: f64, half_width: f64, double: bool) -> Self {
        let half = |c: Contact| Contact {
            kx: 0.5 * c.kx,
            kz: 0.5 * c.kz,
            mu: c.mu,
        };
        Self::block(
            &BlockGrid {
                mass: r.mass,
                gravity: r.gravity,
                cm_height: r.cm_height,
                half_length: r.half_width,
                half_width,
                nx: r.supports,
                ny: 2,
                inertia: Matrix3::identity() * inertia,
                contact: half(r.contact),
                double: r.double.map(|d| DoubleContact {
                    lower: half(d.lower),
                    upper: half(d.upper),
                }),
            },
            double,
        )
    }
}

impl Model<Space> {
    /// The 3D model of `b`: one element per support, or two through a node.
    pub fn space(b: &SpaceBody) -> Self {
        let body = Body {
            mass: b.mass,
            gravity: b.gravity,
            inertia: b.inertia,
            rotation: b.rotation,
            offsets: b.supports.clone(),
            damping: b.damping,
        };
        Self::new(body, &b.contact, b.double.as_ref(), ())
    }
}

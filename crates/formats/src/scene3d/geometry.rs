//! The scene's geometry per model: the body, its supports (a grid in a 3D scene) and
//! the force-arrow scale, in metres.

use rockslide_core::case::{Model, Scene};
use rockslide_core::trace::Trace;

/// The geometry of a scene that has one, in metres, with the static pose of its body.
#[derive(Debug, Clone, PartialEq)]
pub struct Geometry {
    /// `rocking-body`, `rigid-block` or `oscillator` (a 3D scene's mass, drawn as a cube).
    pub kind: &'static str,
    /// Height of the centre of mass above the base when the body rests on the ground, m.
    pub cm_height: f64,
    /// Half-width of the base along x, m.
    pub half_width: f64,
    /// Half of the drawn body's height, m (the body is drawn centred on its centre of mass).
    pub half_height: f64,
    /// Half-depth of the base along y in a 3D scene, m (`None`: a planar scene, drawn
    /// `half_width` deep).
    pub half_depth: Option<f64>,
    /// Support positions (x, y) relative to the base centre O, m (empty: a rigid base).
    pub supports: Vec<[f64; 2]>,
    /// Weight M·g (or M where g = 0), N: sets the force-arrow scale.
    pub weight: f64,
}

fn weight(m: f64, g: f64) -> f64 {
    if g > 0.0 { m * g } else { m }
}

impl Geometry {
    /// The geometry of a planar model, or `None` for a scene without one
    /// (`Model::has_geometry`).
    pub fn of(model: &Model) -> Option<Self> {
        if !model.has_geometry() {
            return None;
        }
        match model {
            Model::Oscillator(_) => None,
            Model::RockingBody(r) => Some(Self {
                kind: "rocking-body",
                cm_height: r.cm_height,
                half_width: r.half_width,
                half_height: r.cm_height,
                half_depth: None,
                supports: r.support_positions().iter().map(|&x| [x, 0.0]).collect(),
                weight: weight(r.mass, r.gravity),
            }),
            Model::RigidBlock(b) => Some(Self {
                kind: "rigid-block",
                cm_height: b.half_height,
                half_width: b.half_width,
                half_height: b.half_height,
                half_depth: None,
                supports: Vec::new(),
                weight: weight(b.mass, b.gravity),
            }),
        }
    }

    /// The geometry of a scene: [`Geometry::of`] for a planar one; for a 3D one the body
    /// with its depth and its grid of supports (`supports` × `support_rows`, rows from −d
    /// to +d), and the oscillator as a cube of half-size 5 × the largest resultant
    /// displacement of `traces` (`rel_disp`, `rel_disp_y`; 1 m when none moves), resting
    /// on its one contact.
    pub fn of_scene(scene: &Scene, traces: &[&Trace]) -> Option<Self> {
        let Some(spatial) = scene.spatial() else {
            return Self::of(&scene.model);
        };
        let half_depth = spatial.depth.map(|d| d.half_depth);
        let rows = spatial.depth.map_or(1, |d| d.support_rows.max(1));
        match &scene.model {
            Model::Oscillator(o) => {
                let s = oscillator_half_size(traces);
                Some(Self {
                    kind: "oscillator",
                    cm_height: s,
                    half_width: s,
                    half_height: s,
                    half_depth: Some(s),
                    supports: vec![[0.0, 0.0]],
                    weight: weight(o.mass, o.gravity),
                })
            }
            Model::RockingBody(_) | Model::RigidBlock(_) => {
                let mut g = Self::of(&scene.model)?;
                let d = half_depth.unwrap_or(g.half_width);
                g.half_depth = Some(d);
                g.supports = grid(&g.supports, d, rows);
                Some(g)
            }
        }
    }

    /// Whether the scene is bidirectional (drawn with its depth, moving in y too).
    pub fn is_spatial(&self) -> bool {
        self.half_depth.is_some()
    }

    /// Depth of the drawn body along y, m.
    pub fn depth(&self) -> f64 {
        self.half_depth.map_or(self.half_width, |d| 2.0 * d)
    }

    /// Distance between the lanes of successive runs along y, m.
    pub fn lane_spacing(&self) -> f64 {
        3.0 * self.depth()
    }

    /// Length of a force arrow per newton, m/N: the weight is drawn as long as the
    /// centre of mass is high.
    pub fn arrow_scale(&self) -> f64 {
        self.cm_height / self.weight
    }
}

/// The planar supports `row` (x, 0) repeated on `rows` rows from y = −d to +d (one row: y = 0).
fn grid(row: &[[f64; 2]], d: f64, rows: usize) -> Vec<[f64; 2]> {
    let ys: Vec<f64> = if rows <= 1 {
        vec![0.0]
    } else {
        (0..rows)
            .map(|j| -d + 2.0 * d * j as f64 / (rows - 1) as f64)
            .collect()
    };
    ys.iter()
        .flat_map(|&y| row.iter().map(move |p| [p[0], y]))
        .collect()
}

/// Half-size of the cube drawn for a 3D oscillator: 5 × the largest finite resultant
/// relative displacement of the traces, 1 m when none moves.
fn oscillator_half_size(traces: &[&Trace]) -> f64 {
    let peak = traces
        .iter()
        .filter_map(|t| {
            let x = t.column("rel_disp")?;
            let y = t.column("rel_disp_y");
            Some(
                (0..x.len())
                    .map(|i| x[i].hypot(y.map_or(0.0, |y| y[i])))
                    .filter(|r| r.is_finite())
                    .fold(0.0, f64::max),
            )
        })
        .fold(0.0, f64::max);
    if peak > 0.0 { 5.0 * peak } else { 1.0 }
}

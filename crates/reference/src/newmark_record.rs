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

pub use crate::block_record::{BlockRecord as NewmarkRun, Slide, Sliding};

/// Run the rigid block under `acc` (m/s², samples every `dt` s, linear in between, then
/// held at zero for `tail` extra seconds so a block still sliding at the record's end comes
/// to rest), yield acceleration `ky` (m/s², ≥ 0): the exact solution for that
/// piecewise-linear input ([`crate::block_record`]), or why it cannot be computed.
pub fn rigid_block(
    dt: f64,
    acc: &[f64],
    ky: f64,
    sliding: Sliding,
    tail: f64,
) -> Result<NewmarkRun, String> {
    NewmarkRun::solve(dt, acc, ky, sliding, tail)
}

/// First onset and last stop of a run, s; `None` when it never slides.
pub type Span = Option<(f64, f64)>;

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
    /// Total distance slid (normal, inverse), m.
    pub total_slid: (f64, f64),
    /// First onset and last stop (normal, inverse), s; `None` when it never slides.
    pub span: (Span, Span),
}

/// First onset and last stop of a run, s.
fn slide_span(run: &NewmarkRun) -> Span {
    Some((run.slides.first()?.start, run.slides.last()?.end))
}

impl NewmarkSummary {
    /// Run a record both ways.
    pub fn of(dt: f64, acc: &[f64], ky: f64, sliding: Sliding, tail: f64) -> Result<Self, String> {
        let inverted: Vec<f64> = acc.iter().map(|a| -a).collect();
        let n = rigid_block(dt, acc, ky, sliding, tail)?;
        let i = rigid_block(dt, &inverted, ky, sliding, tail)?;
        Ok(Self {
            ky,
            normal: n.residual(),
            inverse: i.residual(),
            episodes: (n.episodes(), i.episodes()),
            total_slid: (n.total_slid(), i.total_slid()),
            span: (slide_span(&n), slide_span(&i)),
        })
    }
    /// Mean of the two polarities' |displacement|, m (SLAMMER's "average").
    pub fn mean(&self) -> f64 {
        (self.normal.abs() + self.inverse.abs()) / 2.0
    }
    /// Table in SLAMMER's units: ky in g, displacements in cm (and m), with the slides'
    /// count, total distance, first onset and last stop.
    pub fn table(&self, label: &str) -> String {
        let cm = |m: f64| m * 100.0;
        let ky = self.ky / STANDARD_GRAVITY;
        let span = |s: Option<(f64, f64)>| {
            s.map_or("– | –".to_string(), |(a, b)| format!("{a:.4} | {b:.4}"))
        };
        let mut t = String::from(
            "| record | ky [g] | polarity | displacement [cm] | displacement [m] | slip episodes | total slid [cm] | first onset [s] | last stop [s] |\n\
             |---|---:|---|---:|---:|---:|---:|---:|---:|\n",
        );
        let rows = [
            (
                "normal",
                self.normal,
                self.episodes.0,
                self.total_slid.0,
                self.span.0,
            ),
            (
                "inverse",
                self.inverse,
                self.episodes.1,
                self.total_slid.1,
                self.span.1,
            ),
        ];
        for (pol, d, n, total, s) in rows {
            t.push_str(&format!(
                "| {label} | {ky:.4} | {pol} | {:.3} | {d:.5} | {n} | {:.3} | {} |\n",
                cm(d),
                cm(total),
                span(s)
            ));
        }
        t.push_str(&format!(
            "| {label} | {ky:.4} | mean | {:.3} | {:.5} | | | | |\n",
            cm(self.mean()),
            self.mean()
        ));
        t
    }
}

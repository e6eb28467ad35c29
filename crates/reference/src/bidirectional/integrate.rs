//! The integrator shared by the plan-motion references: one event loop ([`march`]) over a
//! grid with a node at every kink of the drive, an event located inside a step by
//! bisection on the event function of the step's length (a Runge–Kutta step of length τ
//! is a smooth function of τ), so that the state is advanced exactly to the event and the
//! phase changed there; classical RK4 steps ([`rk4`]) for the oscillator.

/// The integrated state at one instant: time, slide (or displacement) and velocity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time, s.
    pub t: f64,
    /// Position relative to the ground (block: slide; oscillator: the mass), m.
    pub pos: [f64; 2],
    /// Velocity relative to the ground, m/s.
    pub vel: [f64; 2],
    /// Acceleration relative to the ground, m/s² (for Hermite interpolation).
    pub acc: [f64; 2],
    /// Plastic slip p (oscillator; the block's slide again), m.
    pub slip: [f64; 2],
    /// Slip rate ṗ, m/s.
    pub slip_rate: [f64; 2],
}

/// Rotate a plane vector by `angle` (rad, from +x toward +y).
pub fn rotate(v: [f64; 2], angle: f64) -> [f64; 2] {
    let (s, c) = angle.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

/// One classical RK4 step of length `h` from (t, y) for y' = f(t, y), N components.
pub fn rk4<const N: usize>(
    f: &impl Fn(f64, &[f64; N]) -> [f64; N],
    t: f64,
    y: &[f64; N],
    h: f64,
) -> [f64; N] {
    let add = |a: &[f64; N], k: &[f64; N], c: f64| {
        let mut r = *a;
        for i in 0..N {
            r[i] += c * k[i];
        }
        r
    };
    let k1 = f(t, y);
    let k2 = f(t + 0.5 * h, &add(y, &k1, 0.5 * h));
    let k3 = f(t + 0.5 * h, &add(y, &k2, 0.5 * h));
    let k4 = f(t + h, &add(y, &k3, h));
    let mut r = *y;
    for i in 0..N {
        r[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    r
}

/// The first τ in (0, h] where `g(τ)` becomes ≤ 0, given g(0) > 0 and g(h) ≤ 0: the
/// upper end of [`bracket`].
pub fn locate(h: f64, g: impl Fn(f64) -> f64) -> f64 {
    bracket(h, g).1
}

/// The event of `g` in (0, h] as two adjacent floats (a, b): g(a) > 0 (or a = 0), g(b) ≤ 0,
/// given g(h) ≤ 0; bisection until the bracket cannot shrink, the one rule of every event
/// locator of the references ([`crate::root::BISECTION_LIMIT`]).
pub fn bracket(h: f64, g: impl Fn(f64) -> f64) -> (f64, f64) {
    let (mut a, mut b) = (0.0_f64, h);
    for _ in 0..crate::root::BISECTION_LIMIT {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        if g(m) > 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    (a, b)
}

/// Most events in one grid step before a reference declares it is not progressing.
const EVENTS_PER_STEP: usize = 64;

/// The event loop of the references: from (0, `y`) in `phase`, for each grid node call
/// `advance(t, node, y, phase)` — which moves `t` to the node or to the first event before
/// it and returns the phase after — until the node is reached; an error when a step
/// needs more than [`EVENTS_PER_STEP`] calls or the state stops being finite.
pub fn march<const N: usize, P: Copy>(
    nodes: &[f64],
    y: &mut [f64; N],
    phase: &mut P,
    mut advance: impl FnMut(&mut f64, f64, &mut [f64; N], P) -> Result<P, String>,
) -> Result<(), String> {
    let mut t = nodes.first().copied().unwrap_or(0.0);
    for &node in nodes.iter().skip(1) {
        let mut events = 0;
        while t < node {
            events += 1;
            if events > EVENTS_PER_STEP {
                return Err(format!("no progress at t = {t:.9} s"));
            }
            *phase = advance(&mut t, node, y, *phase)?;
            if !y.iter().all(|x| x.is_finite()) {
                return Err(format!("the state is not finite at t = {t:.6} s"));
            }
        }
    }
    Ok(())
}

/// The grid nodes over [0, end]: every kink, and pieces between them cut into equal steps
/// of at most `h`.
pub fn grid(kinks: &[f64], end: f64, h: f64) -> Vec<f64> {
    let mut nodes = vec![0.0];
    let mut from = 0.0;
    for &k in kinks.iter().chain(std::iter::once(&end)) {
        let n = ((k - from) / h).ceil().max(1.0) as usize;
        for i in 1..=n {
            nodes.push(if i == n {
                k
            } else {
                from + (k - from) * i as f64 / n as f64
            });
        }
        from = k;
    }
    nodes
}

/// Position, velocity and slip at `t` by cubic Hermite interpolation of the samples
/// (position from the velocities, velocity from the accelerations, slip from the slip
/// rates): O(h⁴) and O(h³) between nodes.
pub fn hermite(samples: &[Sample], t: f64) -> ([f64; 2], [f64; 2], [f64; 2]) {
    hermite_at(samples, samples.partition_point(|s| s.t <= t), t)
}

/// [`hermite`] with the samples' partition point at `t` (the first sample after `t`)
/// already found, e.g. by a [`crate::cursor::Cursor`].
pub(crate) fn hermite_at(samples: &[Sample], i: usize, t: f64) -> ([f64; 2], [f64; 2], [f64; 2]) {
    if i == 0 || i == samples.len() {
        let s = samples[i.saturating_sub(1)];
        return (s.pos, s.vel, s.slip);
    }
    let (a, b) = (samples[i - 1], samples[i]);
    let h = b.t - a.t;
    if h <= 0.0 {
        return (b.pos, b.vel, b.slip);
    }
    let x = (t - a.t) / h;
    let w = [
        (1.0 + 2.0 * x) * (1.0 - x) * (1.0 - x),
        h * x * (1.0 - x) * (1.0 - x),
        x * x * (3.0 - 2.0 * x),
        h * x * x * (x - 1.0),
    ];
    let cubic = |p0: [f64; 2], d0: [f64; 2], p1: [f64; 2], d1: [f64; 2]| {
        [0, 1].map(|k| w[0] * p0[k] + w[1] * d0[k] + w[2] * p1[k] + w[3] * d1[k])
    };
    (
        cubic(a.pos, a.vel, b.pos, b.vel),
        cubic(a.vel, a.acc, b.vel, b.acc),
        cubic(a.slip, a.slip_rate, b.slip, b.slip_rate),
    )
}

/// |v|.
pub fn norm(v: [f64; 2]) -> f64 {
    v[0].hypot(v[1])
}

/// a·b.
pub fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

//! An independent adaptive integrator for the vertical references' tests: Dormand–Prince
//! 5(4) with step-size control, stepping each grid interval of the piecewise-linear inputs
//! separately (the inputs have kinks only at grid points), and locating the switching
//! events (stick/slip, lift-off, landing) by bisecting the step size until the event is
//! bracketed within 1e-14 s. It shares no code with the references: only the inputs.
//! Its Dormand–Prince step (`step`) also serves the record references' tests.

/// State of four components.
pub type Y = [f64; 4];

/// Right-hand side: time within the interval, state → derivative.
pub trait Rhs: Fn(f64, &Y) -> Y {}
impl<F: Fn(f64, &Y) -> Y> Rhs for F {}

const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// The fifth-order weights are the last stage's row (first same as last).
const B5: [f64; 7] = [A[6][0], A[6][1], A[6][2], A[6][3], A[6][4], A[6][5], 0.0];
const B4: [f64; 7] = [
    5179.0 / 57600.0,
    0.0,
    7571.0 / 16695.0,
    393.0 / 640.0,
    -92097.0 / 339200.0,
    187.0 / 2100.0,
    1.0 / 40.0,
];

/// One Dormand–Prince step of y' = f(t, y) for any number of components: the fifth-order
/// result and its error estimate (max norm, scaled per component by `scale`).
pub fn step<const N: usize>(
    f: &impl Fn(f64, &[f64; N]) -> [f64; N],
    t: f64,
    y: &[f64; N],
    h: f64,
    scale: &[f64; N],
) -> ([f64; N], f64) {
    let mut k = [[0.0; N]; 7];
    for s in 0..7 {
        let mut ys = *y;
        for (j, kj) in k.iter().enumerate().take(s) {
            for i in 0..N {
                ys[i] += h * A[s][j] * kj[i];
            }
        }
        k[s] = f(t + C[s] * h, &ys);
    }
    let (mut y5, mut err) = (*y, 0.0_f64);
    for i in 0..N {
        let (mut d5, mut d4) = (0.0, 0.0);
        for s in 0..7 {
            d5 += B5[s] * k[s][i];
            d4 += B4[s] * k[s][i];
        }
        y5[i] += h * d5;
        err = err.max((h * (d5 - d4)).abs() / scale[i]);
    }
    (y5, err)
}

/// Integrate from `t0` to `t1` under `f` with error tolerance 1 (per `scale`, an absolute
/// tolerance per component), stopping early at the first event: `event(t, y) > 0`.
/// Returns the time reached and the state; `true` if it stopped at an event.
pub fn advance(
    f: &impl Rhs,
    event: &impl Fn(f64, &Y) -> f64,
    t0: f64,
    t1: f64,
    y0: Y,
    scale: &Y,
) -> (f64, Y, bool) {
    let (mut t, mut y) = (t0, y0);
    let mut h = t1 - t0;
    let mut guard = 0;
    while t < t1 {
        guard += 1;
        assert!(guard < 1_000_000, "integrator stuck at t = {t}");
        h = h.min(t1 - t);
        let (y_new, err) = step(f, t, &y, h, scale);
        if err > 1.0 && h > 1e-12 {
            h *= (0.9 * err.powf(-0.2)).max(0.1);
            continue;
        }
        let t_new = if h == t1 - t { t1 } else { t + h };
        if event(t_new, &y_new) > 0.0 {
            // bisect the step size: the event lies in (0, h]
            let (mut lo, mut hi) = (0.0, h);
            while hi - lo > 1e-14 {
                let mid = 0.5 * (lo + hi);
                let (ym, _) = step(f, t, &y, mid, scale);
                if event(t + mid, &ym) > 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let (ye, _) = step(f, t, &y, hi, scale);
            return (t + hi, ye, true);
        }
        t = t_new;
        y = y_new;
        h *= (0.9 * err.max(1e-10).powf(-0.2)).min(5.0);
    }
    (t, y, false)
}

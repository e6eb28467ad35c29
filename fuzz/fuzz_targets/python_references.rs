//! The numbers a Python script passes to the package's reference functions
//! (`rockslide.epo_record`, `rigid_block`, `housner`, `plan_block`, `plan_oscillator`),
//! through the same Rust entry points (`rockslide_reference::plain`, `newmark_record`) and
//! the same sampling: any numbers and arrays give an answer or a reason, never a panic, an
//! abort on an allocation or a hang.
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use rockslide_reference::newmark_record::{Sliding, rigid_block};
use rockslide_reference::{ExactSolution, plain, sample};

#[derive(Debug, Arbitrary)]
enum Call {
    EpoRecord {
        dt: f64,
        acceleration: Vec<f64>,
        mass: f64,
        stiffness: f64,
        mu: f64,
        gravity: f64,
        duration: Option<f64>,
    },
    RigidBlock {
        dt: f64,
        acceleration: Vec<f64>,
        ky: f64,
        one_way: bool,
        tail: f64,
    },
    Housner {
        half_width: f64,
        half_height: f64,
        amplitude: f64,
        omega: f64,
        duration: f64,
        cycles: f64,
        gravity: f64,
        initial_tilt: f64,
        samples: u32,
    },
    PlanBlock {
        dt: f64,
        x: Vec<f64>,
        y: Vec<f64>,
        mu: f64,
        gravity: f64,
        duration: Option<f64>,
        step: f64,
    },
    PlanOscillator {
        dt: f64,
        x: Vec<f64>,
        y: Vec<f64>,
        mass: f64,
        stiffness: f64,
        mu: f64,
        duration: Option<f64>,
        step: f64,
    },
}

#[derive(Debug, Arbitrary)]
struct Input {
    call: Call,
    times: Option<Vec<f64>>,
}

/// Sample as the package does: at the given times, or uniformly at about `dt`.
fn sampled(solution: &dyn ExactSolution, times: Option<Vec<f64>>, end: f64, dt: f64) {
    let Ok(n) = plain::intervals(end, dt) else {
        return;
    };
    if let Ok(times) = plain::times(times, end, n) {
        let _ = sample(solution, &times);
    }
}

fuzz_target!(|input: Input| {
    let times = input.times;
    match input.call {
        Call::EpoRecord { dt, acceleration, mass, stiffness, mu, gravity, duration } => {
            let Ok(osc) = plain::oscillator(mass, stiffness, mu, gravity) else {
                return;
            };
            if let Ok((s, end)) = plain::epo_record(dt, acceleration, &osc, duration) {
                sampled(&s, times, end, dt);
            }
        }
        Call::RigidBlock { dt, acceleration, ky, one_way, tail } => {
            let sliding = if one_way { Sliding::OneWay } else { Sliding::TwoWay };
            let _ = rigid_block(dt, &acceleration, ky, sliding, tail);
        }
        Call::Housner {
            half_width,
            half_height,
            amplitude,
            omega,
            duration,
            cycles,
            gravity,
            initial_tilt,
            samples,
        } => {
            let solved = plain::housner(
                half_width,
                half_height,
                amplitude,
                omega,
                duration,
                cycles,
                gravity,
                initial_tilt,
            );
            if let Ok(s) = solved
                && let Ok(t) = plain::times(times, duration, samples as usize)
            {
                let _ = sample(&s, &t);
            }
        }
        Call::PlanBlock { dt, x, y, mu, gravity, duration, step } => {
            if let Ok((s, end)) = plain::plan_block(dt, x, y, mu, gravity, duration, step) {
                sampled(&s, times, end, dt);
            }
        }
        Call::PlanOscillator { dt, x, y, mass, stiffness, mu, duration, step } => {
            let Ok(osc) = plain::oscillator(mass, stiffness, mu, 9.80665) else {
                return;
            };
            if let Ok((s, end)) = plain::plan_oscillator(dt, x, y, &osc, duration, step) {
                sampled(&s, times, end, dt);
            }
        }
    }
});

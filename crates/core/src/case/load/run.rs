//! The case's `name` (a slug naming its output folder) and `[run]`: duration, step and
//! output step, with the number of steps bounded before any work. A duration that is not
//! a multiple of the step ends at the first step after it, for every trace and the exact
//! reference alike ([`end_instant`]).

use std::path::Path;

use super::super::scene::RunSettings;
use super::validator::{Rule, Validator};

impl Validator<'_> {
    /// The case's name, which names its output folder: an explicit `name` must be a
    /// [`slug`](crate::case::slug); without one, the file's stem turned into a slug.
    pub(super) fn name(&mut self, explicit: Option<&str>, path: &Path) -> String {
        match explicit {
            Some(n) => {
                if let Err(why) = crate::case::slug::check(n) {
                    self.fail("name", why);
                }
                n.to_string()
            }
            None => crate::case::slug::from_stem(path),
        }
    }

    pub(super) fn run(&mut self, duration: f64, dt: f64, output_dt: Option<f64>) -> RunSettings {
        self.number("run.duration", Some(duration), Rule::positive("s"));
        self.number("run.dt", Some(dt), Rule::positive("s"));
        if dt > duration {
            self.fail(
                "run.dt",
                format!("is {dt} s, longer than run.duration ({duration} s)"),
            );
        }
        self.steps("run.dt", duration, dt, output_dt);
        if let Some(out) = output_dt {
            self.number("run.output_dt", Some(out), Rule::positive("s"));
            if out < dt || out > duration {
                self.fail(
                    "run.output_dt",
                    format!("is {out} s, but must lie between run.dt ({dt} s) and run.duration ({duration} s)"),
                );
            }
        }
        RunSettings {
            duration: end_instant(duration, dt),
            asked_duration: duration,
            dt,
            output_dt,
        }
    }

    /// Steps of `dt` covering `duration` within [`limits::max_steps`](crate::case::limits), or
    /// with an output step, the rows it keeps within it and the steps within
    /// [`limits::STREAMED_STEPS_FACTOR`](crate::case::limits) times it (a streamed run).
    pub(super) fn steps(&mut self, field: &str, duration: f64, dt: f64, output_dt: Option<f64>) {
        let valid = |x: f64| x > 0.0 && x.is_finite();
        let output_dt = output_dt.filter(|&o| valid(o) && o > dt);
        if valid(duration)
            && valid(dt)
            && let Err(why) = crate::case::limits::check_kept_steps(duration, dt, output_dt)
        {
            self.fail(field, why);
        }
    }
}

/// The instant a run of `duration` at steps of `dt` ends, where every trace and the exact
/// reference are read: `duration` itself when it is a multiple of `dt` (to 1e-9 of a
/// step, as the engines count their steps), else the first step after it, n·dt with
/// n = ⌈duration/dt⌉ — what every engine at `dt` runs to. Invalid values pass unchanged
/// (they are refused on their own).
pub(crate) fn end_instant(duration: f64, dt: f64) -> f64 {
    if !(duration.is_finite() && dt.is_finite() && dt > 0.0 && duration >= dt) {
        return duration;
    }
    let ratio = duration / dt;
    if (ratio - ratio.round()).abs() <= 1e-9 {
        duration
    } else {
        (ratio - 1e-9).ceil() * dt
    }
}

#[cfg(test)]
mod tests {
    use super::end_instant;

    #[test]
    fn a_duration_off_the_step_ends_at_the_first_step_after_it() {
        assert_eq!(end_instant(1.0, 0.001).to_bits(), 1.0_f64.to_bits());
        assert_eq!(end_instant(0.6, 0.2).to_bits(), 0.6_f64.to_bits());
        assert_eq!(end_instant(0.2005, 0.001), 201.0 * 0.001);
        assert_eq!(end_instant(1.05, 0.1), 11.0 * 0.1);
        assert!(end_instant(f64::NAN, 0.1).is_nan());
    }
}

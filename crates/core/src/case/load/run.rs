//! The case's `name` (a slug naming its output folder) and `[run]`: duration, step and
//! output step, with the number of steps bounded before any work.

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
            duration,
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

//! Opt-in timing of a command's stages (`rockslide --timings`): each stage of each case
//! (engines, reference, analysis, trace files, pages) and each whole stage (stability
//! map, sweeps) records its wall time and the process's CPU time over it. Off by default:
//! nothing is recorded and nothing is written, so the default outputs stay byte-identical
//! whatever the machine's speed.
//!
//! Stages run in parallel on every core, so the CPU column of a span counts every thread
//! of the process while it ran: it is the span's own CPU time only when the command runs
//! on one worker (`RAYON_NUM_THREADS=1`, where every stage runs after the other).

use std::sync::Mutex;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use serde::Serialize;

/// One timed span.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Span {
    /// Stage: `stability`, `sweep`, `engines`, `reference`, `analysis`, `traces`, `pages`,
    /// `summary`, `total`.
    pub stage: &'static str,
    /// What it timed: a case name, or `all`.
    pub subject: String,
    /// Start, s since timing was enabled.
    pub start: f64,
    /// Wall time, s.
    pub wall: f64,
    /// CPU time of the whole process (user + system) while the span ran, s.
    pub cpu: f64,
}

static ENABLED: AtomicBool = AtomicBool::new(false);
static EPOCH: OnceLock<Instant> = OnceLock::new();
static SPANS: Mutex<Vec<Span>> = Mutex::new(Vec::new());

/// Start recording spans (the clock starts now).
pub fn enable() {
    EPOCH.get_or_init(Instant::now);
    ENABLED.store(true, Ordering::SeqCst);
}

/// Whether spans are being recorded.
pub fn enabled() -> bool {
    ENABLED.load(Ordering::Relaxed)
}

/// Run `f`, recording its wall and CPU time as `stage` of `subject` when timing is on.
pub fn time<T>(stage: &'static str, subject: &str, f: impl FnOnce() -> T) -> T {
    if !enabled() {
        return f();
    }
    let epoch = *EPOCH.get_or_init(Instant::now);
    let (start, cpu0) = (Instant::now(), process_cpu_seconds());
    let out = f();
    let span = Span {
        stage,
        subject: subject.to_string(),
        start: start.duration_since(epoch).as_secs_f64(),
        wall: start.elapsed().as_secs_f64(),
        cpu: process_cpu_seconds() - cpu0,
    };
    SPANS.lock().unwrap_or_else(|e| e.into_inner()).push(span);
    out
}

/// The spans recorded so far, in start order (and emptied).
pub fn take() -> Vec<Span> {
    let mut spans = std::mem::take(&mut *SPANS.lock().unwrap_or_else(|e| e.into_inner()));
    spans.sort_by(|a, b| a.start.total_cmp(&b.start));
    spans
}

/// CPU time of the whole process so far, user + system, s (NaN where unknown).
pub fn process_cpu_seconds() -> f64 {
    #[cfg(unix)]
    {
        // SAFETY: getrusage fills the zeroed struct it is given and reads nothing else.
        let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
        if unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut usage) } == 0 {
            let seconds = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
            return seconds(usage.ru_utime) + seconds(usage.ru_stime);
        }
    }
    f64::NAN
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_span_is_recorded_only_when_timing_is_on_and_counts_the_cpu_it_burns() {
        assert_eq!(time("engines", "off", || 7), 7);
        assert!(SPANS.lock().unwrap().iter().all(|s| s.subject != "off"));
        enable();
        let spin = || {
            let t = Instant::now();
            let mut x = 0u64;
            while t.elapsed().as_secs_f64() < 0.05 {
                x = std::hint::black_box(x.wrapping_add(1));
            }
            x
        };
        time("engines", "on", spin);
        let spans = take();
        let span = spans.iter().find(|s| s.subject == "on").expect("recorded");
        assert_eq!(span.stage, "engines");
        assert!(span.wall >= 0.05, "{span:?}");
        // a busy loop of 50 ms wall burns CPU: at least a tenth of it even on a loaded
        // machine (getrusage has a 1 µs resolution, the scheduler's tick is coarser). The
        // span counts the whole process, and the other unit tests run on the other cores
        // meanwhile: at most every core for the span's wall time.
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get()) as f64;
        assert!(
            span.cpu > 0.005 && span.cpu <= cores * span.wall + 0.02,
            "{span:?}"
        );
    }
}

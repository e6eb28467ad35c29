//! Provenance: what a reader needs to reproduce a report — the tool's version and the git
//! commit of the sources it was built from (the build's one stamp, `crate::stamp`), the
//! case file's SHA-256, every engine setting, the machine and the date. Machine facts are
//! gathered once per process.

use rockslide_core::case::REFERENCE_LABEL;
use std::sync::OnceLock;

use rockslide_verify::suite::CaseResult;

/// Where and when a report was made (the case-specific part lives in the case result).
#[derive(Debug, Clone, PartialEq)]
pub struct Provenance {
    /// `rockslide <version>`.
    pub tool: String,
    /// The commit the tool was built from ([`crate::stamp::COMMIT`]: fixed at build time,
    /// `+dirty` when the sources had local changes).
    pub commit: String,
    /// Host name.
    pub host: String,
    /// Operating system and architecture (and distribution, where `/etc/os-release` says).
    pub os: String,
    /// Logical CPUs available to the process.
    pub cpus: usize,
    /// UTC date and time the report was written, RFC 3339.
    pub date: String,
}

impl Provenance {
    /// The provenance of this process (gathered on first use, then cached).
    pub fn current() -> &'static Provenance {
        static CELL: OnceLock<Provenance> = OnceLock::new();
        CELL.get_or_init(Provenance::collect)
    }

    /// Gather the facts now.
    pub fn collect() -> Provenance {
        Provenance {
            tool: crate::stamp::tool(),
            commit: crate::stamp::COMMIT.to_string(),
            host: hostname().unwrap_or_else(|| "unknown".into()),
            os: os_name(),
            cpus: std::thread::available_parallelism().map_or(1, |n| n.get()),
            date: chrono::Utc::now().to_rfc3339_opts(chrono::SecondsFormat::Secs, true),
        }
    }

    /// (name, value) lines for a case: the process facts plus the case's own and every
    /// run's engine settings.
    pub fn lines(&self, r: &CaseResult) -> Vec<(String, String)> {
        let c = &r.case;
        let mut v = vec![
            ("tool".to_string(), self.tool.clone()),
            ("commit".into(), self.commit.clone()),
            ("case file".into(), c.path.display().to_string()),
            ("case sha256".into(), c.sha256.clone()),
            (
                "run".into(),
                format!("{} s, default dt {} s", c.run.duration, c.run.dt),
            ),
        ];
        match &r.reference {
            Ok(x) => v.push((REFERENCE_LABEL.into(), x.solution.method())),
            Err(why) => v.push((REFERENCE_LABEL.into(), format!("none — {why}"))),
        }
        for run in &r.runs {
            let settings: Vec<String> = run
                .settings
                .iter()
                .map(|s| format!("{} = {}", s.label(), s.value_text()))
                .collect();
            v.push((format!("settings {}", run.label()), settings.join("; ")));
        }
        v.extend([
            ("machine".into(), self.machine()),
            ("date".into(), self.date.clone()),
        ]);
        v
    }

    /// `host (os, N CPUs)`.
    pub fn machine(&self) -> String {
        format!("{} ({}, {} CPUs)", self.host, self.os, self.cpus)
    }
}

fn hostname() -> Option<String> {
    let from_proc = std::fs::read_to_string("/proc/sys/kernel/hostname").ok();
    let name = from_proc
        .or_else(|| std::env::var("HOSTNAME").ok())
        .or_else(|| std::env::var("COMPUTERNAME").ok())?;
    let name = name.trim().to_string();
    (!name.is_empty()).then_some(name)
}

fn os_name() -> String {
    let base = format!("{}-{}", std::env::consts::OS, std::env::consts::ARCH);
    let pretty = std::fs::read_to_string("/etc/os-release")
        .ok()
        .and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("PRETTY_NAME="))
                .map(|v| v.trim_matches('"').to_string())
        });
    match pretty {
        Some(p) => format!("{base}, {p}"),
        None => base,
    }
}

//! Safe, atomic output.
//!
//! - [`inside`]: every output path is built from the output folder and a relative part
//!   that may not be absolute, may not climb (`..`) and may not pass through a symbolic
//!   link leading out of the folder — a case file from someone else cannot make rockslide
//!   write anywhere but the output folder.
//! - [`write_atomically`]: every file is written to a temporary sibling and renamed into
//!   place, so a reader never sees a half-written report, trace or JUnit file. The
//!   temporary sibling has a fixed name (`.<file>.rockslide-tmp`), so one left behind by an
//!   interrupted run is reused and renamed away by the next run writing that file, and
//!   [`remove_stale_temporaries`] clears the others from a folder. Only temporaries
//!   untouched for [`STALE_AFTER`] are stale: another process writing into the same folder
//!   (the shards of a study share one) keeps its temporary for milliseconds only.

use std::io::Write;
use std::path::{Component, Path, PathBuf};
use std::time::{Duration, SystemTime};

use crate::error::Error;

/// Suffix of the temporary sibling a file is written to before it is renamed into place.
pub const TEMP_SUFFIX: &str = ".rockslide-tmp";

/// `root/relative`, checked to lie inside `root`: `relative` must be non-empty, relative,
/// made of plain names only (no `..`, no `.`, no root or drive prefix), and the part of
/// the joined path that already exists must resolve (symbolic links followed) inside
/// `root`.
pub fn inside(root: &Path, relative: impl AsRef<Path>) -> Result<PathBuf, Error> {
    let relative = relative.as_ref();
    let refuse = |why: &str| {
        Error::Other(format!(
            "refusing to write {} under the output folder {}: {why}",
            relative.display(),
            root.display()
        ))
    };
    if relative.as_os_str().is_empty() {
        return Err(refuse("the path is empty"));
    }
    if !relative
        .components()
        .all(|c| matches!(c, Component::Normal(_)))
    {
        return Err(refuse(
            "only plain names are allowed (no absolute path, `.` or `..`)",
        ));
    }
    let joined = root.join(relative);
    if let Ok(real_root) = root.canonicalize() {
        // the deepest existing ancestor of the target must resolve inside the root
        let existing = joined.ancestors().find(|p| p.exists());
        if let Some(real) = existing.and_then(|p| p.canonicalize().ok())
            && !real.starts_with(&real_root)
        {
            return Err(refuse("a symbolic link leads out of the output folder"));
        }
    }
    Ok(joined)
}

/// The temporary sibling `path` is written to before being renamed into place.
pub fn temporary_for(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}{TEMP_SUFFIX}"))
}

/// Write `bytes` to `path` atomically, creating parent folders ([`write_atomically_with`]
/// with one write).
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    write_atomically_with(path, |w| w.write_all(bytes).map_err(|e| Error::io(path, e)))
}

/// Buffer of a streamed file ([`write_atomically_with`]): 1 MiB, so that a long trace
/// reaches the disk in few large writes.
pub const STREAM_BUFFER_BYTES: usize = 1 << 20;

/// Stream a file to `path` atomically: `write` fills a buffered temporary sibling, which
/// is renamed into place only when `write` succeeds (otherwise it is removed). Nothing of
/// the file is held in memory but the buffer, whatever its size.
pub fn write_atomically_with(
    path: &Path,
    write: impl FnOnce(&mut std::io::BufWriter<std::fs::File>) -> Result<(), Error>,
) -> Result<(), Error> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let tmp = temporary_for(path);
    let result = stream_and_rename(&tmp, path, write);
    if result.is_err() {
        // best effort: a failed write leaves nothing behind
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

fn stream_and_rename(
    tmp: &Path,
    path: &Path,
    write: impl FnOnce(&mut std::io::BufWriter<std::fs::File>) -> Result<(), Error>,
) -> Result<(), Error> {
    // never follow a symbolic link planted where the temporary file goes
    if tmp.symlink_metadata().is_ok() {
        std::fs::remove_file(tmp).map_err(|e| Error::io(tmp, e))?;
    }
    let file = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(tmp)
        .map_err(|e| Error::io(tmp, e))?;
    let mut w = std::io::BufWriter::with_capacity(STREAM_BUFFER_BYTES, file);
    write(&mut w)?;
    w.flush().map_err(|e| Error::io(path, e))?;
    drop(w);
    std::fs::rename(tmp, path).map_err(|e| Error::io(path, e))
}

/// A temporary file not modified for this long belongs to no live writer (one write takes
/// milliseconds): it was left by an interrupted run.
pub const STALE_AFTER: Duration = Duration::from_secs(60);

/// Remove the temporary files (`.*.rockslide-tmp`) an interrupted run left directly in `dir` and unmodified for [`STALE_AFTER`];
/// returns how many were removed. A folder that does not exist has none.
pub fn remove_stale_temporaries(dir: &Path) -> Result<usize, Error> {
    remove_stale_in(dir, 0)
}

/// [`remove_stale_temporaries`] in the output folder `root` and in its subfolders one
/// level down (each case's, `runs/`, `stability/`): every folder a command writes into.
/// Symbolic links are not followed, so nothing outside `root` is touched.
pub fn remove_stale_temporaries_under(root: &Path) -> Result<usize, Error> {
    remove_stale_in(root, 1)
}

fn remove_stale_in(dir: &Path, depth: usize) -> Result<usize, Error> {
    let entries = match std::fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(0),
        Err(e) => return Err(Error::io(dir, e)),
    };
    let mut removed = 0;
    for entry in entries {
        let entry = entry.map_err(|e| Error::io(dir, e))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        // the entry's own type: a symbolic link is neither a file nor a folder here
        let kind = entry.file_type().map_err(|e| Error::io(&entry.path(), e))?;
        if kind.is_dir() && depth > 0 {
            removed += remove_stale_in(&entry.path(), depth - 1)?;
        } else if kind.is_file() && is_stale_temporary(&name) && untouched_for_long(&entry) {
            std::fs::remove_file(entry.path()).map_err(|e| Error::io(&entry.path(), e))?;
            removed += 1;
        }
    }
    Ok(removed)
}

/// Not modified for [`STALE_AFTER`] (a modification time in the future counts as recent).
fn untouched_for_long(entry: &std::fs::DirEntry) -> bool {
    entry
        .metadata()
        .and_then(|m| m.modified())
        .ok()
        .and_then(|t| SystemTime::now().duration_since(t).ok())
        .is_some_and(|age| age >= STALE_AFTER)
}

/// `.x.rockslide-tmp`: our own temporary-name pattern only. (The `.tmpXXXXXX` names of
/// `tempfile` are not ours alone: another tool's file of that name is left alone.)
fn is_stale_temporary(name: &str) -> bool {
    name.len() > 1 + TEMP_SUFFIX.len() && name.starts_with('.') && name.ends_with(TEMP_SUFFIX)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inside_refuses_climbing_and_absolute_paths() {
        let root = Path::new("out");
        assert!(inside(root, "case/report.html").is_ok());
        for bad in ["", ".", "..", "../x", "a/../../x", "/etc/x", "./a"] {
            assert!(inside(root, bad).is_err(), "{bad:?} accepted");
        }
    }

    #[test]
    fn stale_temporaries_are_recognised() {
        assert!(is_stale_temporary(".report.html.rockslide-tmp"));
        assert!(!is_stale_temporary(".tmpAb12Cd"));
        assert!(!is_stale_temporary(".rockslide-tmp"));
        assert!(!is_stale_temporary("report.html"));
        assert!(!is_stale_temporary(".tmp"));
        assert!(!is_stale_temporary(".tmpfolder-long"));
    }
}

//! Safe, atomic output.
//!
//! - [`inside`]: every output path is built from the output folder and a relative part
//!   that may not be absolute, may not climb (`..`) and may not pass through a symbolic
//!   link leading out of the folder — a case file from someone else cannot make rockslide
//!   write anywhere but the output folder.
//! - [`output_target`]: the file a path names is written as the user means it — a new
//!   name or a regular file is replaced, a symbolic link is followed (its target is
//!   written, the link kept), and a folder, a device, a FIFO or a socket is refused with
//!   the reason, never replaced by a regular file.
//! - [`write_atomically`]: every file is written to a temporary sibling and renamed into
//!   place, so a reader never sees a half-written report, trace or JUnit file. The
//!   temporary sibling's name is unique to the process and the write
//!   (`.<file>.<pid>-<n>.rockslide-tmp`), so two runs writing into one folder at once
//!   (parallel CI jobs) never take each other's temporary: both succeed, the last rename
//!   of a file wins, and every file is whole. [`remove_stale_temporaries`] clears the
//!   temporaries an interrupted run left, and writing a file clears its fixed-name
//!   temporary (`.<file>.rockslide-tmp`, which earlier versions used). Only temporaries
//!   untouched for [`STALE_AFTER`] are stale: another process writing into the same
//!   folder keeps its temporary for milliseconds only.

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

/// Writes made by this process so far: the second part of a temporary name, so that two
/// threads writing one file never share a temporary.
static WRITES: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

/// A temporary sibling `path` is written to before being renamed into place, unique to
/// this process and this call: `.<file>.<pid>-<n>.rockslide-tmp`.
pub fn temporary_for(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let n = WRITES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let pid = std::process::id();
    path.with_file_name(format!(".{name}.{pid}-{n}{TEMP_SUFFIX}"))
}

/// The file `path` is written to, or why it is not written: a new name or a regular file
/// is itself; a symbolic link is followed to its target (the link is kept, its target
/// replaced) — a link to nothing is refused; a folder (or a path ending in `/`), a device,
/// a FIFO or a socket is refused, never replaced by a regular file.
pub fn output_target(path: &Path) -> Result<PathBuf, Error> {
    let refuse = |why: String| Error::Other(format!("{}: {why}", path.display()));
    if names_a_folder(path) {
        return Err(refuse(
            "names a folder (it ends in `/`, `.` or `..`): give a file name".into(),
        ));
    }
    let meta = match path.symlink_metadata() {
        Ok(meta) => meta,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(path.to_path_buf()),
        Err(e) => return Err(Error::io(path, e)),
    };
    if meta.file_type().is_symlink() {
        return match std::fs::canonicalize(path) {
            Ok(real) => output_target(&real),
            Err(_) => Err(refuse(format!(
                "is a symbolic link to {}, which does not exist: rockslide follows a link \
                 to a file but does not replace the link; name its target instead",
                std::fs::read_link(path).map_or("?".into(), |t| t.display().to_string())
            ))),
        };
    }
    match file_kind(&meta.file_type()) {
        None => Ok(path.to_path_buf()),
        Some(kind) => Err(refuse(format!(
            "is {kind}, not a regular file: rockslide writes only regular files (or new names), \
             and never replaces anything else"
        ))),
    }
}

/// A path that can only name a folder: it ends in a separator, `.` or `..`.
fn names_a_folder(path: &Path) -> bool {
    let text = path.as_os_str().to_string_lossy();
    text.ends_with(std::path::MAIN_SEPARATOR)
        || text.ends_with('/')
        || matches!(
            path.components().next_back(),
            None | Some(Component::CurDir | Component::ParentDir | Component::RootDir)
        )
}

/// What a file that is not regular is, in words (`None`: a regular file).
fn file_kind(kind: &std::fs::FileType) -> Option<&'static str> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_char_device() {
            return Some("a character device");
        }
        if kind.is_block_device() {
            return Some("a block device");
        }
        if kind.is_fifo() {
            return Some("a FIFO (named pipe)");
        }
        if kind.is_socket() {
            return Some("a socket");
        }
    }
    if kind.is_dir() {
        Some("a folder")
    } else if kind.is_file() {
        None
    } else {
        Some("not a regular file")
    }
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
    let path = &output_target(path)?;
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
    } else {
        remove_fixed_name_temporary(path);
    }
    result
}

/// Remove `.<file>.rockslide-tmp`, the fixed-name temporary of `path` an interrupted run
/// of an earlier version left (no writer uses that name now), once the file is whole.
fn remove_fixed_name_temporary(path: &Path) {
    let Some(name) = path.file_name() else {
        return;
    };
    let fixed = path.with_file_name(format!(".{}{TEMP_SUFFIX}", name.to_string_lossy()));
    if fixed.symlink_metadata().is_ok_and(|m| m.is_file()) {
        let _ = std::fs::remove_file(fixed);
    }
}

fn stream_and_rename(
    tmp: &Path,
    path: &Path,
    write: impl FnOnce(&mut std::io::BufWriter<std::fs::File>) -> Result<(), Error>,
) -> Result<(), Error> {
    // never follow a symbolic link planted where the temporary file goes (or a file a
    // dead process of the same id left)
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

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("rockslide-io-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// `newmark --csv /dev/full` left a 454-byte regular file where the device was: a
    /// device is refused before anything is written (asked of the target only, so that
    /// this test cannot replace the system's device even if it regressed).
    #[test]
    fn a_device_given_as_output_is_refused_not_replaced() {
        let e = output_target(Path::new("/dev/null"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("is a character device"), "{e}");
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_given_as_output_is_refused_and_kept() {
        let dir = scratch("fifo");
        let fifo = dir.join("pipe");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        assert!(made.is_ok_and(|s| s.success()), "mkfifo failed");
        let e = write_atomically(&fifo, b"x").unwrap_err().to_string();
        assert!(e.contains("is a FIFO"), "{e}");
        use std::os::unix::fs::FileTypeExt;
        assert!(fifo.symlink_metadata().unwrap().file_type().is_fifo());
        std::fs::remove_dir_all(dir).unwrap();
    }

    /// A symbolic link given as `--csv` was replaced by a regular file and its target left
    /// untouched: the link is followed, its target written and the link kept; a link to
    /// nothing is refused.
    #[cfg(unix)]
    #[test]
    fn a_symbolic_link_given_as_output_is_followed_not_replaced() {
        let dir = scratch("link");
        let target = dir.join("target.csv");
        std::fs::write(&target, "old").unwrap();
        let link = dir.join("link.csv");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        write_atomically(&link, b"new").unwrap();
        assert!(link.symlink_metadata().unwrap().file_type().is_symlink());
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        let dangling = dir.join("dangling.csv");
        std::os::unix::fs::symlink(dir.join("nowhere.csv"), &dangling).unwrap();
        let e = write_atomically(&dangling, b"x").unwrap_err().to_string();
        assert!(e.contains("does not exist"), "{e}");
        assert!(
            dangling
                .symlink_metadata()
                .unwrap()
                .file_type()
                .is_symlink()
        );
        std::fs::remove_dir_all(dir).unwrap();
    }

    /// `--csv out/` said "Not a directory": a folder, or a path that can only name one,
    /// is refused with that reason.
    #[test]
    fn a_folder_or_trailing_slash_given_as_output_says_so() {
        let dir = scratch("folder");
        let e = write_atomically(&dir, b"x").unwrap_err().to_string();
        assert!(e.contains("is a folder"), "{e}");
        let slash = PathBuf::from(format!("{}/new/", dir.display()));
        let e = write_atomically(&slash, b"x").unwrap_err().to_string();
        assert!(e.contains("names a folder"), "{e}");
        assert!(!dir.join("new").exists());
        std::fs::remove_dir_all(dir).unwrap();
    }

    /// Two runs into one folder failed with "….mcap: No such file or directory": each
    /// took the other's fixed-name temporary. Temporaries are unique per process and
    /// write, so concurrent writers of one file all succeed and the file is whole.
    #[test]
    fn concurrent_writers_of_one_file_all_succeed() {
        let dir = scratch("concurrent");
        let path = dir.join("trace.csv");
        assert_ne!(temporary_for(&path), temporary_for(&path));
        let texts: Vec<String> = (0..8).map(|i| format!("{i}").repeat(100_000)).collect();
        std::thread::scope(|s| {
            for text in &texts {
                let path = &path;
                s.spawn(move || {
                    for _ in 0..20 {
                        write_atomically(path, text.as_bytes()).unwrap();
                    }
                });
            }
        });
        let last = std::fs::read_to_string(&path).unwrap();
        assert!(texts.contains(&last), "a mixed or truncated file");
        let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(left.len(), 1, "temporaries left behind");
        std::fs::remove_dir_all(dir).unwrap();
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

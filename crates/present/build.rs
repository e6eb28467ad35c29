//! Fixes the build's commit stamp at build time, so that a report or an MCAP file says
//! which sources made it even when the tool runs outside a checkout: `ROCKSLIDE_GIT_COMMIT`
//! when the builder sets it (e.g. CI building from a tarball), else `git rev-parse HEAD`
//! of the source tree with `+dirty` when tracked files had local changes, else `unknown`.
//! Exposed to the crate as the `ROCKSLIDE_COMMIT` environment variable at compile time.

use std::path::{Path, PathBuf};
use std::process::Command;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=ROCKSLIDE_GIT_COMMIT");
    let commit = std::env::var("ROCKSLIDE_GIT_COMMIT")
        .ok()
        .filter(|c| !c.trim().is_empty())
        .or_else(from_git)
        .unwrap_or_else(|| "unknown".into());
    println!("cargo:rustc-env=ROCKSLIDE_COMMIT={}", commit.trim());
}

/// `git <args>` in this crate's folder, its trimmed output when it succeeded.
fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git")
        .arg("--no-optional-locks") // never rewrite the index: it is watched below
        .args(args)
        .current_dir(manifest_dir())
        .output()
        .ok()
        .filter(|o| o.status.success())?;
    Some(String::from_utf8_lossy(&out.stdout).trim().to_string())
}

fn manifest_dir() -> PathBuf {
    PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".into()))
}

/// Ask cargo to run this script again when `path` changes (only a path that exists: cargo
/// reruns the script on every build for a missing one).
fn watch(path: &Path) {
    if path.exists() {
        println!("cargo:rerun-if-changed={}", path.display());
    }
}

/// HEAD of the checkout, `+dirty` when tracked files differ from it; also registers what
/// must trigger a new stamp: HEAD, the branch it points to, the index, and the sources.
fn from_git() -> Option<String> {
    let head = git(&["rev-parse", "HEAD"]).filter(|h| !h.is_empty())?;
    let dir = manifest_dir();
    let mut files = vec!["HEAD".to_string(), "index".into(), "packed-refs".into()];
    files.extend(git(&["symbolic-ref", "-q", "HEAD"]));
    for f in files {
        if let Some(p) = git(&["rev-parse", "--git-path", &f]) {
            watch(&dir.join(p));
        }
    }
    if let Some(root) = git(&["rev-parse", "--show-toplevel"]) {
        let root = PathBuf::from(root);
        for d in ["crates", "src", "Cargo.toml", "Cargo.lock"] {
            watch(&root.join(d));
        }
    }
    let dirty =
        git(&["status", "--porcelain", "--untracked-files=no"]).is_some_and(|s| !s.is_empty());
    Some(if dirty { format!("{head}+dirty") } else { head })
}

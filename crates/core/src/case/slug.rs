//! Case names are folder names under the output folder, so they are slugs: 1 to
//! [`MAX_LEN`] characters from `A–Z a–z 0–9 . _ -`, starting with a letter or digit, not
//! ending in an output file's extension and not one of the names the suite writes at the
//! output root ([`RESERVED`]). Two cases of one run may not share a name, compared without
//! case (output folders on case-insensitive file systems would merge).

use std::path::Path;

use crate::case::Case;
use crate::error::InputErrors;

/// Longest case name.
pub const MAX_LEN: usize = 80;

/// Names the suite uses at the output root.
pub const RESERVED: &[&str] = &["summary", "stability", "study", "sweep", "index"];

/// Extensions of the files rockslide writes; a folder may not look like one of them.
const OUTPUT_EXTENSIONS: &[&str] = &[
    "md", "html", "csv", "json", "mcap", "svg", "xml", "toml", "txt",
];

/// `Ok` when `name` is a valid case name, else the reason.
pub fn check(name: &str) -> Result<(), String> {
    let shown = format!("{name:?}");
    if name.is_empty() {
        return Err("is empty; a case name names its output folder".into());
    }
    if name.chars().count() > MAX_LEN {
        return Err(format!("is longer than {MAX_LEN} characters"));
    }
    if let Some(c) = name.chars().find(|c| !is_slug_char(*c)) {
        return Err(format!(
            "is {shown}, with {c:?}; a case name names its output folder and may use only \
             letters, digits, `.`, `_` and `-`"
        ));
    }
    if !name.starts_with(|c: char| c.is_ascii_alphanumeric()) {
        return Err(format!(
            "is {shown}; it must start with a letter or a digit"
        ));
    }
    let lower = name.to_ascii_lowercase();
    let (stem, extension) = lower.rsplit_once('.').unwrap_or((&lower, ""));
    if OUTPUT_EXTENSIONS.contains(&extension) {
        return Err(format!(
            "is {shown}, which looks like an output file; choose a name without `.{extension}`"
        ));
    }
    if RESERVED.contains(&stem) || RESERVED.contains(&lower.as_str()) {
        return Err(format!(
            "is {shown}, a name the suite uses in the output folder; choose another"
        ));
    }
    Ok(())
}

/// A slug from a case file's stem: characters outside the slug set become `-`, the result
/// is cut to [`MAX_LEN`], made to start with a letter or digit, and kept off reserved names.
pub fn from_stem(path: &Path) -> String {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut slug: String = stem
        .chars()
        .map(|c| if is_slug_char(c) { c } else { '-' })
        .take(MAX_LEN)
        .collect();
    if !slug.starts_with(|c: char| c.is_ascii_alphanumeric()) {
        slug.insert_str(0, "case");
    }
    if check(&slug).is_err() {
        slug = format!("case-{}", slug.replace('.', "-"));
        slug.truncate(MAX_LEN);
    }
    slug
}

fn is_slug_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-')
}

/// Every pair of `cases` sharing a name (without case), as errors on the later file.
pub fn check_unique(cases: &[Case]) -> Result<(), InputErrors> {
    let mut errors = Vec::new();
    for (i, c) in cases.iter().enumerate() {
        let first = cases[..i]
            .iter()
            .find(|o| o.name.eq_ignore_ascii_case(&c.name));
        if let Some(first) = first {
            errors.push(c.locator.error(
                "name",
                format!(
                    "is {:?}, the name of {} too; two cases would write the same output folder",
                    c.name,
                    first.path.display()
                ),
            ));
        }
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(InputErrors(errors))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_that_escape_or_collide_are_refused() {
        for bad in [
            "",
            ".",
            "..",
            "../escaped",
            "/tmp/abs",
            "a/b",
            ".hidden",
            "summary.csv",
            "summary",
            "Stability",
            "x.html",
            "a b",
        ] {
            assert!(check(bad).is_err(), "{bad:?} accepted");
        }
        for good in ["pepo-ground-disp", "case_1.5", "A1"] {
            assert_eq!(check(good), Ok(()), "{good:?} refused");
        }
    }

    #[test]
    fn stems_become_valid_slugs() {
        for (stem, slug) in [
            ("pepo.toml", "pepo"),
            ("my case.toml", "my-case"),
            (".hidden.toml", "case.hidden"),
            ("summary.toml", "case-summary"),
            ("été.toml", "case-t-"),
        ] {
            let got = from_stem(Path::new(stem));
            assert_eq!(got, slug);
            assert_eq!(check(&got), Ok(()));
        }
    }
}

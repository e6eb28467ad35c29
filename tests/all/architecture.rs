//! ARCHITECTURE.md against the Cargo manifests. rockslide shall document its crate graph
//! as it is: the table lists every crate of `crates/` and the root package, its package
//! name, and exactly the workspace crates its manifest depends on; the diagram names every
//! crate; and the graph keeps the rules the verification rests on (no engine depends on
//! another engine, on the references or on the file formats; the references depend on
//! core only).

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use crate::common::repo;

/// The prefix of every workspace package; the table names crates without it.
const PREFIX: &str = "rockslide-";

/// One row of ARCHITECTURE.md's crate table.
#[derive(Debug)]
struct Row {
    /// `crates/<name>` or `src` (the root package).
    folder: String,
    /// The package name, `rockslide-<name>` or `rockslide`.
    package: String,
    /// The short names of the workspace crates it may depend on.
    deps: BTreeSet<String>,
}

/// The names between backticks in a table cell, in order.
fn ticked(cell: &str) -> Vec<String> {
    cell.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

/// The crate table: the rows after the header `| folder | package | owns | may depend on |`.
fn table(text: &str) -> Vec<Row> {
    let mut lines = text.lines().skip_while(|l| {
        let cells: Vec<&str> = l.split('|').map(str::trim).collect();
        cells.get(1..5) != Some(&["folder", "package", "owns", "may depend on"][..])
    });
    assert!(
        lines.next().is_some(),
        "ARCHITECTURE.md: no table with the header | folder | package | owns | may depend on |"
    );
    lines
        .skip(1) // |---|---|---|---|
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            assert_eq!(
                cells.len(),
                6,
                "ARCHITECTURE.md: a table row of 4 cells: {l}"
            );
            let one = |cell: &str, what: &str| -> String {
                match ticked(cell).as_slice() {
                    [name] => name.clone(),
                    _ => panic!("ARCHITECTURE.md: the {what} cell names one `name`: {l}"),
                }
            };
            Row {
                folder: one(cells[1], "folder").trim_end_matches('/').to_string(),
                package: one(cells[2], "package"),
                deps: ticked(cells[4]).into_iter().collect(),
            }
        })
        .collect()
}

/// The first ```text block: the diagram.
fn diagram(text: &str) -> &str {
    let start = text
        .find("```text")
        .expect("ARCHITECTURE.md has a ```text diagram")
        + 7;
    let len = text[start..]
        .find("```")
        .expect("the diagram's block is closed");
    &text[start..start + len]
}

/// A manifest's package name and the short names of the workspace crates it depends on
/// (normal dependencies on `rockslide-*`, a renamed one by its `package`).
fn manifest(path: &Path) -> (String, BTreeSet<String>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    let doc: toml::Table = text.parse().unwrap_or_else(|e| panic!("{path:?}: {e}"));
    let name = doc["package"]["name"]
        .as_str()
        .expect("package.name")
        .to_string();
    let deps = doc
        .get("dependencies")
        .and_then(toml::Value::as_table)
        .into_iter()
        .flatten()
        .map(|(key, value)| {
            value
                .get("package")
                .and_then(toml::Value::as_str)
                .unwrap_or(key)
                .to_string()
        })
        .filter_map(|package| package.strip_prefix(PREFIX).map(str::to_string))
        .collect();
    (name, deps)
}

/// Every package of the workspace by folder (`crates/<name>`, `src` for the root and
/// `python` for the Python module),
/// from the manifests on disk.
fn manifests() -> BTreeMap<String, (String, BTreeSet<String>)> {
    let mut out = BTreeMap::new();
    out.insert("src".to_string(), manifest(&repo("Cargo.toml")));
    out.insert("python".to_string(), manifest(&repo("python/Cargo.toml")));
    for entry in std::fs::read_dir(repo("crates")).unwrap() {
        let dir = entry.unwrap().path();
        if dir.join("Cargo.toml").is_file() {
            let name = dir.file_name().unwrap().to_string_lossy();
            out.insert(format!("crates/{name}"), manifest(&dir.join("Cargo.toml")));
        }
    }
    out
}

#[test]
fn the_architecture_table_lists_every_crate_with_exactly_its_workspace_dependencies() {
    let text = std::fs::read_to_string(repo("ARCHITECTURE.md")).unwrap();
    let rows = table(&text);
    let manifests = manifests();
    let mut problems = Vec::new();
    let listed: BTreeSet<&str> = rows.iter().map(|r| r.folder.as_str()).collect();
    for folder in manifests.keys() {
        if !listed.contains(folder.as_str()) {
            problems.push(format!(
                "{folder}: a crate of the workspace missing from the table"
            ));
        }
    }
    for row in &rows {
        let Some((package, deps)) = manifests.get(&row.folder) else {
            problems.push(format!(
                "{} ({}): a row of the table with no such crate folder",
                row.folder, row.package
            ));
            continue;
        };
        if &row.package != package {
            problems.push(format!(
                "{}: the table says package `{}`, its Cargo.toml `{package}`",
                row.folder, row.package
            ));
        }
        for dep in deps.difference(&row.deps) {
            problems.push(format!(
                "{} ({package}): depends on `{PREFIX}{dep}`, which its \"may depend on\" cell does not name",
                row.folder
            ));
        }
        for dep in row.deps.difference(deps) {
            problems.push(format!(
                "{} ({package}): the table names `{dep}`, but its Cargo.toml does not depend on `{PREFIX}{dep}`",
                row.folder
            ));
        }
    }
    assert!(
        problems.is_empty(),
        "ARCHITECTURE.md against the manifests:\n{}",
        problems.join("\n")
    );
}

#[test]
fn the_architecture_diagram_names_every_crate() {
    let text = std::fs::read_to_string(repo("ARCHITECTURE.md")).unwrap();
    let picture = diagram(&text);
    let missing: Vec<String> = manifests()
        .into_iter()
        .filter(|(_, (package, _))| package.starts_with(PREFIX))
        .map(|(_, (package, _))| package)
        .filter(|package| {
            let short = &package[PREFIX.len()..];
            !picture.contains(package.as_str()) && !picture.contains(short)
        })
        .collect();
    assert!(
        missing.is_empty(),
        "ARCHITECTURE.md's diagram does not name {missing:?}"
    );
    assert!(
        picture.contains("src/"),
        "ARCHITECTURE.md's diagram shows the application at src/"
    );
}

#[test]
fn engines_depend_on_core_and_the_engine_api_only_and_the_references_on_core_only() {
    let manifests = manifests();
    let engines: BTreeSet<String> = manifests
        .keys()
        .filter_map(|f| f.strip_prefix("crates/"))
        .filter(|name| name.starts_with("engine-") && *name != "engine-api")
        .map(str::to_string)
        .collect();
    assert!(
        engines.len() >= 3,
        "the predictor-corrector, fe and rapier engines, found {engines:?}"
    );
    let mut problems = Vec::new();
    for engine in &engines {
        let (package, deps) = &manifests[&format!("crates/{engine}")];
        for dep in deps.iter().filter(|d| *d != "core" && *d != "engine-api") {
            let what = match dep.as_str() {
                d if engines.contains(d) => "another engine",
                "reference" => "the references",
                "formats" => "the file formats",
                _ => "neither core nor the engine API",
            };
            problems.push(format!(
                "{package} depends on `{PREFIX}{dep}` ({what}; an engine depends on core and the engine API only)"
            ));
        }
    }
    let (package, deps) = &manifests["crates/reference"];
    for dep in deps.iter().filter(|d| *d != "core") {
        problems.push(format!("{package} depends on `{PREFIX}{dep}` (core only)"));
    }
    assert!(
        problems.is_empty(),
        "the crate graph's rules:\n{}",
        problems.join("\n")
    );
}

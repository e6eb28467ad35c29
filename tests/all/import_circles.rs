//! No import circle inside a crate. rockslide shall keep each crate's modules in layers:
//! no module uses another that, directly or through others, uses it back. Each crate's
//! module tree is read from its root file (`lib.rs`, `main.rs`) through its `mod`
//! declarations, and every `use` and every `crate::`, `super::` and `self::` path of
//! non-test code is resolved to the module that defines the name (through `use`
//! re-exports). A path from module `a::x` to module `a::y` is an edge between the sibling
//! modules `x` and `y` of `a`, at every level: the crate's top-level modules and the
//! submodules of each directory module. A strongly connected group of siblings is a
//! circle; the test names it and one line for each of its edges.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use crate::common::repo;

/// A module's path inside its crate (`["case", "record", "station"]`; the root is empty).
type ModPath = Vec<String>;

/// One token of Rust source, with its line; comments, strings, characters, lifetimes
/// and numbers are dropped.
#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Ident(String),
    PathSep,
    Open(char),
    Close(char),
    Semi,
    Comma,
    Pound,
    Bang,
    Star,
    Dollar,
    Other,
}

/// The tokens of a source text.
fn tokens(text: &str) -> Vec<(Tok, usize)> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line) = (0, 1);
    let at = |k: usize| chars.get(k).copied().unwrap_or('\0');
    while i < chars.len() {
        let c = chars[i];
        if c == '\n' {
            line += 1;
            i += 1;
        } else if c.is_whitespace() {
            i += 1;
        } else if c == '/' && at(i + 1) == '/' {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    i += 2;
                } else if chars[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    line += usize::from(chars[i] == '\n');
                    i += 1;
                }
            }
        } else if c == '"' {
            i = skip_string(&chars, i + 1, None, &mut line);
        } else if c == '\'' {
            // a character literal ('a', '\n', '✓') or a lifetime ('a)
            if at(i + 1) == '\\' {
                i += 3;
                while i < chars.len() && chars[i] != '\'' {
                    i += 1;
                }
                i += 1;
            } else if at(i + 2) == '\'' {
                i += 3;
            } else {
                i += 1;
                while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                    i += 1;
                }
            }
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            let word: String = chars[start..i].iter().collect();
            // raw strings r"…", r#"…"#, br"…"; raw identifiers r#type stay identifiers
            if matches!(word.as_str(), "r" | "br" | "cr") && matches!(at(i), '"' | '#') {
                let hashes = chars[i..].iter().take_while(|&&h| h == '#').count();
                if at(i + hashes) == '"' {
                    i = skip_string(&chars, i + hashes + 1, Some(hashes), &mut line);
                    continue;
                }
                i += hashes;
                continue;
            }
            out.push((Tok::Ident(word), line));
        } else if c.is_ascii_digit() {
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
        } else {
            let tok = match c {
                ':' if at(i + 1) == ':' => {
                    i += 1;
                    Tok::PathSep
                }
                '{' | '(' | '[' => Tok::Open(c),
                '}' | ')' | ']' => Tok::Close(c),
                ';' => Tok::Semi,
                ',' => Tok::Comma,
                '#' => Tok::Pound,
                '!' => Tok::Bang,
                '*' => Tok::Star,
                '$' => Tok::Dollar,
                _ => Tok::Other,
            };
            out.push((tok, line));
            i += 1;
        }
    }
    out
}

/// The index after a string whose opening quote ends before `i`; `raw` holds a raw
/// string's number of `#` (no escapes; closed by `"` and that many `#`).
fn skip_string(chars: &[char], mut i: usize, raw: Option<usize>, line: &mut usize) -> usize {
    let hashes = raw.unwrap_or(0);
    while i < chars.len() {
        match chars[i] {
            '\\' if raw.is_none() => i += 2,
            '"' if chars[i + 1..].iter().take_while(|&&h| h == '#').count() >= hashes => {
                return i + 1 + hashes;
            }
            c => {
                *line += usize::from(c == '\n');
                i += 1;
            }
        }
    }
    i
}

/// A path as written, in the module where it is written.
#[derive(Debug, Clone)]
struct Written {
    segments: Vec<String>,
    line: usize,
}

/// A name a `use` binds in a module (`None`: a glob), to the path it names.
#[derive(Debug, Clone)]
struct Import {
    binding: Option<String>,
    path: Written,
}

/// What the parser learns of one module.
#[derive(Debug, Default)]
struct Module {
    file: PathBuf,
    children: BTreeSet<String>,
    /// Items defined at the module's level (functions, types, constants, macros).
    defined: BTreeSet<String>,
    /// Module-level `use` items: what the module's children may name through it.
    imports: Vec<Import>,
    /// Every path the module's non-test code writes: `use` paths and `crate::`,
    /// `super::`, `self::` paths.
    paths: Vec<Written>,
}

/// A crate's module tree, keyed by module path.
type Tree = BTreeMap<ModPath, Module>;

/// Reads a file's text (the disk in the test, a map in the unit tests).
type Read<'a> = &'a dyn Fn(&Path) -> Option<String>;

/// The module tree of the crate whose root file is `root`.
fn module_tree(root: &Path, read: Read) -> Result<Tree, String> {
    let mut tree = Tree::new();
    let dir = root.parent().unwrap_or(Path::new("")).to_path_buf();
    load_file(root, &dir, Vec::new(), read, &mut tree)?;
    Ok(tree)
}

/// Parses one file as the module `path`, whose child files live in `dir`, then each
/// child file it declares.
fn load_file(
    file: &Path,
    dir: &Path,
    path: ModPath,
    read: Read,
    tree: &mut Tree,
) -> Result<(), String> {
    let text = read(file).ok_or_else(|| format!("{}: cannot be read", file.display()))?;
    let toks = tokens(&text);
    let mut parser = Parser {
        toks: &toks,
        at: 0,
        file,
        tree,
        files: Vec::new(),
    };
    parser.module(&path, 0, dir);
    let files = std::mem::take(&mut parser.files);
    for (child_path, child_dir, name) in files {
        let flat = child_dir.join(format!("{name}.rs"));
        let nested = child_dir.join(&name).join("mod.rs");
        let (child_file, grand_dir) = if read(&flat).is_some() {
            (flat, child_dir.join(&name))
        } else if read(&nested).is_some() {
            (nested, child_dir.join(&name))
        } else {
            return Err(format!(
                "{}: `mod {name};` has no file {} or {}",
                file.display(),
                flat.display(),
                nested.display()
            ));
        };
        load_file(&child_file, &grand_dir, child_path, read, tree)?;
    }
    Ok(())
}

/// A recursive-descent walk over one file's tokens that keeps module structure, items
/// and paths, and skips `#[cfg(test)]` items.
struct Parser<'a> {
    toks: &'a [(Tok, usize)],
    at: usize,
    file: &'a Path,
    tree: &'a mut Tree,
    /// Child modules declared `mod name;`: their path, the folder of their file, name.
    files: Vec<(ModPath, PathBuf, String)>,
}

impl Parser<'_> {
    fn peek(&self, k: usize) -> Option<&Tok> {
        self.toks.get(self.at + k).map(|(t, _)| t)
    }

    fn ident(&self, k: usize) -> Option<&str> {
        match self.peek(k) {
            Some(Tok::Ident(s)) => Some(s),
            _ => None,
        }
    }

    fn line(&self) -> usize {
        self.toks.get(self.at).map_or(0, |(_, l)| *l)
    }

    /// The items of module `path` until the `}` that closes it (or the file's end):
    /// `depth` is 0 for a file, 1 inside an inline `mod name { … }`.
    fn module(&mut self, path: &ModPath, depth: usize, dir: &Path) {
        let file = self.file.to_path_buf();
        self.tree.entry(path.clone()).or_default().file = file;
        let mut braces = 0usize;
        while let Some(tok) = self.peek(0).cloned() {
            match tok {
                Tok::Pound if self.is_cfg_test() => self.skip_item(),
                Tok::Open('{') => {
                    braces += 1;
                    self.at += 1;
                }
                Tok::Close('}') => {
                    self.at += 1;
                    if braces == 0 && depth > 0 {
                        return;
                    }
                    braces = braces.saturating_sub(1);
                }
                Tok::Ident(word) => self.word(&word, path, braces == 0, dir),
                _ => self.at += 1,
            }
        }
    }

    /// One identifier in module `path`; `top` when at the module's own level.
    fn word(&mut self, word: &str, path: &ModPath, top: bool, dir: &Path) {
        let follows_dollar = self.at > 0 && self.toks[self.at - 1].0 == Tok::Dollar;
        match word {
            "use" => self.use_item(path, top),
            "mod" if top && self.ident(1).is_some() => {
                let name = self.ident(1).unwrap_or_default().to_string();
                let mut child = path.clone();
                child.push(name.clone());
                self.tree
                    .entry(path.clone())
                    .or_default()
                    .children
                    .insert(name.clone());
                self.at += 2;
                if self.peek(0) == Some(&Tok::Semi) {
                    self.files.push((child, dir.to_path_buf(), name));
                    self.at += 1;
                } else if self.peek(0) == Some(&Tok::Open('{')) {
                    self.at += 1;
                    let inner = dir.join(&name);
                    self.module(&child, 1, &inner);
                }
            }
            "fn" | "struct" | "enum" | "trait" | "type" | "const" | "static" | "union" if top => {
                if let Some(name) = self.ident(1).map(str::to_string) {
                    self.defined(path, name);
                }
                self.at += 1;
            }
            "macro_rules" if top && self.peek(1) == Some(&Tok::Bang) => {
                if let Some(name) = self.ident(2).map(str::to_string) {
                    self.defined(path, name);
                }
                self.at += 1;
            }
            "crate" | "super" | "self"
                if !follows_dollar && self.peek(1) == Some(&Tok::PathSep) =>
            {
                let written = self.path_segments();
                self.module_mut(path).paths.push(written);
            }
            _ => self.at += 1,
        }
    }

    fn module_mut(&mut self, path: &ModPath) -> &mut Module {
        self.tree.entry(path.clone()).or_default()
    }

    fn defined(&mut self, path: &ModPath, name: String) {
        self.module_mut(path).defined.insert(name);
    }

    /// `a::b::c` from here: the identifiers joined by `::`.
    fn path_segments(&mut self) -> Written {
        let line = self.line();
        let mut segments = Vec::new();
        while let Some(name) = self.ident(0).map(str::to_string) {
            segments.push(name);
            self.at += 1;
            if self.peek(0) == Some(&Tok::PathSep) && self.ident(1).is_some() {
                self.at += 1;
            } else {
                break;
            }
        }
        Written { segments, line }
    }

    /// `use tree;`: every path it names, and at the module's level what it binds.
    fn use_item(&mut self, path: &ModPath, top: bool) {
        self.at += 1;
        if self.peek(0) == Some(&Tok::PathSep) {
            // `use ::name`: an extern crate
            self.skip_to_semi();
            return;
        }
        let mut found = Vec::new();
        self.use_tree(&[], &mut found);
        let module = self.module_mut(path);
        for import in found {
            module.paths.push(import.path.clone());
            if top {
                module.imports.push(import);
            }
        }
        self.skip_to_semi();
    }

    /// One use tree under `prefix`: `a::b`, `a::b as c`, `a::*`, `a::{tree, …}`.
    fn use_tree(&mut self, prefix: &[String], found: &mut Vec<Import>) {
        let line = self.line();
        let mut segments = prefix.to_vec();
        loop {
            match self.peek(0).cloned() {
                Some(Tok::Ident(name)) => {
                    self.at += 1;
                    if name == "as" {
                        let alias = self.ident(0).map(str::to_string);
                        self.at += 1;
                        found.push(Import {
                            binding: alias,
                            path: Written { segments, line },
                        });
                        return;
                    }
                    segments.push(name);
                    if self.peek(0) == Some(&Tok::PathSep) {
                        self.at += 1;
                        continue;
                    }
                    let binding = match segments.last().map(String::as_str) {
                        Some("self") => {
                            segments.pop();
                            segments.last().cloned()
                        }
                        last => last.map(str::to_string),
                    };
                    found.push(Import {
                        binding,
                        path: Written { segments, line },
                    });
                    return;
                }
                Some(Tok::Star) => {
                    self.at += 1;
                    found.push(Import {
                        binding: None,
                        path: Written { segments, line },
                    });
                    return;
                }
                Some(Tok::Open('{')) => {
                    self.at += 1;
                    while !matches!(self.peek(0), None | Some(Tok::Close('}'))) {
                        if self.peek(0) == Some(&Tok::Comma) {
                            self.at += 1;
                            continue;
                        }
                        let before = self.at;
                        self.use_tree(&segments, found);
                        if self.at == before {
                            self.at += 1;
                        }
                    }
                    self.at += 1;
                    return;
                }
                _ => return,
            }
        }
    }

    fn skip_to_semi(&mut self) {
        while !matches!(self.peek(0), None | Some(Tok::Semi)) {
            self.at += 1;
        }
        self.at += 1;
    }

    /// `#[cfg(test)]` here.
    fn is_cfg_test(&self) -> bool {
        let want = [
            Tok::Pound,
            Tok::Open('['),
            Tok::Ident("cfg".into()),
            Tok::Open('('),
            Tok::Ident("test".into()),
            Tok::Close(')'),
            Tok::Close(']'),
        ];
        want.iter()
            .enumerate()
            .all(|(k, t)| self.peek(k) == Some(t))
    }

    /// Skips an attribute's item: its further attributes, then up to its `;` or its
    /// closed `{ … }` body.
    fn skip_item(&mut self) {
        let mut nesting = 0usize;
        while let Some(tok) = self.peek(0).cloned() {
            self.at += 1;
            match tok {
                Tok::Open(_) => nesting += 1,
                Tok::Close(c) => {
                    nesting = nesting.saturating_sub(1);
                    // the end of an attribute `#[…]` is not the end of the item
                    if c == '}' && nesting == 0 {
                        return;
                    }
                }
                Tok::Semi if nesting == 0 => return,
                _ => {}
            }
        }
    }
}

/// The module a written path names, from the module `from`: `crate::`, `super::` and
/// `self::` paths, and paths that start with a child module or an imported name of
/// `from`. `None` for a path outside the crate (`std::…`, another crate).
fn absolute(tree: &Tree, from: &ModPath, segments: &[String], depth: usize) -> Option<ModPath> {
    let (first, rest) = segments.split_first()?;
    let mut base = match first.as_str() {
        "crate" => Vec::new(),
        "self" => from.clone(),
        "super" => {
            let mut up = from.clone();
            up.pop()?;
            let mut rest = rest;
            while rest.first().map(String::as_str) == Some("super") {
                up.pop()?;
                rest = &rest[1..];
            }
            return Some([up, rest.to_vec()].concat());
        }
        name => {
            let module = tree.get(from)?;
            if module.children.contains(name) {
                let mut p = from.clone();
                p.push(name.to_string());
                p
            } else {
                let import = module
                    .imports
                    .iter()
                    .find(|i| i.binding.as_deref() == Some(name))?;
                if depth > 8 {
                    return None;
                }
                absolute(tree, from, &import.path.segments, depth + 1)?
            }
        }
    };
    base.extend(rest.iter().cloned());
    Some(base)
}

/// The module that defines what an absolute path names, following `use` re-exports.
fn defining_module(tree: &Tree, path: &[String], depth: usize) -> ModPath {
    let mut module: ModPath = Vec::new();
    for (k, segment) in path.iter().enumerate() {
        let Some(m) = tree.get(&module) else {
            return module;
        };
        if m.children.contains(segment) {
            module.push(segment.clone());
            continue;
        }
        if m.defined.contains(segment) || depth > 8 {
            return module;
        }
        if let Some(import) = m
            .imports
            .iter()
            .find(|i| i.binding.as_deref() == Some(segment.as_str()))
            && let Some(target) = absolute(tree, &module, &import.path.segments, 0)
        {
            return defining_module(tree, &target, depth + 1);
        }
        for glob in m.imports.iter().filter(|i| i.binding.is_none()) {
            let Some(mut target) = absolute(tree, &module, &glob.path.segments, 0) else {
                continue;
            };
            let through = defining_module(tree, &target, depth + 1);
            let names_it = tree.get(&through).is_some_and(|g| {
                g.defined.contains(segment)
                    || g.children.contains(segment)
                    || g.imports
                        .iter()
                        .any(|i| i.binding.as_deref() == Some(segment.as_str()))
            });
            if names_it {
                target.extend(path[k..].iter().cloned());
                return defining_module(tree, &target, depth + 1);
            }
        }
        return module;
    }
    module
}

/// One edge between sibling modules and the line that makes it.
#[derive(Debug, Clone)]
struct Witness {
    file: PathBuf,
    line: usize,
    path: String,
}

/// The edges between sibling modules, per parent module: parent → (from, to) → witness.
type Levels = BTreeMap<ModPath, BTreeMap<(String, String), Witness>>;

fn sibling_edges(tree: &Tree) -> Levels {
    let mut levels = Levels::new();
    for (from, module) in tree {
        for written in &module.paths {
            let Some(path) = absolute(tree, from, &written.segments, 0) else {
                continue;
            };
            let to = defining_module(tree, &path, 0);
            let common = from.iter().zip(&to).take_while(|(a, b)| a == b).count();
            if common < from.len() && common < to.len() {
                levels
                    .entry(from[..common].to_vec())
                    .or_default()
                    .entry((from[common].clone(), to[common].clone()))
                    .or_insert_with(|| Witness {
                        file: module.file.clone(),
                        line: written.line,
                        path: written.segments.join("::"),
                    });
            }
        }
    }
    levels
}

/// One circle per strongly connected group of a directed graph's nodes, each as the
/// nodes of a shortest cycle through the group's first node: `[a, b, c]` for a → b → c → a.
fn circles(edges: &BTreeSet<(String, String)>) -> Vec<Vec<String>> {
    let mut next: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for (a, b) in edges {
        next.entry(a).or_default().push(b);
    }
    let reach = |start: &str| -> BTreeMap<String, String> {
        // node → its predecessor on a shortest path from `start` (breadth first)
        let mut parent = BTreeMap::new();
        let mut queue = std::collections::VecDeque::from([start.to_string()]);
        while let Some(n) = queue.pop_front() {
            for &m in next.get(n.as_str()).into_iter().flatten() {
                if !parent.contains_key(m) {
                    parent.insert(m.to_string(), n.clone());
                    queue.push_back(m.to_string());
                }
            }
        }
        parent
    };
    let nodes: BTreeSet<&str> = edges
        .iter()
        .flat_map(|(a, b)| [a.as_str(), b.as_str()])
        .collect();
    let mut seen = BTreeSet::new();
    let mut out = Vec::new();
    for &n in &nodes {
        if seen.contains(n) {
            continue;
        }
        let from_n = reach(n);
        if !from_n.contains_key(n) {
            continue;
        }
        for &m in &nodes {
            if from_n.contains_key(m) && reach(m).contains_key(n) {
                seen.insert(m);
            }
        }
        let mut cycle = vec![n.to_string()];
        let mut at = from_n[n].clone();
        while at != n {
            cycle.push(at.clone());
            at = from_n[&at].clone();
        }
        cycle[1..].reverse();
        out.push(cycle);
    }
    out
}

/// Every import circle of a crate's tree, one line each: where, the cycle, and the
/// path behind each edge.
fn circle_lines(name: &str, tree: &Tree, base: &Path) -> Vec<String> {
    let mut out = Vec::new();
    for (parent, edges) in sibling_edges(tree) {
        let keys: BTreeSet<(String, String)> = edges.keys().cloned().collect();
        for cycle in circles(&keys) {
            let mut closed = cycle.clone();
            closed.push(cycle[0].clone());
            let evidence: Vec<String> = closed
                .windows(2)
                .map(|w| {
                    let e = &edges[&(w[0].clone(), w[1].clone())];
                    let file = e.file.strip_prefix(base).unwrap_or(&e.file);
                    format!("{}:{} uses {}", file.display(), e.line, e.path)
                })
                .collect();
            let place = if parent.is_empty() {
                "top level".to_string()
            } else {
                parent.join("::")
            };
            out.push(format!(
                "{name}, {place}: {} ({})",
                closed.join(" → "),
                evidence.join("; ")
            ));
        }
    }
    out
}

/// The root files of the workspace's crates: each `crates/*/src/lib.rs`, the root
/// package's library and binary, the Python module.
fn crate_roots() -> Vec<(String, PathBuf)> {
    let mut roots = vec![
        ("rockslide (lib)".to_string(), repo("src/lib.rs")),
        ("rockslide (bin)".to_string(), repo("src/main.rs")),
        ("rockslide-python".to_string(), repo("python/src/lib.rs")),
    ];
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(repo("crates"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    dirs.sort();
    for dir in dirs {
        let lib = dir.join("src/lib.rs");
        if lib.is_file() {
            let name = dir.file_name().unwrap().to_string_lossy();
            roots.push((format!("rockslide-{name}"), lib));
        }
    }
    roots
}

fn read_disk(path: &Path) -> Option<String> {
    std::fs::read_to_string(path).ok()
}

#[test]
fn no_crate_has_an_import_circle_between_its_modules() {
    let mut found = Vec::new();
    let mut modules = 0;
    for (name, root) in crate_roots() {
        let tree = module_tree(&root, &read_disk).unwrap_or_else(|e| panic!("{name}: {e}"));
        modules += tree.len();
        found.extend(circle_lines(&name, &tree, &repo("")));
    }
    // the walk reached the module trees, not only their roots
    assert!(modules > 200, "{modules} modules read");
    let circle = |line: &str| line.split(" (").next().unwrap_or(line).to_string();
    let new: Vec<&String> = found
        .iter()
        .filter(|l| !KNOWN_CIRCLES.contains(&circle(l).as_str()))
        .collect();
    assert!(
        new.is_empty(),
        "import circles inside crates (a module that uses another which, directly or through others, uses it back):\n{}",
        new.iter()
            .map(|l| l.as_str())
            .collect::<Vec<_>>()
            .join("\n")
    );
    let gone: Vec<&&str> = KNOWN_CIRCLES
        .iter()
        .filter(|k| !found.iter().any(|l| circle(l) == **k))
        .collect();
    assert!(
        gone.is_empty(),
        "listed circles no longer found (remove them from KNOWN_CIRCLES): {gone:?}"
    );
}

/// Circles the tree still has, each to be removed by moving the shared piece down: the
/// check fails on any other circle, and on a listed one that is gone. The finder reports
/// one circle per tangle, so fixing one may show the next of the same tangle.
const KNOWN_CIRCLES: &[&str] = &[];

/// A crate of files held in memory, for the unit tests.
fn memory(files: &[(&str, &str)]) -> impl Fn(&Path) -> Option<String> {
    let map: BTreeMap<PathBuf, String> = files
        .iter()
        .map(|(p, t)| (PathBuf::from(p), t.to_string()))
        .collect();
    move |p: &Path| map.get(p).cloned()
}

fn set(edges: &[(&str, &str)]) -> BTreeSet<(String, String)> {
    edges
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect()
}

#[test]
fn the_cycle_finder_names_each_strongly_connected_group_once() {
    // a → b → c → a and d ⇄ e are circles; c → d and e → f are not part of one
    let edges = set(&[
        ("a", "b"),
        ("b", "c"),
        ("c", "a"),
        ("c", "d"),
        ("d", "e"),
        ("e", "d"),
        ("e", "f"),
    ]);
    assert_eq!(circles(&edges), vec![vec!["a", "b", "c"], vec!["d", "e"]]);
    // a layered graph has none
    assert!(circles(&set(&[("a", "b"), ("b", "c"), ("a", "c")])).is_empty());
}

#[test]
fn a_circle_through_a_re_export_in_a_directory_module_is_found_and_located() {
    let read = memory(&[
        (
            "src/lib.rs",
            "mod record;\nmod scene;\n#[cfg(test)]\nmod tests;\n",
        ),
        // `tests.rs` does not exist: a `#[cfg(test)]` module is not read
        (
            "src/record/mod.rs",
            "//! use crate::scene in a comment is no edge\nmod station;\nmod cosmos;\npub use station::{Station, read};\n",
        ),
        (
            "src/record/station.rs",
            "pub struct Station;\npub fn read() { super::cosmos::parse(\"crate::scene::X\"); }\n",
        ),
        (
            "src/record/cosmos.rs",
            "use super::Station;\npub fn parse(_: &str) -> Option<Station> { None }\n",
        ),
        (
            "src/scene.rs",
            "use crate::record::read;\n#[cfg(test)]\nmod t { use crate::scene::X; }\npub struct X;\n",
        ),
    ]);
    let tree = module_tree(Path::new("src/lib.rs"), &read).unwrap();
    let lines = circle_lines("demo", &tree, Path::new(""));
    assert_eq!(
        lines,
        vec![
            "demo, record: cosmos → station → cosmos (src/record/cosmos.rs:1 uses super::Station; src/record/station.rs:2 uses super::cosmos::parse)"
        ]
    );
}

#[test]
fn layered_modules_have_no_circle() {
    let read = memory(&[
        ("src/lib.rs", "mod a;\nmod b;\nmod c;\n"),
        (
            "src/a.rs",
            "use crate::b::B;\nuse crate::c::{self, C};\nfn f() { c::g(); }\n",
        ),
        ("src/b.rs", "pub struct B(crate::c::C);\n"),
        ("src/c.rs", "pub struct C;\npub fn g() {}\n"),
    ]);
    let tree = module_tree(Path::new("src/lib.rs"), &read).unwrap();
    let edges = sibling_edges(&tree);
    let top: BTreeSet<_> = edges[&Vec::new()].keys().cloned().collect();
    assert_eq!(top, set(&[("a", "b"), ("a", "c"), ("b", "c")]));
    assert!(circle_lines("demo", &tree, Path::new("")).is_empty());
}

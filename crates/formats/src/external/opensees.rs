//! OpenSees recorder files, as `recorder Node` and `recorder Element` write them with
//! `-time`: no header, each line the time then the recorded values, blank-separated —
//! for a Node recorder each node's degrees of freedom in the order given (`-node 2 3 -dof
//! 1 2 disp`: node 2 DOF 1, node 2 DOF 2, node 3 DOF 1, …), for an Element recorder each
//! element's response components in turn.
//!
//! The columns are named from the recorder command — given as `recorder` in the case, or
//! found in the script named by `script` (Tcl `recorder Node -file …`, or OpenSeesPy
//! `ops.recorder('Node', '-file', …)`) by its `-file` — as `"node 2 dof 1 disp"` and
//! `"element 1 force 1"`. Without either, the columns are named by position (`"column
//! 2"`, the time being column 1). OpenSees has no units: the map states them. Files
//! written with `-xml` and `-binary` are read too (`opensees_xml`).

use std::path::Path;

use rockslide_core::case::{ExternalFormat, ExternalTrace};
use rockslide_core::error::{InputError, InputErrors};

use super::ansys::words;
use super::number::{Decimal, parse_number};
use super::opensees_xml;
use super::read_text;
use super::sheet::Sheet;

/// What a recorder command says about its file's columns.
#[derive(Debug, PartialEq)]
struct Recorder {
    /// `Node` or `Element`.
    kind: String,
    /// The `-file` it writes.
    file: Option<String>,
    /// Whether the first column is the time (`-time`).
    time: bool,
    /// Nodes or elements, in order.
    objects: Vec<String>,
    /// Degrees of freedom (Node recorders).
    dofs: Vec<String>,
    /// The response (`disp`, `force`, `deformation`…).
    response: String,
}

/// Read a recorder file (see the module docs).
pub(super) fn read(
    path: &Path,
    text: &str,
    format: &ExternalFormat,
) -> Result<ExternalTrace, InputErrors> {
    if opensees_xml::is_xml(text) {
        return opensees_xml::read_xml(path, text, format);
    }
    let mut sheet = Sheet::new(path, "OpenSees recorder file", "time");
    let recorder = recorder(path, format)?;
    if let Some(r) = &recorder {
        if !r.time {
            let why = "the recorder writes no time column: add `-time` to it";
            return Err(InputError::new(path, "recorder", why).into());
        }
        sheet.notes.push(format!(
            "recorder {} {} {} ({})",
            r.kind,
            r.objects.join(" "),
            r.response,
            r.file.as_deref().unwrap_or("file not named")
        ));
    } else {
        sheet
            .notes
            .push("columns named by position: no recorder command given".into());
    }
    let mut series: Vec<usize> = Vec::new();
    let mut width = 0;
    for (index, raw) in text.lines().enumerate() {
        let line_no = index + 1;
        let w = words(raw.trim_end_matches('\r'));
        if w.is_empty() {
            continue;
        }
        if series.is_empty() {
            width = w.len();
            let names = column_names(recorder.as_ref(), width)
                .map_err(|why| sheet.error((line_no, 1), why))?;
            series = names
                .iter()
                .enumerate()
                .map(|(k, n)| sheet.series(n, None, (line_no, w[k + 1].1)))
                .collect();
        }
        if w.len() != width {
            let why = format!("has {} fields, but line 1 of the data has {width}", w.len());
            return Err(sheet
                .error((line_no, w.last().map_or(1, |f| f.1)), why)
                .into());
        }
        let number = |sheet: &Sheet, (text, col): (&str, usize)| {
            parse_number(text, Decimal::Point)
                .map(|x| x.0)
                .map_err(|why| sheet.error((line_no, col), why))
        };
        let t = number(&sheet, w[0])?;
        for (&s, &field) in series.iter().zip(&w[1..]) {
            let v = number(&sheet, field)?;
            sheet.push(s, t, (line_no, w[0].1), v)?;
        }
    }
    sheet.assemble(format)
}

/// The recorder command that wrote the file: `recorder`, or the one in `script`.
fn recorder(path: &Path, format: &ExternalFormat) -> Result<Option<Recorder>, InputErrors> {
    Ok(match (&format.recorder, &format.script) {
        (Some(command), _) => {
            Some(parse_recorder(command).map_err(|why| {
                InputError::new(path, "recorder", format!("\"{command}\": {why}"))
            })?)
        }
        (None, Some(script)) => Some(from_script(script, path)?),
        (None, None) => None,
    })
}

/// Whether a recorder file's bytes are `-binary` output: not UTF-8, or holding a NUL
/// (a text recorder file has neither).
pub(super) fn is_binary(bytes: &[u8]) -> bool {
    bytes.contains(&0) || std::str::from_utf8(bytes).is_err()
}

/// Read a `-binary` recorder file: its width from the recorder command where it gives it
/// (a Node recorder: the time and nodes × DOFs), its columns named as a text file's.
pub(super) fn read_binary(
    path: &Path,
    bytes: &[u8],
    format: &ExternalFormat,
) -> Result<ExternalTrace, InputErrors> {
    let recorder = recorder(path, format)?;
    if let Some(r) = &recorder {
        if !r.time {
            let why = "the recorder writes no time column: add `-time` to it";
            return Err(InputError::new(path, "recorder", why).into());
        }
    }
    let width = recorder
        .as_ref()
        .filter(|r| r.kind == "Node")
        .map(|r| 1 + r.objects.len() * r.dofs.len());
    opensees_xml::read_binary(
        path,
        bytes,
        width,
        |w| column_names(recorder.as_ref(), w),
        format,
    )
}

/// The names of a file's value columns (`width` fields a row, the time first).
fn column_names(recorder: Option<&Recorder>, width: usize) -> Result<Vec<String>, String> {
    let values = width.saturating_sub(1);
    let Some(r) = recorder else {
        return Ok((2..=width).map(|k| format!("column {k}")).collect());
    };
    if r.kind == "Node" {
        let expected = r.objects.len() * r.dofs.len();
        if values != expected {
            return Err(format!(
                "has {values} values a row, but the recorder ({} nodes × {} DOFs) writes \
                 {expected}",
                r.objects.len(),
                r.dofs.len()
            ));
        }
        let resp = &r.response;
        return Ok(r
            .objects
            .iter()
            .flat_map(|n| {
                r.dofs
                    .iter()
                    .map(move |d| format!("node {n} dof {d} {resp}"))
            })
            .collect());
    }
    let n = r.objects.len();
    if n == 0 || values % n != 0 {
        return Err(format!(
            "has {values} values a row, which {n} elements cannot share equally"
        ));
    }
    let per = values / n;
    let resp = &r.response;
    Ok(r.objects
        .iter()
        .flat_map(|e| (1..=per).map(move |k| format!("element {e} {resp} {k}")))
        .collect())
}

/// The tokens of a recorder command, Tcl (`recorder Node -file d.out …`) or OpenSeesPy
/// (`ops.recorder('Node', '-file', 'd.out', …)`), without the word `recorder`.
fn tokens(command: &str) -> Vec<String> {
    let c = command.trim();
    let inner = match (c.find("recorder("), c.rfind(')')) {
        (Some(start), Some(end)) if end > start => &c[start + 9..end],
        _ => c.strip_prefix("recorder").unwrap_or(c),
    };
    inner
        .split(|ch: char| ch == ',' || ch.is_whitespace())
        .map(|t| t.trim_matches(|ch| ch == '\'' || ch == '"').to_string())
        .filter(|t| !t.is_empty())
        .collect()
}

/// A Node or Element recorder command's columns, or the reason it is not read.
fn parse_recorder(command: &str) -> Result<Recorder, String> {
    let t = tokens(command);
    let kind = t.first().cloned().unwrap_or_default();
    if kind != "Node" && kind != "Element" {
        return Err("is not a Node or Element recorder".into());
    }
    let mut r = Recorder {
        kind,
        file: None,
        time: false,
        objects: Vec::new(),
        dofs: Vec::new(),
        response: String::new(),
    };
    let mut i = 1;
    let mut rest = Vec::new();
    while i < t.len() {
        let flag = t[i].as_str();
        // a flag's arguments: the file's name, else the numbers that follow it
        let args: Vec<&String> = if flag.starts_with("-file") || flag == "-xml" || flag == "-binary"
        {
            t.get(i + 1).into_iter().collect()
        } else {
            t[i + 1..]
                .iter()
                .take_while(|a| a.parse::<f64>().is_ok())
                .collect()
        };
        match flag {
            "-file" | "-fileCSV" | "-xml" | "-binary" => {
                r.file = args.first().map(|s| s.to_string())
            }
            "-time" => r.time = true,
            "-node" | "-ele" => r.objects = args.iter().map(|s| s.to_string()).collect(),
            "-nodeRange" | "-eleRange" => r.objects = range(&args)?,
            "-dof" => r.dofs = args.iter().map(|s| s.to_string()).collect(),
            f if f.starts_with('-') => {}
            _ => {
                rest.push(t[i].clone());
                i += 1;
                continue;
            }
        }
        i += 1 + args.len();
    }
    r.response = rest.join(" ");
    if r.objects.is_empty() {
        return Err("names no node or element (-node, -ele)".into());
    }
    if r.kind == "Node" && r.dofs.is_empty() {
        return Err("names no degree of freedom (-dof)".into());
    }
    Ok(r)
}

/// The tags `a..=b` of a `-nodeRange a b`.
fn range(args: &[&String]) -> Result<Vec<String>, String> {
    let n = |k: usize| args.get(k).and_then(|s| s.parse::<u64>().ok());
    match (n(0), n(1)) {
        (Some(a), Some(b)) if a <= b && b - a < 100_000 => {
            Ok((a..=b).map(|k| k.to_string()).collect())
        }
        _ => Err("a range needs two tags, the first not above the second".into()),
    }
}

/// The recorder command of `script` that writes the file at `data`.
fn from_script(script: &Path, data: &Path) -> Result<Recorder, InputErrors> {
    let text = read_text(script).map_err(|e| {
        InputErrors(
            e.0.into_iter()
                .map(|err| InputError {
                    field: "script".into(),
                    ..err
                })
                .collect(),
        )
    })?;
    let name = data.file_name().map(|n| n.to_string_lossy().to_string());
    let mut files = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let l = line.trim();
        if !(l.starts_with("recorder") || l.contains("recorder(")) || l.starts_with('#') {
            continue;
        }
        let Ok(r) = parse_recorder(l) else { continue };
        let file = r
            .file
            .as_deref()
            .map(|f| f.rsplit(['/', '\\']).next().unwrap_or(f));
        if file.map(str::to_string) == name {
            return Ok(r);
        }
        files.push(format!(
            "{} (line {})",
            r.file.clone().unwrap_or_default(),
            index + 1
        ));
    }
    let why = format!(
        "has no Node or Element recorder writing \"{}\"; its recorders write: {}",
        name.unwrap_or_default(),
        if files.is_empty() {
            "none".into()
        } else {
            files.join(", ")
        }
    );
    Err(InputError::new(script, "script", why).into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tcl_and_python_recorders_name_their_columns() {
        let tcl =
            parse_recorder("recorder Node -file disp.out -time -node 2 3 -dof 1 2 disp").unwrap();
        assert_eq!(
            column_names(Some(&tcl), 5).unwrap(),
            [
                "node 2 dof 1 disp",
                "node 2 dof 2 disp",
                "node 3 dof 1 disp",
                "node 3 dof 2 disp"
            ]
        );
        let py = parse_recorder(
            "ops.recorder('Element', '-file', 'f.out', '-time', '-ele', 1, 'force')",
        )
        .unwrap();
        assert_eq!(py.file.as_deref(), Some("f.out"));
        assert_eq!(
            column_names(Some(&py), 3).unwrap(),
            ["element 1 force 1", "element 1 force 2"]
        );
        assert!(
            column_names(Some(&tcl), 4)
                .unwrap_err()
                .contains("writes 4")
        );
        let xml = parse_recorder("recorder Node -xml a.xml -time -node 1 -dof 1 disp").unwrap();
        assert_eq!(xml.file.as_deref(), Some("a.xml"));
        let r =
            parse_recorder("recorder Node -file a -time -nodeRange 3 5 -dof 1 reaction").unwrap();
        assert_eq!(r.objects, ["3", "4", "5"]);
    }
}

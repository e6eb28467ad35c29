//! Document control: what identifies a report and its revision. A case report's document
//! ID from its inputs' SHA-256, the running headers of the printed case report and suite
//! summary, and the case report's control block (ID, revision, date, inputs, the fields
//! left to sign).

use super::provenance::Provenance;
use crate::doc::Block;
use rockslide_core::case::Case;

/// SHA-256 of the inputs a case run reads: the case file's text and, for a recorded
/// motion, its samples as used (after scaling, f64 little-endian) and sample interval.
fn inputs_sha256(c: &Case) -> String {
    use sha2::{Digest, Sha256};
    let mut h = Sha256::new();
    h.update(c.text.as_bytes());
    if let Some(rockslide_core::case::Signal::Record { dt, samples, .. }) =
        c.scene.excitation.signal()
    {
        h.update(dt.to_le_bytes());
        for x in samples.iter() {
            h.update(x.to_le_bytes());
        }
    }
    format!("{:x}", h.finalize())
}

/// The inputs' hash and the case file's, each once: the same hash when the case file is
/// the only input.
fn inputs_text(c: &Case, inputs: &str) -> String {
    if inputs == c.sha256 {
        return format!("sha256 {inputs} (the case file {})", c.path.display());
    }
    format!(
        "sha256 {inputs} (the case file {} with the record's samples as used; the case file alone sha256 {})",
        c.path.display(),
        c.sha256
    )
}

/// The document ID of a case report: `RS-<case>-<12 hex of the inputs' SHA-256>`.
fn document_id(c: &Case) -> String {
    format!("RS-{}-{}", c.name, &inputs_sha256(c)[..12])
}

/// The running header of a printed case report: its document ID and revision.
pub(super) fn running_header(c: &Case, prov: &Provenance) -> String {
    format!(
        "{} · {}, commit {}",
        document_id(c),
        prov.tool,
        short_commit(&prov.commit)
    )
}

/// The running header of the printed suite summary: what it is and its revision.
pub(super) fn suite_header(prov: &Provenance) -> String {
    format!(
        "rockslide verification suite · {}, commit {}",
        prov.tool,
        short_commit(&prov.commit)
    )
}

fn short_commit(commit: &str) -> &str {
    commit.get(..12).unwrap_or(commit)
}

/// The document-control block of a case report: document ID `RS-<case>-<12 hex of the
/// inputs' SHA-256>` (the same inputs give the same ID), revision (the build stamp), date,
/// the inputs' hashes, and the prepared / checked / approved fields left to sign.
pub(super) fn document_control(c: &Case, prov: &Provenance) -> Block {
    let inputs = inputs_sha256(c);
    let blank = "________________  date ________".to_string();
    Block::Facts(vec![
        ("Document ID".into(), document_id(c)),
        (
            "Revision".into(),
            format!("{}, commit {}", prov.tool, prov.commit),
        ),
        ("Date".into(), prov.date.clone()),
        ("Inputs".into(), inputs_text(c, &inputs)),
        ("Prepared by".into(), blank.clone()),
        ("Checked by".into(), blank.clone()),
        ("Approved by".into(), blank),
    ])
}

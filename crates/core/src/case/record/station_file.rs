//! A station file read by its layout: its first line tells COSMOS, CSMIP, USGS SMC and
//! GeoNet apart, and that layout's reader reads it into a [`StationRecord`].

use std::path::Path;

use crate::error::{InputError, InputErrors};

use super::cosmos::parse_cosmos;
use super::csmip::parse_csmip;
use super::file::read_text;
use super::geonet::parse_geonet;
use super::smc::parse_smc;
use super::station::StationRecord;
use super::token::at;

/// Read a station file: its layout told by its first line (COSMOS "(Format v01.20 with
/// N text lines)", CSMIP "Uncorrected Accelerogram Data" / "CORRECTED ACCELEROGRAM", SMC
/// "1 UNCORRECTED ACCELEROGRAM" / "2 CORRECTED ACCELEROGRAM", GeoNet V1A/V2A
/// "Uncorrected accelerogram … GNS Science" / "Corrected accelerogram … GNS Science").
pub fn read_station(path: &Path) -> Result<StationRecord, InputErrors> {
    let text = read_text(path)?;
    parse_station(path, &text).map_err(Into::into)
}

/// [`read_station`] from the file's text.
pub fn parse_station(path: &Path, text: &str) -> Result<StationRecord, InputError> {
    let first = text.lines().next().unwrap_or("").to_ascii_uppercase();
    let first = first.trim();
    if first.contains("TEXT LINES") && first.contains("FORMAT V") {
        parse_cosmos(path, text)
    } else if first.starts_with("1 UNCORRECTED ACCELEROGRAM")
        || first.starts_with("2 CORRECTED ACCELEROGRAM")
    {
        parse_smc(path, text)
    } else if (first.starts_with("UNCORRECTED ACCELEROGRAM")
        || first.starts_with("CORRECTED ACCELEROGRAM"))
        && first.contains("GNS SCIENCE")
    {
        parse_geonet(path, text)
    } else if first.starts_with("UNCORRECTED ACCELEROGRAM")
        || first.starts_with("CORRECTED ACCELEROGRAM")
    {
        parse_csmip(path, text)
    } else {
        Err(at(
            path,
            1,
            Some(1),
            "not a station record this program reads: expected a COSMOS file (\"… (Format v01.20 with 13 text lines)\"), a CSMIP volume (\"Uncorrected Accelerogram Data\" or \"CORRECTED ACCELEROGRAM\"), a USGS SMC file (\"2 CORRECTED ACCELEROGRAM\") or a GeoNet V1A/V2A volume (\"Uncorrected accelerogram … GNS Science\")",
        ))
    }
}

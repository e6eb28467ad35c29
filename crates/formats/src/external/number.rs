//! Numbers as programs print them: Rust's and Fortran's forms (`0.12345E-03`, `10.E-03`,
//! `1.0D-03`), and a decimal comma (`0,0012`) where the file's separator is not a comma.

/// Whether a decimal comma may stand for the decimal point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Decimal {
    /// Only `.` (the separator is a comma).
    Point,
    /// `.` or `,` (a `;`, tab or blank separator, as European exports write).
    PointOrComma,
}

impl Decimal {
    /// What a file separated by `delimiter` may use.
    pub(super) fn for_delimiter(delimiter: char) -> Self {
        if delimiter == ',' {
            Decimal::Point
        } else {
            Decimal::PointOrComma
        }
    }
}

/// A field read as a finite number: `Ok((value, read_a_decimal_comma))`, or the reason.
pub(super) fn parse_number(text: &str, decimal: Decimal) -> Result<(f64, bool), String> {
    let s = text.trim();
    if s.is_empty() {
        return Err("empty value (a missing value is not zero)".into());
    }
    let comma = decimal == Decimal::PointOrComma && s.contains(',') && !s.contains('.');
    let fortran_double = s.contains(['d', 'D']);
    let parsed = if comma || fortran_double {
        s.replacen(',', ".", 1)
            .replace(['d', 'D'], "e")
            .parse::<f64>()
    } else {
        s.parse::<f64>()
    };
    match parsed {
        Ok(x) if x.is_finite() => Ok((x, comma)),
        Ok(_) => Err(format!("\"{s}\" is not a finite number")),
        Err(_) => Err(format!("\"{s}\" is not a number")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn program_forms_and_decimal_commas() {
        let n = |s| parse_number(s, Decimal::PointOrComma);
        assert_eq!(n("0.12345E-03"), Ok((0.00012345, false)));
        assert_eq!(n("10.E-03"), Ok((0.01, false)));
        assert_eq!(n("1.0D-03"), Ok((0.001, false)));
        assert_eq!(n("-0,0012"), Ok((-0.0012, true)));
        assert_eq!(n("1,5E-3"), Ok((0.0015, true)));
        assert!(n("1,000.5").is_err());
        assert_eq!(n("inf"), Err("\"inf\" is not a finite number".into()));
        assert!(parse_number("0,5", Decimal::Point).is_err());
        assert!(n(" ").unwrap_err().contains("missing value is not zero"));
    }
}

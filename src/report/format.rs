//! Number formatting shared by the Markdown, HTML and CSV renderers, so that a value reads
//! the same in every output: display units of the paper (kN, mm), 4 significant digits.

use crate::analysis::quantity_def;

/// A value of response quantity `key` in its display unit, 4 significant digits.
pub(crate) fn show(key: &str, si: f64) -> String {
    let (_, f) = display_unit(key);
    sig(si * f)
}

/// Display unit and factor from SI of a response quantity (`("mm", 1e3)`).
pub(crate) fn display_unit(key: &str) -> (&'static str, f64) {
    quantity_def(key).map_or(("", 1.0), |d| d.display())
}

/// 4 significant digits, scientific notation outside [1e-3, 1e5).
pub(crate) fn sig(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if !x.is_finite() {
        format!("{x}")
    } else if x.abs() >= 1e5 || x.abs() < 1e-3 {
        format!("{x:.3e}")
    } else {
        let digits = (3 - x.abs().log10().floor() as i32).max(0) as usize;
        format!("{x:.digits$}")
    }
}

/// A signed percentage with two decimals, `—` when undefined.
pub(crate) fn pct(p: Option<f64>) -> String {
    p.map_or("—".into(), |p| format!("{p:+.2} %"))
}

/// A ratio (normalised difference) in scientific notation, `—` when undefined.
pub(crate) fn ratio(x: Option<f64>) -> String {
    x.map_or("—".into(), |x| format!("{x:.3e}"))
}

/// Escape text for HTML element content and attribute values.
pub(crate) fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// Escape the pipe in Markdown table cells.
pub(crate) fn md_cell(s: &str) -> String {
    s.replace('|', "\\|")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_significant_digits() {
        assert_eq!(sig(9.2063), "9.206");
        assert_eq!(sig(500.0), "500.0");
        assert_eq!(sig(0.0628718), "0.06287");
        assert_eq!(sig(1.5e6), "1.500e6");
    }

    #[test]
    fn html_escapes_markup() {
        assert_eq!(esc("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}

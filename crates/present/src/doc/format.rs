//! Number formatting shared by the Markdown, HTML and CSV renderers, so that a value reads
//! the same in every output: display units of the paper (kN, mm), 4 significant digits.

pub(crate) use rockslide_core::response::{display_unit, show, sig};

/// A signed percentage with two decimals, `—` when undefined.
pub(crate) fn pct(p: Option<f64>) -> String {
    p.map_or("—".into(), |p| format!("{p:+.2} %"))
}

/// A ratio (normalised difference) in scientific notation, `—` when undefined.
pub(crate) fn ratio(x: Option<f64>) -> String {
    x.map_or("—".into(), |x| format!("{x:.3e}"))
}

/// A number in engineering notation with 3 decimals, `—` when absent.
pub(crate) fn sci(x: Option<f64>) -> String {
    x.map_or("—".into(), |v| format!("{v:.3e}"))
}

/// An order of accuracy with `digits` decimals, `—` when there is none.
pub(crate) fn order(p: Option<f64>, digits: usize) -> String {
    p.map_or("—".into(), |p| format!("{p:.digits$}"))
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

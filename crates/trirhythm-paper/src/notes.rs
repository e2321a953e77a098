//! Text that travels with a figure's data: its caption (what it shows, the shared parameters,
//! the formula variant, the choices made where the paper is silent) and the notes of its data
//! table (parameters per panel, methods, verdicts), and the number formats they use.
//!
//! Nothing here is a picture: a caption is the words a report or a plot puts beside the
//! numbers, and the CLI draws it above its PNG/SVG.

use crate::FigureOptions;
use serde::{Deserialize, Serialize};
use trirhythm::model::Params;
use trirhythm::theory::averaging::Variant;

/// A figure's caption: a one-line title and lines giving the shared parameters, the formula
/// variant and the choices the project made where the paper is silent.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Caption {
    /// "Fig. N: what it shows".
    pub title: String,
    /// Parameters, variant, choices, one statement per line.
    pub lines: Vec<String>,
}

/// Notes for a figure's data table: title, variant, then each note as `note: …`.
pub fn table_notes(n: u32, title: &str, options: &FigureOptions, notes: &[String]) -> Vec<String> {
    let mut h = vec![
        format!("trirhythm figure {n}: {title}"),
        format!("variant: {}", options.variant.name()),
    ];
    h.extend(notes.iter().map(|s| format!("note: {s}")));
    h
}

/// A panel's parameters as one note.
pub fn panel_line(label: &str, p: &Params) -> String {
    format!("panel {label}: {}", p.describe())
}

/// The formula variant in words: a `--variant consistent` figure says so in its caption.
pub fn variant_line(v: Variant) -> String {
    match v {
        Variant::Paper => {
            "averaged theory: the paper's formulas as printed, typos fixed (--variant paper)".into()
        }
        Variant::Consistent => {
            "averaged theory: CONSISTENT variant — exact impact loss ω1A ln r/π, \
                                coloured noise through sgn Z (--variant consistent)"
                .into()
        }
    }
}

/// The user-facing symbol of a parameter key.
pub fn symbol(key: &str) -> &str {
    match key {
        "mu0" => "μ0",
        "omega0" => "ω0",
        "lambda" => "λ",
        "alpha0" => "α0",
        "beta0" => "β0",
        "gamma0" => "γ0",
        "delta0" => "δ0",
        "tau" => "τ",
        k => k,
    }
}

/// "μ0 = 0.01, ω0 = 1, …" for the keys of `p` not in `varying` (those the panels set).
pub fn params_text(p: &Params, varying: &[&str]) -> String {
    p.key_values()
        .into_iter()
        .filter(|(k, _)| !varying.contains(&k.as_str()))
        .map(|(k, v)| format!("{} = {}", symbol(&k), trirhythm::error::Exact(v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A figure's caption: "Fig. N: title", the shared parameters (what the panels vary named),
/// the formula variant, then `extra` lines (choices where the paper is silent, methods).
pub fn caption(
    n: u32,
    title: &str,
    options: &FigureOptions,
    base: &Params,
    varying: &[&str],
    extra: Vec<String>,
) -> Caption {
    let mut lines = vec![format!(
        "{}{}",
        params_text(base, varying),
        if varying.is_empty() {
            String::new()
        } else {
            format!(
                "; per panel: {}",
                varying
                    .iter()
                    .map(|k| symbol(k))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }
    )];
    lines.push(variant_line(options.variant));
    lines.extend(extra);
    Caption {
        title: format!("Fig. {n}: {title}"),
        lines,
    }
}

/// A number in its shortest round-trip form (the data tables' cells): −0 as 0, non-finite
/// values as `nan`, `inf`, `-inf`.
pub fn num(v: f64) -> String {
    let v = v + 0.0; // −0 prints as 0
    if v.is_nan() {
        "nan".into()
    } else if v == f64::NEG_INFINITY {
        "-inf".into()
    } else if v == f64::INFINITY {
        "inf".into()
    } else {
        // shortest round-trip digits; exponent notation where plain digits would run long
        trirhythm::error::Exact(v).to_string()
    }
}

/// A number for prose (notes, messages) to `digits` significant digits, trailing zeros dropped:
/// 0.40800000000000003 → "0.408", −3.6500952558839547e-4 → "-0.000365" (at 3), exponent
/// notation outside [1e-4, 1e9); in words where the number is not finite: "undefined" for
/// NaN, "∞" and "−∞" (prose never prints `nan`). Data cells use [`num`] (round-trip) instead.
pub fn sig(v: f64, digits: usize) -> String {
    let v = v + 0.0;
    let a = v.abs();
    if v.is_nan() {
        return "undefined".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "∞" } else { "−∞" }.into();
    }
    if v == 0.0 {
        return num(v);
    }
    let digits = digits.max(1);
    let trim = |t: &str| -> String {
        if t.contains('.') {
            t.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            t.to_string()
        }
    };
    if (1e-4..1e9).contains(&a) {
        // round first, then count the decimals: 9.9996 at 4 digits is 10.00, not 9.9996
        let rounded: f64 = format!("{:.*e}", digits - 1, v).parse().unwrap_or(v);
        let exponent = rounded.abs().log10().floor() as i32;
        let decimals = (digits as i32 - 1 - exponent).max(0) as usize;
        trim(&format!("{rounded:.decimals$}"))
    } else {
        let t = format!("{:.*e}", digits - 1, v);
        match t.split_once('e') {
            Some((m, e)) => format!("{}e{e}", trim(m)),
            None => t,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::sig;

    #[test]
    fn significant_digits_for_prose() {
        assert_eq!(sig(0.40800000000000003, 4), "0.408");
        assert_eq!(sig(-0.00036500952558839547, 3), "-0.000365");
        assert_eq!(sig(0.0002654057820450608, 2), "0.00027");
        assert_eq!(sig(1.9901309893509918, 4), "1.99");
        assert_eq!(sig(9.99996, 4), "10");
        assert_eq!(sig(1234567.0, 3), "1230000");
        assert_eq!(sig(-6.913418236253023e-5, 3), "-6.91e-5");
        assert_eq!(sig(2.5e12, 2), "2.5e12");
        assert_eq!(sig(0.0, 3), "0");
        assert_eq!(sig(-0.0, 3), "0");
        // prose never prints `nan`: non-finite numbers in words
        assert_eq!(sig(f64::NAN, 3), "undefined");
        assert_eq!(sig(f64::INFINITY, 3), "∞");
        assert_eq!(sig(f64::NEG_INFINITY, 3), "−∞");
        assert_eq!(sig(2.0, 4), "2");
    }
}

//! JSON documents: numbers that refuse to be non-finite ([`jnum`]), the parameters, and
//! [`emit`], which writes a document (or any text) to a file or standard output.

use anyhow::Result;
use std::path::Path;
use trirhythm::model::Params;

thread_local! {
    /// Non-finite numbers met by [`jnum`] since the last [`emit`].
    static NONFINITE_JSON: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// Write `text` to `out` (atomically) or to standard output, unless [`jnum`] met a non-finite
/// number since the last call.
pub fn emit(out: Option<&Path>, text: &str) -> Result<()> {
    let bad_numbers = NONFINITE_JSON.with(|c| c.replace(0));
    if bad_numbers > 0 {
        let place = serde_json::from_str::<serde_json::Value>(text)
            .ok()
            .and_then(|doc| first_marked(&doc, String::new()))
            .map(|at| format!(", the first at {at}"))
            .unwrap_or_default();
        anyhow::bail!(
            "the computation produced {bad_numbers} non-finite value(s){place} (overflow or an \
             undefined quantity); nothing written"
        );
    }
    match out {
        Some(path) => super::files::write_atomic(path, text.as_bytes()),
        None => super::files::stdout_write(text.as_bytes()),
    }
}

/// What [`jnum`] puts in place of a non-finite number: a string no document holds, so that
/// [`emit`] can name where the first one is.
const NONFINITE_MARK: &str = "\u{1}non-finite";

/// The place of the first [`NONFINITE_MARK`] in a document: `field.sub[row]`.
fn first_marked(v: &serde_json::Value, at: String) -> Option<String> {
    match v {
        serde_json::Value::String(s) if s.starts_with(NONFINITE_MARK) => {
            let value = &s[NONFINITE_MARK.len()..];
            Some(format!(
                "{} (value {value})",
                if at.is_empty() { "the top" } else { &at }
            ))
        }
        serde_json::Value::Array(items) => items
            .iter()
            .enumerate()
            .find_map(|(i, x)| first_marked(x, format!("{at}[{i}]"))),
        serde_json::Value::Object(fields) => fields.iter().find_map(|(k, x)| {
            let path = if at.is_empty() {
                k.clone()
            } else {
                format!("{at}.{k}")
            };
            first_marked(x, path)
        }),
        _ => None,
    }
}

/// A JSON number; a non-finite value is counted and marked, so that [`emit`] refuses the
/// document and names the field and row of the first one.
pub fn jnum(v: f64) -> serde_json::Value {
    match serde_json::Number::from_f64(v) {
        Some(n) => serde_json::Value::Number(n),
        None => {
            NONFINITE_JSON.with(|c| c.set(c.get() + 1));
            serde_json::Value::String(format!("{NONFINITE_MARK}{v}"))
        }
    }
}

/// A JSON number that may be ±∞ as a limit (log p where p = 0, U_eff at A = 0): the string
/// `"inf"` or `"-inf"` there, as the library's serde writes every non-finite number
/// (`trirhythm::non_finite`), so that one rule holds in every JSON document; NaN is still
/// counted by [`jnum`].
pub fn jlimit(v: f64) -> serde_json::Value {
    match v {
        f64::INFINITY => serde_json::Value::String("inf".into()),
        f64::NEG_INFINITY => serde_json::Value::String("-inf".into()),
        _ => jnum(v),
    }
}

/// The parameters as a JSON object in key order.
pub fn params_json(p: &Params) -> serde_json::Value {
    let mut m = serde_json::Map::new();
    for (k, v) in p.key_values() {
        m.insert(k, jnum(v));
    }
    serde_json::Value::Object(m)
}

/// A list of JSON numbers ([`jnum`] each).
pub fn jvec(v: &[f64]) -> serde_json::Value {
    serde_json::Value::Array(v.iter().map(|&x| jnum(x)).collect())
}

/// A document as indented JSON with a final newline.
pub fn pretty<T: serde::Serialize>(doc: &T) -> Result<String> {
    Ok(serde_json::to_string_pretty(doc)? + "\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_non_finite_number_is_refused_with_its_field_and_row() {
        let doc = serde_json::json!({
            "params": {"D": jnum(0.1)},
            "A": [jnum(1.0), jnum(2.0)],
            "p": [jnum(0.5), jnum(f64::INFINITY), jnum(f64::NAN)],
        });
        let err = emit(None, &doc.to_string()).unwrap_err().to_string();
        assert!(err.contains("2 non-finite value(s)"), "{err}");
        assert!(err.contains("the first at p[1] (value inf)"), "{err}");
        // the count is reset: a clean document is written
        let clean = serde_json::json!({"A": [jnum(1.0)]});
        assert_eq!(NONFINITE_JSON.with(|c| c.get()), 0);
        assert!(first_marked(&clean, String::new()).is_none());
    }
}

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
        anyhow::bail!(
            "the computation produced {bad_numbers} non-finite value(s) (overflow or an undefined \
             quantity); nothing written"
        );
    }
    match out {
        Some(path) => super::files::write_atomic(path, text.as_bytes()),
        None => super::files::stdout_write(text.as_bytes()),
    }
}

/// A JSON number; a non-finite value becomes `null` and is counted, so that [`emit`] refuses
/// the document.
pub fn jnum(v: f64) -> serde_json::Value {
    match serde_json::Number::from_f64(v) {
        Some(n) => serde_json::Value::Number(n),
        None => {
            NONFINITE_JSON.with(|c| c.set(c.get() + 1));
            serde_json::Value::Null
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

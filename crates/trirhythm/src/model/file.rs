//! The model file: TOML text ↔ [`Model`], with errors naming the dotted field.
//!
//! Form: `format = 1`, then the tables `leading`, `damping`, `restoring` (required) and
//! `fractional`, `wall`, `forcing`, `noise`, `start` (optional), every field documented in
//! `docs/model-file.md`. Unknown fields are refused (`deny_unknown_fields`).
//!
//! Method: the text is parsed to a TOML table, `format` checked and removed, the rest
//! deserialised through `serde_path_to_error`, so that a missing, unknown or mistyped field is
//! reported by its dotted path ([`Error::Malformed`]); then [`Model::validate`] checks ranges
//! and cross-field rules ([`Error::InvalidParameter`] with the dotted field). [`Model::to_toml`]
//! writes a commented file with every float in shortest round-trip form, so that
//! `from_toml_str(to_toml(m)) == m` bit for bit.
//!
//! Reference: TOML v1.0 (toml.io); `docs/model-file.md`.
//!
//! Tests: `tests/model_file.rs` (round trip of every preset and of a model using every term;
//! malformed files each refused with the field named).

use super::class::Model;
use super::terms::{Keep, Restitution};
use crate::error::{Error, Result};

/// The file format this program reads and writes.
pub const FORMAT: i64 = 1;

fn malformed(field: impl Into<String>, detail: impl Into<String>) -> Error {
    Error::Malformed {
        field: field.into(),
        detail: detail.into(),
    }
}

impl Model {
    /// Read and validate a model file's text.
    pub fn from_toml_str(text: &str) -> Result<Model> {
        let mut table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
            let at = match e.span() {
                Some(span) => {
                    let line = text[..span.start.min(text.len())].matches('\n').count() + 1;
                    format!(" (line {line})")
                }
                None => String::new(),
            };
            malformed("(syntax)", format!("{}{at}", e.message().trim()))
        })?;
        match table.remove("format") {
            None => {
                return Err(malformed(
                    "format",
                    format!("missing: a model file opens with `format = {FORMAT}`"),
                ))
            }
            Some(toml::Value::Integer(FORMAT)) => {}
            Some(other) => {
                let shown = match other {
                    toml::Value::Integer(i) => i.to_string(),
                    toml::Value::Float(x) => float(x),
                    toml::Value::String(s) => format!("{s:?}"),
                    other => format!("a {}", other.type_str()),
                };
                return Err(malformed(
                    "format",
                    format!("= {shown}: this program reads format {FORMAT} only"),
                ));
            }
        }
        Model::from_tables(toml::Value::Table(table))
    }

    /// A model from its tables through any serde deserializer (the Python front end passes
    /// JSON), without the `format` key; validated. Errors name the dotted field.
    pub fn from_tables<'de, D: serde::Deserializer<'de>>(tables: D) -> Result<Model>
    where
        D::Error: std::fmt::Display,
    {
        let model: Model = serde_path_to_error::deserialize(tables).map_err(|e| {
            let path: Vec<String> = e
                .path()
                .iter()
                .filter_map(|s| {
                    use serde_path_to_error::Segment as S;
                    match s {
                        S::Seq { index } => Some(index.to_string()),
                        S::Map { key } => Some(key.clone()),
                        S::Enum { variant } => Some(variant.clone()),
                        S::Unknown => None,
                    }
                })
                .collect();
            let message = e.inner().to_string();
            let message = message.lines().next().unwrap_or("").trim().to_string();
            // name the missing or unknown field itself, not only its table
            let named = ["missing field `", "unknown field `"]
                .iter()
                .find_map(|p| message.strip_prefix(p))
                .and_then(|rest| rest.split('`').next())
                .map(str::to_string);
            let mut field = path.join(".");
            if let Some(name) = named.filter(|n| path.last() != Some(n)) {
                if !field.is_empty() {
                    field.push('.');
                }
                field.push_str(&name);
            }
            if field.is_empty() {
                field = "(top level)".into();
            }
            let detail = if message.starts_with("data did not match any variant") {
                "expected a number r ∈ [0, 1] or a table { r0, r_fast, speed }".to_string()
            } else {
                message
            };
            malformed(field, detail)
        })?;
        model.validate()?;
        Ok(model)
    }

    /// The model as a commented model file (`format = 1` first), every float in shortest
    /// round-trip form: [`Model::from_toml_str`] reads it back to the same bits.
    pub fn to_toml(&self) -> String {
        let mut s = String::new();
        let mut line = |l: String| {
            s.push_str(&l);
            s.push('\n');
        };
        line(format!("format = {FORMAT}"));
        line(String::new());
        line("# D^{1+lambda}U, lambda in (0, 1] (lambda = 1: the second derivative)".into());
        line("[leading]".into());
        line(format!("lambda = {}", float(self.leading.lambda)));
        line(String::new());
        line("# h(U, U') = mu0*P(U) + sum_k rayleigh[k-1]*U'^(2k) in the term -h*U'; P(U) = sum_k coefficients[k]*U^(2k)".into());
        line("[damping]".into());
        line(format!("mu0 = {}", float(self.damping.mu0)));
        line(format!(
            "coefficients = {}",
            floats(&self.damping.coefficients)
        ));
        line(format!("rayleigh = {}", floats(&self.damping.rayleigh)));
        line(String::new());
        line("# k(U) = omega0^2*U + cubic*U^3 + quintic*U^5".into());
        line("[restoring]".into());
        line(format!("omega0 = {}", float(self.restoring.omega0)));
        line(format!("cubic = {}", float(self.restoring.cubic)));
        line(format!("quintic = {}", float(self.restoring.quintic)));
        line(String::new());
        line(
            "# fractional terms K*D^alpha U (at most two): [[fractional]] coefficient, order"
                .into(),
        );
        for f in &self.fractional {
            line("[[fractional]]".into());
            line(format!("coefficient = {}", float(f.coefficient)));
            line(format!("order = {}", float(f.order)));
        }
        line(String::new());
        line("# walls (none, one, or two: lower keep = \"above\", then upper keep = \"below\"); impact U'+ = -r*U'-,".into());
        line("# restitution = r, or { r0, r_fast, speed }: r(v) = r_fast + (r0 - r_fast)*exp(-v/speed), v = |U'-|".into());
        for w in &self.walls {
            line("[[wall]]".into());
            line(format!("position = {}", float(w.position)));
            line(format!(
                "keep = \"{}\"",
                match w.keep {
                    Keep::Above => "above",
                    Keep::Below => "below",
                }
            ));
            match w.restitution {
                Restitution::Constant(r) => line(format!("restitution = {}", float(r))),
                Restitution::Speed(v) => line(format!(
                    "restitution = {{ r0 = {}, r_fast = {}, speed = {} }}",
                    float(v.r0),
                    float(v.r_fast),
                    float(v.speed)
                )),
            }
        }
        line(String::new());
        line(
            "# harmonic forcing F*cos(Omega*t + phi): [forcing] amplitude, frequency, phase".into(),
        );
        if let Some(f) = &self.forcing {
            line("[forcing]".into());
            line(format!("amplitude = {}", float(f.amplitude)));
            line(format!("frequency = {}", float(f.frequency)));
            line(format!("phase = {}", float(f.phase)));
        }
        line(String::new());
        line("# noises: white (correlation_time = 0): <eta(t)eta(s)> = 2*D*delta(t-s);".into());
        line(
            "# Ornstein-Uhlenbeck (correlation_time = tau > 0): <eta(t)eta(s)> = (D/tau)*exp(-|t-s|/tau)"
                .into(),
        );
        line(
            "# additive eta_a, multiplicative eta_m (the term U*eta_m), correlation c in [-1, 1]"
                .into(),
        );
        line("[noise]".into());
        line(format!("correlation = {}", float(self.noise.correlation)));
        for (name, n) in [
            ("additive", &self.noise.additive),
            ("multiplicative", &self.noise.multiplicative),
        ] {
            if let Some(n) = n {
                line(String::new());
                line(format!("[noise.{name}]"));
                line(format!("intensity = {}", float(n.intensity)));
                line(format!("correlation_time = {}", float(n.correlation_time)));
            }
        }
        line(String::new());
        line("# the start (U(0), U'(0))".into());
        line("[start]".into());
        line(format!("u0 = {}", float(self.start.u0)));
        line(format!("v0 = {}", float(self.start.v0)));
        s
    }
}

/// A finite float as a TOML float in shortest round-trip digits (`1.0`, `2.13e-7`).
fn float(x: f64) -> String {
    let s = crate::error::Exact(x).to_string();
    if s.contains(['.', 'e', 'E']) || !x.is_finite() {
        s
    } else {
        format!("{s}.0")
    }
}

fn floats(xs: &[f64]) -> String {
    format!(
        "[{}]",
        xs.iter().map(|&x| float(x)).collect::<Vec<_>>().join(", ")
    )
}

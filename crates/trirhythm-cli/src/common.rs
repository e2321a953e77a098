//! Argument handling shared by every command: parameters, formats, grids, atomic output.

use anyhow::Result;
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};
use trirhythm::model::{preset, Params};
use trirhythm::theory::averaging::Variant;

/// Bad input from the user: exit status 2.
#[derive(Debug)]
pub struct BadInput(pub String);

impl std::fmt::Display for BadInput {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for BadInput {}

/// Return a [`BadInput`] error.
pub fn bad<T>(msg: impl Into<String>) -> Result<T> {
    Err(BadInput(msg.into()).into())
}

/// Whether an error chain is the user's fault (bad parameter, unknown name, undefined quantity).
pub fn is_bad_input(err: &anyhow::Error) -> bool {
    err.chain().any(|e| {
        e.downcast_ref::<BadInput>().is_some()
            || matches!(
                e.downcast_ref::<trirhythm::Error>(),
                Some(
                    trirhythm::Error::InvalidParameter { .. }
                        | trirhythm::Error::Unknown { .. }
                        | trirhythm::Error::Undefined { .. }
                )
            )
    })
}

/// `paper` or `consistent` (see the `averaging` module).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum VariantArg {
    /// The paper's formulas as printed (Eq. 27's typo fixed).
    #[default]
    Paper,
    /// The corrected formulas (exact impact loss, coloured noise through sgn Z).
    Consistent,
}

impl From<VariantArg> for Variant {
    fn from(v: VariantArg) -> Self {
        match v {
            VariantArg::Paper => Variant::Paper,
            VariantArg::Consistent => Variant::Consistent,
        }
    }
}

/// Parameter selection: a preset, then `--param KEY=VALUE` overrides.
#[derive(Debug, Clone, Args)]
pub struct ParamArgs {
    /// A figure's parameter set (e.g. fig4c); without it, Fig. 4(c)'s set with r = 1, D = 0, τ = 0.
    #[arg(long)]
    pub preset: Option<String>,
    /// Override a parameter: KEY=VALUE with KEY in mu0 omega0 lambda r alpha0 beta0 gamma0
    /// delta0 D tau, or `c<k>` for the coefficient of U^(2k) (repeatable).
    #[arg(long = "param", value_name = "KEY=VALUE")]
    pub params: Vec<String>,
    /// Formula variant of the averaged theory.
    #[arg(long, value_enum, default_value_t = VariantArg::Paper)]
    pub variant: VariantArg,
}

impl ParamArgs {
    /// The validated parameters.
    pub fn resolve(&self) -> Result<Params> {
        let mut p = match &self.preset {
            Some(name) => preset(name)?.params,
            None => Params::default(),
        };
        for kv in &self.params {
            let Some((k, v)) = kv.split_once('=') else {
                return bad(format!("--param expects KEY=VALUE, got `{kv}`"));
            };
            let value: f64 = match v.trim().parse() {
                Ok(x) => x,
                Err(_) => {
                    return bad(format!(
                        "invalid value for parameter {}: `{v}` is not a number",
                        k.trim()
                    ))
                }
            };
            p.set(k.trim(), value)?;
        }
        p.validate()?;
        Ok(p)
    }

    /// The variant as the library's type.
    pub fn variant(&self) -> Variant {
        self.variant.into()
    }
}

/// Output format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum Format {
    /// Aligned text for reading.
    #[default]
    Table,
    /// JSON object.
    Json,
    /// Comma-separated values with a `#` header.
    Csv,
}

/// Output selection.
#[derive(Debug, Clone, Args)]
pub struct OutputArgs {
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Write to this file (atomically) instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

impl OutputArgs {
    /// Emit `text` to the chosen destination, refusing a document with non-finite JSON
    /// numbers (tables and CSV check their own cells).
    pub fn emit(&self, text: &str) -> Result<()> {
        emit(self.out.as_deref(), text)
    }
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
        Some(path) => crate::output::write_atomic(path, text.as_bytes()),
        None => crate::output::stdout_write(text.as_bytes()),
    }
}

/// A grid `START:STOP:COUNT` of `COUNT` equally spaced points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// First point.
    pub start: f64,
    /// Last point.
    pub stop: f64,
    /// Number of points (≥ 2).
    pub count: usize,
}

impl Grid {
    /// Parse `START:STOP:COUNT`; `what` names the flag in errors.
    pub fn parse(s: &str, what: &str) -> Result<Grid> {
        let parts: Vec<&str> = s.split(':').collect();
        if parts.len() != 3 {
            return bad(format!("{what} expects START:STOP:COUNT, got `{s}`"));
        }
        let num = |t: &str| -> Result<f64> {
            match t.trim().parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => bad(format!("{what}: `{t}` is not a finite number (in `{s}`)")),
            }
        };
        let (start, stop) = (num(parts[0])?, num(parts[1])?);
        let count: usize = match parts[2].trim().parse() {
            Ok(c) if (2..=10_000_000).contains(&c) => c,
            _ => {
                return bad(format!(
                    "{what}: COUNT = `{}` must be an integer in [2, 10000000]",
                    parts[2]
                ))
            }
        };
        if start >= stop {
            return bad(format!(
                "{what}: START = {start} must be below STOP = {stop}"
            ));
        }
        Ok(Grid { start, stop, count })
    }

    /// The points.
    pub fn points(&self) -> Vec<f64> {
        let h = (self.stop - self.start) / (self.count - 1) as f64;
        (0..self.count).map(|i| self.start + h * i as f64).collect()
    }
}

thread_local! {
    /// Non-finite numbers met by [`jnum`] since the last [`emit`].
    static NONFINITE_JSON: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// The first non-finite cell of a table or CSV document, and how many there are.
#[derive(Default)]
struct NonFinite {
    first: Option<(String, usize, String, String)>,
    count: usize,
    /// Columns where ±∞ is a value (a limit: log p where p = 0, U_eff at A = 0).
    infinity_ok: Vec<String>,
}

impl NonFinite {
    /// Look at one row of cells (formatted by [`num`]).
    fn scan(&mut self, columns: &[String], row: usize, cells: &[String]) {
        for (i, c) in cells.iter().enumerate() {
            let ok = (c == "-inf" || c == "inf")
                && columns
                    .get(i)
                    .is_some_and(|name| self.infinity_ok.contains(name));
            if !ok && matches!(c.as_str(), "nan" | "inf" | "-inf" | "NaN") {
                self.count += 1;
                if self.first.is_none() {
                    let col = columns.get(i).cloned().unwrap_or_default();
                    let lead = format!(
                        "{} = {}",
                        columns.first().cloned().unwrap_or_default(),
                        cells.first().cloned().unwrap_or_default()
                    );
                    self.first = Some((col, row, lead, c.clone()));
                }
            }
        }
    }

    /// An error naming where, if any.
    fn check(&self) -> Result<()> {
        match &self.first {
            None => Ok(()),
            Some((col, row, lead, v)) => anyhow::bail!(
                "the computation produced a non-finite value: column {col} = {v} at row {row} \
                 ({lead}), {} such value(s) in all (overflow or an undefined quantity); nothing \
                 written",
                self.count
            ),
        }
    }
}

/// A CSV document: `#` comment lines, a header row, rows of numbers.
pub struct Csv {
    text: String,
    columns: Vec<String>,
    rows: usize,
    nonfinite: NonFinite,
}

impl Csv {
    /// Start with comment lines (each prefixed by `# `) and the column names.
    pub fn new(comments: &[String], columns: &[&str]) -> Csv {
        let mut text = String::new();
        for c in comments {
            for line in c.lines() {
                text.push_str("# ");
                text.push_str(line);
                text.push('\n');
            }
        }
        text.push_str(&columns.join(","));
        text.push('\n');
        Csv {
            text,
            columns: columns.iter().map(|c| c.to_string()).collect(),
            rows: 0,
            nonfinite: NonFinite::default(),
        }
    }

    /// Let `column` hold ±∞ where that is the value (a limit such as log 0): written as
    /// `inf`/`-inf`, not refused; NaN still is.
    pub fn allow_infinity(mut self, column: &str) -> Csv {
        self.nonfinite.infinity_ok.push(column.to_string());
        self
    }

    /// Append a row of cells (already formatted).
    pub fn row<I: IntoIterator<Item = String>>(&mut self, cells: I) {
        let cells: Vec<String> = cells.into_iter().collect();
        self.rows += 1;
        self.nonfinite.scan(&self.columns, self.rows, &cells);
        self.text.push_str(&cells.join(","));
        self.text.push('\n');
    }

    /// The document, or an error naming the first non-finite cell.
    pub fn finish(self) -> Result<String> {
        self.nonfinite.check()?;
        Ok(self.text)
    }
}

/// Numbers for CSV cells (round-trip) and prose (significant digits): the paper crate's.
pub use trirhythm_paper::notes::{num, sig};

/// A table cell with `digits` decimals, in exponent notation outside [1e-4, 1e9) so that no
/// cell runs to hundreds of digits or rounds a small value to 0.
pub fn fixed(v: f64, digits: usize) -> String {
    let v = v + 0.0;
    let a = v.abs();
    if !v.is_finite() {
        num(v)
    } else if v == 0.0 || (1e-4..1e9).contains(&a) {
        format!("{v:.digits$}")
    } else {
        format!("{v:.digits$e}")
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

/// A JSON number that may be ±∞ as a limit (log p where p = 0, U_eff at A = 0): `null` there
/// (documented, not an error); NaN is still counted by [`jnum`].
pub fn jlimit(v: f64) -> serde_json::Value {
    if v.is_infinite() {
        serde_json::Value::Null
    } else {
        jnum(v)
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

/// An aligned text table, or an error naming its first non-finite cell (±∞ is allowed in the
/// columns named in `infinite`, where it is the value).
pub fn table(columns: &[&str], rows: &[Vec<String>], infinite: &[&str]) -> Result<String> {
    let mut nonfinite = NonFinite {
        infinity_ok: infinite.iter().map(|c| c.to_string()).collect(),
        ..Default::default()
    };
    let names: Vec<String> = columns.iter().map(|c| c.to_string()).collect();
    for (i, r) in rows.iter().enumerate() {
        nonfinite.scan(&names, i + 1, r);
    }
    nonfinite.check()?;
    let mut widths: Vec<usize> = columns.iter().map(|c| c.chars().count()).collect();
    for r in rows {
        for (i, cell) in r.iter().enumerate() {
            widths[i] = widths[i].max(cell.chars().count());
        }
    }
    let fmt_row = |cells: &mut dyn Iterator<Item = &str>| -> String {
        let mut line = cells
            .enumerate()
            .map(|(i, c)| format!("{:>w$}", c, w = widths[i]))
            .collect::<Vec<_>>()
            .join("  ");
        line.push('\n');
        line
    };
    let mut out = fmt_row(&mut columns.iter().copied());
    for r in rows {
        out.push_str(&fmt_row(&mut r.iter().map(|s| s.as_str())));
    }
    Ok(out)
}

/// A progress bar on a terminal, hidden otherwise.
/// A library call's monitor that hands its progress (done, total) to a closure (which moves a
/// progress bar).
pub struct Report<F>(pub F);

impl<T: ?Sized, F: Fn(u64, u64) + Sync> trirhythm::monitor::Monitor<T> for Report<F> {
    fn progress(&self, done: u64, total: u64) {
        (self.0)(done, total)
    }
}

pub fn progress(len: u64, message: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} ({eta})")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_message(message.to_string());
    bar
}

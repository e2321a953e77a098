//! A paper figure's files, shared by `trirhythm figure` and `trirhythm report`: compute the
//! figure (or read its `figNN.json` back), write its tables as CSV, its data as JSON when
//! asked, and its picture as PNG + SVG with the verdicts on the claims resting on it drawn
//! under the heading.
//!
//! Method: the data is a `trirhythm_paper` figure value ([`trirhythm_paper::Figure`]); its
//! verdicts come from [`judge_figure`] (the figure's data alone, with the options it was
//! computed with), its caption from the picture's [`Heading`]. A report also collects the data
//! in a [`Figures`] value to judge every claim at once ([`Made`] carries what it shows).
//!
//! Tests: `tests/figure_data.rs` (JSON round trip, `--from-data` byte-identical),
//! `tests/pictures.rs`, `tests/report.rs`.

use crate::error::{bad, is_bad_input};
use crate::io::progress::Bar;
use crate::io::{write_atomic, Csv, TemporaryDir};
use crate::render::plot::{save, Heading, Picture, VerdictLine};
use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use trirhythm::profile::Profile;
use trirhythm::theory::averaging::Variant;
use trirhythm_paper::notes::sig;
use trirhythm_paper::table::Table;
use trirhythm_paper::verdict::claims::{judge_figure, ClaimVerdict, Figures, Slot};
use trirhythm_paper::verdict::{Check, Decision, Outcome};
use trirhythm_paper::{Figure, FigureOptions};

/// `dir/figNN` (without extension).
pub fn stem(dir: &Path, n: u32) -> PathBuf {
    dir.join(format!("fig{n:02}"))
}

/// `figNN.json`: the figure's data with what produced it.
#[derive(Serialize, Deserialize)]
struct DataFile<F> {
    /// The figure number.
    figure: u32,
    /// The version of trirhythm that computed it.
    trirhythm: String,
    /// The formula variant of the averaged theory.
    variant: Variant,
    /// Quick (coarse) or paper quality.
    quick: bool,
    /// The value the files are drawn from (the library's data type, serialised).
    data: F,
}

/// Where a figure's data comes from.
#[derive(Clone, Copy)]
pub enum Request<'a> {
    /// Computed with these options; with `profile`, its parallel profile recorded.
    Compute {
        /// Quality and variant.
        options: FigureOptions,
        /// Record the computation's parallel profile ([`Made::profile`]).
        profile: bool,
    },
    /// Read from `DIR/figNN.json`.
    FromData(&'a Path),
}

/// What making one figure gave: the files written and what the figure says.
pub struct Made {
    /// The paths written, in order (JSON, CSV, PNG, SVG).
    pub files: Vec<PathBuf>,
    /// The picture's heading: title, caption lines (parameters, variant, choices) and the
    /// verdicts drawn under it.
    pub heading: Heading,
    /// The computation's parallel profile, when asked.
    pub profile: Option<Profile>,
}

/// Make a figure's files: `(request, out_dir, write figNN.json, collect the data here)`.
pub type Make = fn(&Request, &Path, bool, Option<&mut Figures>) -> Result<Made>;

/// One figure of the registry: its number, title and how to make it.
pub struct Entry {
    /// The paper's figure number.
    pub number: u32,
    /// What it shows.
    pub title: &'static str,
    /// Make the figure's files.
    pub make: Make,
}

fn entry<F: Slot + Picture>() -> Entry {
    Entry {
        number: F::NUMBER,
        title: F::TITLE,
        make: make::<F>,
    }
}

/// The figures this build can make, by number.
pub fn registry() -> Vec<Entry> {
    vec![
        entry::<trirhythm_paper::fig01_phase_recurrence::Fig01>(),
        entry::<trirhythm_paper::fig02_rhythmicity_planes::Fig02>(),
        entry::<trirhythm_paper::fig03_restitution_planes::Fig03>(),
        entry::<trirhythm_paper::fig04_drift::Fig04>(),
        entry::<trirhythm_paper::fig05_branches::Fig05>(),
        entry::<trirhythm_paper::fig06_fractional_planes::Fig06>(),
        entry::<trirhythm_paper::fig07_pseudo_potential::Fig07>(),
        entry::<trirhythm_paper::fig08_barriers::Fig08>(),
        entry::<trirhythm_paper::fig09_barrier_surfaces::Fig09>(),
        entry::<trirhythm_paper::fig10_pbif_lambda_tau::Fig10>(),
        entry::<trirhythm_paper::fig11_amplitude_lambda::Fig11>(),
        entry::<trirhythm_paper::fig12_pbif_maps::Fig12>(),
        entry::<trirhythm_paper::fig13_pdf_restitution::Fig13>(),
        entry::<trirhythm_paper::fig14_joint_pdf::Fig14>(),
        entry::<trirhythm_paper::fig15_oscillation_boundaries::Fig15>(),
        entry::<trirhythm_paper::fig16_oscillation_regions::Fig16>(),
        entry::<trirhythm_paper::fig17_lle_noise::Fig17>(),
        entry::<trirhythm_paper::fig18_lle_noise_fractional::Fig18>(),
        entry::<trirhythm_paper::fig19_critical_noise::Fig19>(),
    ]
}

fn make<F: Slot + Picture>(
    request: &Request,
    out_dir: &Path,
    data: bool,
    figures: Option<&mut Figures>,
) -> Result<Made> {
    let mut profile = None;
    let file = match request {
        Request::Compute {
            options,
            profile: profiled,
        } => {
            let bar = Bar::new(&format!("figure {}", F::NUMBER));
            let data = if *profiled {
                let (data, p) = trirhythm::profile::record(|| F::compute(options, &bar));
                profile = Some(p);
                data?
            } else {
                F::compute(options, &bar)?
            };
            DataFile {
                figure: F::NUMBER,
                trirhythm: env!("CARGO_PKG_VERSION").to_string(),
                variant: options.variant,
                quick: options.quick,
                data,
            }
        }
        Request::FromData(dir) => read_data::<F>(dir)?,
    };
    std::fs::create_dir_all(out_dir).with_context(|| format!("creating {}", out_dir.display()))?;
    // the files are written into a staging directory beside them and moved into `out_dir`
    // together once all are complete: a figure that fails leaves none of its files
    let staging = TemporaryDir::create(&stem(out_dir, F::NUMBER))?;
    let staged = stem(staging.path(), F::NUMBER);
    let options = FigureOptions {
        quick: file.quick,
        variant: file.variant,
    };
    let from = match request {
        Request::FromData(dir) => Some(stem(dir, F::NUMBER).with_extension("json")),
        Request::Compute { .. } => None,
    };
    let write = || write_files::<F>(file, &staged, data, &options, from.as_deref());
    let (files, data) = match &from {
        Some(path) => drawn_from(path, write)?,
        None => write()?,
    };
    let files = publish(&files, out_dir)?;
    drop(staging);
    let (data, heading) = data;
    if let Some(figures) = figures {
        *F::slot(figures) = Some(data);
    }
    Ok(Made {
        files,
        heading,
        profile,
    })
}

/// Write a figure's files under `stem` (JSON when asked, CSV, PNG, SVG); returns the paths
/// written, the data judged and the picture's heading. Data read `from` a file whose tables
/// hold values no CSV may (NaN, ±∞ where not allowed) is bad input naming that file.
fn write_files<F: Slot + Picture>(
    file: DataFile<F>,
    stem: &Path,
    data: bool,
    options: &FigureOptions,
    from: Option<&Path>,
) -> Result<(Vec<PathBuf>, (F, Heading))> {
    let mut files = Vec::new();
    if data {
        let path = stem.with_extension("json");
        let json = serde_json::to_string(&file).context("serialising the figure's data")?;
        // a file that `--from-data` could not read is not written
        if let Err(e) = serde_json::from_str::<DataFile<F>>(&json) {
            anyhow::bail!(
                "figure {}: its data does not read back from JSON ({e}); {} not written",
                F::NUMBER,
                path.display()
            );
        }
        write_atomic(&path, json.as_bytes())?;
        files.push(path);
    }
    for table in file.data.tables() {
        let csv = match (Csv::of(&table), from) {
            (Ok(csv), _) => csv,
            (Err(e), Some(path)) => {
                return bad(format!(
                    "--from-data: {}: the data holds values its tables cannot: {e:#}",
                    path.display()
                ))
            }
            (Err(e), None) => return Err(e),
        };
        files.push(write_table(stem, &table, &csv)?);
    }
    let (data, verdicts) = judge_figure(file.data, options);
    let verdicts = verdict_lines(&verdicts);
    files.extend(save(&data, verdicts.clone(), stem)?);
    let heading = Heading {
        verdicts,
        ..data.heading()
    };
    Ok((files, (data, heading)))
}

/// Draw data read from the file `path` (already checked by [`Figure::validate`]): should the
/// drawing still refuse a value of it, or fail on it with a panic (a figure whose checks miss
/// an inconsistency), that is bad input naming the file, reported without a backtrace, and
/// nothing is written.
fn drawn_from<T>(path: &Path, draw: impl FnOnce() -> Result<T>) -> Result<T> {
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let drawn = std::panic::catch_unwind(std::panic::AssertUnwindSafe(draw));
    std::panic::set_hook(hook);
    match drawn {
        Ok(Err(e)) if is_bad_input(&e) => bad(format!(
            "--from-data: {}: the data cannot be drawn: {e:#}",
            path.display()
        )),
        Ok(result) => result,
        Err(payload) => {
            let why = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            bad(format!(
                "--from-data: {}: the data is inconsistent and cannot be drawn ({why}); write \
                 it again with `figure N --data`",
                path.display()
            ))
        }
    }
}

/// Move the staged `files` into `dir` under their names; returns their new paths. Should one
/// move fail, those already moved are removed again (all or none).
fn publish(files: &[PathBuf], dir: &Path) -> Result<Vec<PathBuf>> {
    let mut moved: Vec<PathBuf> = Vec::new();
    for f in files {
        let to = dir.join(f.file_name().unwrap_or_default());
        if let Err(e) = std::fs::rename(f, &to) {
            for m in &moved {
                let _ = std::fs::remove_file(m);
            }
            return Err(e).with_context(|| format!("moving {} into place", to.display()));
        }
        moved.push(to);
    }
    Ok(moved)
}

/// The verdicts on a figure's claims as short lines for its picture, each at most about two
/// printed lines ([`VERDICT_CHARS`]): the claim's id, the verdict, for an undetermined one its
/// reason first, then the deciding numbers, all taken from the decision, laid out by rule:
/// a count lists the counts found against the paper's ("positive roots of f, panel a–d: 3,
/// 2, 2, 0 against the paper's 5, 5, 3, 0"), an agreement H ± s.e. against floor + k s.e., a
/// trend the values across its range with z (or t) where stochastic, the rest (closeness,
/// sign change) the statistic against its threshold. The checks' long descriptions are
/// shortened for the picture ([`shorten`]); the decision itself is unchanged.
pub fn verdict_lines(verdicts: &[ClaimVerdict]) -> Vec<VerdictLine> {
    verdicts
        .iter()
        .map(|v| {
            let (text, full, head) = verdict_text(v);
            let tag = v.decision.verdict.tag().to_string();
            let badge = match v.decision.decisive() {
                Some(c) => format!("{} — {tag} ({})", v.claim.id, c.statistic_words()),
                None => format!("{} — {tag}", v.claim.id),
            };
            VerdictLine {
                tag,
                text,
                full,
                head,
                badge,
            }
        })
        .collect()
}

/// The most characters a verdict line takes: about two printed lines on the narrowest
/// picture.
pub const VERDICT_CHARS: usize = 190;

/// The verdict line, the same for the caption (up to [`CAPTION_CHARS`]), and how many
/// characters open them as `{claim} — {verdict} ({number})`.
fn verdict_text(v: &ClaimVerdict) -> (String, String, usize) {
    use trirhythm_paper::verdict::Verdict;
    let d = &v.decision;
    // the deciding number in the words claims.md and the page quote (first, so that a long
    // line never cuts it), then the reason when undetermined
    let mut notes: Vec<String> = d
        .decisive()
        .map(|c| c.statistic_words())
        .into_iter()
        .collect();
    if let Verdict::Undetermined { why } = &d.verdict {
        notes.push(first_clause(&shorten(why)));
    }
    let mut head = format!("{} — {}", v.claim.id, d.verdict.tag());
    let mut kept = head.chars().count();
    if !notes.is_empty() {
        head.push_str(&format!(" ({})", notes.join("; ")));
        // the deciding number, with its parenthesis when it comes alone
        kept += 2 + notes[0].chars().count() + usize::from(notes.len() == 1);
    }
    let items = match d.rule.as_str() {
        "count" => count_items(d),
        "agreement" => agreement_items(d),
        "trend" => trend_items(d),
        _ => d.deciding(3).iter().map(|c| statistic_item(c)).collect(),
    };
    let total: usize = d.tally.iter().sum();
    let tail = match (&d.verdict, d.rule.as_str()) {
        (_, "count") => String::new(),
        (Verdict::Refuted, _) if total > 3 => {
            format!(" ({} of {total} checks against)", d.tally[1])
        }
        _ => String::new(),
    };
    let mut full = fit(&head, &items, &tail, CAPTION_CHARS);
    if full != fit(&head, &items, &tail, usize::MAX) {
        full.push_str(" (every check: the report's verdicts.json)");
    }
    (fit(&head, &items, &tail, VERDICT_CHARS), full, kept)
}

/// The most characters a verdict line takes in a caption (a figure's hundred thousand
/// grid checks are in the report's verdicts.json, not under the picture).
pub const CAPTION_CHARS: usize = 600;

/// `head: item; item…tail`, with as many items as fit in `max` characters (at least the
/// first, cut with "…" when it alone is too long).
fn fit(head: &str, items: &[String], tail: &str, max: usize) -> String {
    let mut text = head.to_string();
    for (i, item) in items.iter().enumerate() {
        let sep = if i == 0 { ": " } else { "; " };
        let len = |s: &str| s.chars().count();
        if i > 0 && len(&text) + len(sep) + len(item) + len(tail) > max {
            text.push_str("; …");
            break;
        }
        text.push_str(sep);
        text.push_str(item);
    }
    text.push_str(tail);
    if text.chars().count() > max {
        text = text
            .chars()
            .take(max - 1)
            .collect::<String>()
            .trim_end()
            .to_string();
        text.push('…');
    }
    text
}

/// A check's description made short for a picture: the Monte Carlo boilerplate dropped (the
/// panel label kept), a formula variant as "(… variant)", the map shares named by rhythm.
fn shorten(text: &str) -> String {
    let mut t = text.to_string();
    for (long, short) in [
        ("peaks of the Monte Carlo P(A) of Eq. 1, ", "peaks, "),
        ("share of grid points with count one (%)", "mono share (%)"),
        ("share of grid points with count two (%)", "bi share (%)"),
        ("share of grid points with count three (%)", "tri share (%)"),
        (", MC of Eq. 1, paper formulas", ""),
        (", MC of Eq. 1, consistent formulas", ""),
    ] {
        t = t.replace(long, short);
    }
    t
}

/// The formula variant a check's description names, as "(paper variant)", or nothing.
fn variant_of(what: &str) -> &'static str {
    if what.contains(", paper formulas") {
        " (paper variant)"
    } else if what.contains(", consistent formulas") {
        " (consistent variant)"
    } else {
        ""
    }
}

/// A count decision: the counts found against the paper's, in the checks' order, under the
/// description they share (or each with its own when they share none).
fn count_items(d: &Decision) -> Vec<String> {
    let whats: Vec<String> = d.checks.iter().map(|c| label_of(&c.what)).collect();
    let noun = shared_noun(&whats);
    let n = |v: f64| sig(v, 3);
    if noun.is_empty() || d.checks.len() == 1 {
        return d
            .checks
            .iter()
            .zip(&whats)
            .map(|(c, w)| {
                format!(
                    "{w} {} against the paper's {}",
                    n(c.statistic_value),
                    n(c.threshold)
                )
            })
            .collect();
    }
    // a count that decides nothing (from a non-stationary ensemble) in parentheses
    let deciding = |c: &Check| matches!(c.outcome, Outcome::For | Outcome::Against);
    let found: Vec<String> = d
        .checks
        .iter()
        .map(|c| {
            if deciding(c) {
                n(c.statistic_value)
            } else {
                format!("({})", n(c.statistic_value))
            }
        })
        .collect();
    let claimed: Vec<String> = d.checks.iter().map(|c| n(c.threshold)).collect();
    let note = if d.checks.iter().all(deciding) {
        ""
    } else {
        " (in parentheses: not deciding)"
    };
    vec![format!(
        "{noun} {} against the paper's {}{note}",
        runs(&found),
        runs(&claimed)
    )]
}

/// Values as a list, runs of one value written `v ×n` when there are more than eight.
fn runs(values: &[String]) -> String {
    if values.len() <= 8 {
        return values.join(", ");
    }
    let mut out: Vec<String> = Vec::new();
    let mut i = 0;
    while i < values.len() {
        let j = (i..values.len())
            .find(|&j| values[j] != values[i])
            .unwrap_or(values.len());
        out.push(if j - i > 1 {
            format!("{} ×{}", values[i], j - i)
        } else {
            values[i].clone()
        });
        i = j;
    }
    out.join(", ")
}

/// The description the items share: their common beginning cut back to its last ", " or
/// " at " (empty when none).
fn shared_noun(whats: &[String]) -> String {
    let Some(first) = whats.first() else {
        return String::new();
    };
    let mut common = first.len();
    for w in &whats[1..] {
        common = common.min(
            first
                .char_indices()
                .zip(w.chars())
                .find(|((_, a), b)| a != b)
                .map_or(first.len().min(w.len()), |((i, _), _)| i),
        );
    }
    let prefix = &first[..common];
    let cut = [prefix.rfind(", "), prefix.rfind(" at ")]
        .into_iter()
        .flatten()
        .max();
    match cut {
        Some(i) => format!("{}:", prefix[..i].trim_end_matches([',', ':', ' '])),
        None => String::new(),
    }
}

/// An agreement decision: per deciding comparison, H ± s.e. against the finite-sample floor
/// + k s.e., with the formula variant.
fn agreement_items(d: &Decision) -> Vec<String> {
    use trirhythm_paper::verdict::rules::AGREEMENT_K;
    use trirhythm_paper::verdict::Uncertainty;
    d.deciding(3)
        .iter()
        .map(|c| {
            let se = match c.value.uncertainty {
                Uncertainty::StdErr { se, .. } => se,
                _ => 0.0,
            };
            format!(
                "{}: H = {} ± {} against {} + {} s.e.{}",
                label_of(&c.what),
                sig(c.statistic_value, 3),
                sig(se, 2),
                sig(c.threshold - AGREEMENT_K * se, 3),
                sig(AGREEMENT_K, 1),
                variant_of(&c.what)
            )
        })
        .collect()
}

/// A trend decision: the changes across the range (or the deciding steps) as "what: a → b
/// (x = … → …)", with z or t against its threshold where the values are stochastic.
fn trend_items(d: &Decision) -> Vec<String> {
    let deciding = d.deciding(usize::MAX);
    let ranges: Vec<&&Check> = deciding
        .iter()
        .filter(|c| c.what.contains(", across the range "))
        .collect();
    let shown: Vec<&Check> = if ranges.is_empty() {
        deciding.into_iter().take(3).collect()
    } else {
        ranges.into_iter().copied().collect()
    };
    shown
        .iter()
        .map(|c| {
            let what = shorten(&c.what);
            let item = match what.rsplit_once(": ") {
                Some((head, values)) => {
                    let (label, range) = head
                        .split_once(", across the range ")
                        .or_else(|| head.rsplit_once(", "))
                        .unwrap_or((head, ""));
                    if range.is_empty() {
                        format!("{label}: {values}")
                    } else {
                        format!("{label}: {values} ({range})")
                    }
                }
                None => what.clone(),
            };
            let stochastic = c.statistic == "z" || c.statistic.starts_with("t ");
            if stochastic {
                format!(
                    "{item}, {} = {} against {}",
                    c.statistic,
                    sig(c.statistic_value, 3),
                    sig(c.threshold, 3)
                )
            } else {
                item
            }
        })
        .collect()
}

/// A check's description for a picture: shortened, its parenthetical details (the floor of
/// an agreement) dropped, and compared numbers ("a against b") to three digits.
fn label_of(what: &str) -> String {
    let what = shorten(what);
    let what = match what.find(" (floor") {
        Some(i) => what[..i].to_string(),
        None => what,
    };
    let numbers = what.rsplit_once(": ").and_then(|(head, tail)| {
        let (a, b) = tail.split_once(" against ")?;
        Some(format!(
            "{head}: {} against {}",
            sig(a.parse().ok()?, 3),
            sig(b.parse().ok()?, 3)
        ))
    });
    first_clause(&numbers.unwrap_or(what))
}

/// A check as "what, statistic value against threshold".
fn statistic_item(c: &Check) -> String {
    format!(
        "{}, {} {} against {}{}",
        label_of(&c.what),
        c.statistic,
        sig(c.statistic_value, 3),
        sig(c.threshold, 3),
        variant_of(&c.what)
    )
}

/// `text` up to its first `; ` (with "…" when cut), at most 90 characters.
fn first_clause(text: &str) -> String {
    let cut = text.find("; ").unwrap_or(text.len());
    let mut out: String = text[..cut].chars().take(90).collect();
    if out.len() < text.len() {
        out.push('…');
    }
    out
}

/// Write one of a figure's tables, `csv` (its [`Csv::of`]), as `stem{suffix}.csv`. Returns the
/// path written.
fn write_table(stem: &Path, table: &Table, csv: &str) -> Result<PathBuf> {
    let name = stem.file_name().unwrap_or_default().to_string_lossy();
    let path = stem.with_file_name(format!("{name}{}.csv", table.suffix));
    write_atomic(&path, csv.as_bytes())?;
    Ok(path)
}

/// Read `dir/figNN.json` for figure `F` (bad input when missing, malformed, of another
/// figure, written by another version of trirhythm, or inconsistent in itself: see
/// [`Figure::validate`]).
fn read_data<F: Figure>(dir: &Path) -> Result<DataFile<F>> {
    let path = stem(dir, F::NUMBER).with_extension("json");
    let text = std::fs::read_to_string(&path).or_else(|e| {
        bad(format!(
            "--from-data {}: cannot read {} ({e}); write it with `figure {} --data`",
            dir.display(),
            path.display(),
            F::NUMBER
        ))
    })?;
    #[derive(Deserialize)]
    struct Stamp {
        figure: u32,
        trirhythm: Option<String>,
    }
    let stamp = match serde_json::from_str::<Stamp>(&text) {
        Ok(n) if n.figure == F::NUMBER => n,
        Ok(n) => {
            return bad(format!(
                "--from-data: {} holds the data of figure {}, not {}",
                path.display(),
                n.figure,
                F::NUMBER
            ))
        }
        Err(e) => {
            return bad(format!(
                "--from-data: {} is not figure data ({e})",
                path.display()
            ))
        }
    };
    let this = env!("CARGO_PKG_VERSION");
    if let Some(version) = stamp.trirhythm.filter(|v| v != this) {
        return bad(format!(
            "--from-data: {}: field `trirhythm` is {version:?}, but this is trirhythm {this}; \
             figure data is read only by the version that wrote it (write it again with \
             `figure {} --data`)",
            path.display(),
            F::NUMBER
        ));
    }
    let value: serde_json::Value = serde_json::from_str(&text).or_else(|e| {
        bad(format!(
            "--from-data: {} is not figure data ({e})",
            path.display()
        ))
    })?;
    if let Some((field, x)) = beyond(&value["data"], "data") {
        return bad(format!(
            "--from-data: {}: field `{field}` is {x:e}, beyond ±{MAX_MAGNITUDE:e} (no quantity \
             of a figure comes near; such a value cannot be drawn)",
            path.display()
        ));
    }
    let file: DataFile<F> = serde_json::from_str(&text).or_else(|e| {
        bad(format!(
            "--from-data: {} is not the data of figure {} as this version writes it ({e})",
            path.display(),
            F::NUMBER
        ))
    })?;
    if let Err(e) = file.data.validate() {
        return bad(format!(
            "--from-data: {}: field `data.{}` is inconsistent: {}; write it again with \
             `figure {} --data`",
            path.display(),
            e.field,
            e.why,
            F::NUMBER
        ));
    }
    Ok(file)
}

/// The largest magnitude a number of figure data may have: far beyond every quantity of the
/// paper's figures, and far enough below `f64::MAX` that a difference or a scale of two of them
/// stays finite.
const MAX_MAGNITUDE: f64 = 1e100;

/// The first number of `v` (at path `at`) beyond ±[`MAX_MAGNITUDE`], with its path.
fn beyond(v: &serde_json::Value, at: &str) -> Option<(String, f64)> {
    match v {
        serde_json::Value::Number(n) => n
            .as_f64()
            .filter(|x| x.abs() > MAX_MAGNITUDE)
            .map(|x| (at.to_string(), x)),
        serde_json::Value::Array(a) => a
            .iter()
            .enumerate()
            .find_map(|(i, x)| beyond(x, &format!("{at}[{i}]"))),
        serde_json::Value::Object(m) => m.iter().find_map(|(k, x)| beyond(x, &format!("{at}.{k}"))),
        _ => None,
    }
}

/// What a `figNN.json` says of itself, before its data is read.
#[derive(Deserialize)]
struct Head {
    figure: u32,
    variant: Variant,
    quick: bool,
}

/// The head of `path` (holding `text`), which must be figure `n`'s.
fn head(path: &Path, text: &str, n: u32) -> Result<Head> {
    match serde_json::from_str::<Head>(text) {
        Ok(h) if h.figure == n => Ok(h),
        Ok(h) => bad(format!(
            "--from-data: {} holds the data of figure {}, not {n}",
            path.display(),
            h.figure
        )),
        Err(e) => bad(format!(
            "--from-data: {} is not figure data ({e})",
            path.display()
        )),
    }
}

/// The options `DIR/figNN.json` was computed with, without reading its data: `None` when the
/// file does not exist; bad input when it exists but is not figure data.
pub fn data_options(dir: &Path, n: u32) -> Result<Option<FigureOptions>> {
    let path = stem(dir, n).with_extension("json");
    if !path.exists() {
        return Ok(None);
    }
    let text = std::fs::read_to_string(&path)
        .or_else(|e| bad(format!("--from-data: cannot read {} ({e})", path.display())))?;
    let h = head(&path, &text, n)?;
    Ok(Some(FigureOptions {
        quick: h.quick,
        variant: h.variant,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use trirhythm_paper::verdict::claims::Claim;
    use trirhythm_paper::verdict::{Measured, Outcome, Verdict};

    fn check(what: &str, value: Measured, stat: (&str, f64, f64), outcome: Outcome) -> Check {
        Check {
            what: what.into(),
            value,
            statistic: stat.0.into(),
            statistic_value: stat.1,
            threshold: stat.2,
            outcome,
        }
    }

    fn verdict(id: &str, rule: &str, verdict: Verdict, checks: Vec<Check>) -> ClaimVerdict {
        let mut tally = [0; 4];
        for c in &checks {
            tally[c.outcome as usize] += 1;
        }
        ClaimVerdict {
            claim: Claim {
                id: id.into(),
                figure: 4,
                place: "Fig. 4".into(),
                words: "words".into(),
                rule: rule.into(),
                model: "averaged theory (Eq. 18)".into(),
            },
            decision: Decision {
                verdict,
                rule: rule.into(),
                statistic: "statistic".into(),
                tests: 0,
                alpha: None,
                checks,
                tally,
            },
        }
    }

    #[test]
    fn a_count_lists_the_counts_against_the_papers() {
        let checks = [(3, 5), (2, 5), (2, 3), (0, 0)]
            .iter()
            .zip(["a (r = 1)", "b (r = 0.98)", "c (r = 0.96)", "d (r = 0.9)"])
            .map(|(&(n, claimed), panel)| {
                check(
                    &format!("positive roots of f, panel {panel}"),
                    Measured::exact(n as f64),
                    ("count", n as f64, claimed as f64),
                    if n == claimed {
                        Outcome::For
                    } else {
                        Outcome::Against
                    },
                )
            })
            .collect();
        let lines = verdict_lines(&[verdict("fig04-roots", "count", Verdict::Refuted, checks)]);
        assert_eq!(lines[0].tag, "refuted");
        assert_eq!(
            lines[0].text,
            "fig04-roots — refuted (count = 2 against 5): positive roots of f: 3, 2, 2, 0 against the paper's 5, 5, 3, 0"
        );
    }

    #[test]
    fn a_count_that_decides_nothing_is_in_parentheses() {
        // peaks of non-stationary ensembles (outcome undefined) beside a deciding one
        let checks = [(1, 3, Outcome::Undefined), (1, 2, Outcome::Against)]
            .iter()
            .zip(["(a1) r = 0.99", "(a3) r = 0.96"])
            .map(|(&(n, claimed, outcome), panel)| {
                check(
                    &format!("peaks of the Monte Carlo P(A) of Eq. 1, {panel}"),
                    Measured::exact(n as f64),
                    ("count", n as f64, claimed as f64),
                    outcome,
                )
            })
            .collect();
        let lines = verdict_lines(&[verdict("fig13a-peaks", "count", Verdict::Refuted, checks)]);
        assert_eq!(
            lines[0].text,
            "fig13a-peaks — refuted (count = 1 against 2): peaks: (1), 1 against the paper's 3, 2 (in parentheses: not \
             deciding)"
        );
    }

    #[test]
    fn an_agreement_gives_h_against_floor_and_standard_errors() {
        let c = check(
            "(b1) λ = 0.93, MC of Eq. 1, paper formulas (floor √(bins/(8·ESS)) = 0.05, bins 50, ESS 2500)",
            Measured::with_se(0.24, 0.002),
            ("H", 0.24, 0.05 + 2.0 * 0.002),
            Outcome::Against,
        );
        let lines = verdict_lines(&[verdict(
            "fig11b-agreement",
            "agreement",
            Verdict::Refuted,
            vec![c],
        )]);
        assert_eq!(
            lines[0].text,
            "fig11b-agreement — refuted (H = 0.24 against 0.054): (b1) λ = 0.93: H = 0.24 ± 0.002 against 0.05 + 2 s.e. (paper variant)"
        );
    }

    #[test]
    fn an_undetermined_verdict_gives_its_reason_first_and_stays_short() {
        let why = "λ and r are not printed for Fig. 2; λ = 1, r = 1 chosen (with the values chosen: refuted)";
        let checks: Vec<Check> = (0..40)
            .map(|i| {
                check(
                    &format!("share of grid points with count three (%), across the range r = 1 → r = 0.{i}: 3.353 → 2.469"),
                    Measured::exact(-0.88),
                    ("relative change", -0.26, 1e-9),
                    Outcome::Neither,
                )
            })
            .collect();
        let v = verdict("fig02-regions", "trend", Verdict::undetermined(why), checks);
        let text = &verdict_lines(&[v])[0].text;
        assert!(
            text.starts_with(
                "fig02-regions — undetermined (relative change = -0.26 against 1e-9; λ and r are not printed for Fig. 2…): tri share (%): 3.353 → 2.469 (r = 1 → r = 0.0)"
            ),
            "{text}"
        );
        assert!(text.chars().count() <= VERDICT_CHARS, "{text}");
        assert!(text.ends_with('…'), "{text}");
    }
}

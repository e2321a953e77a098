//! The report's page: one static HTML5 document (inline CSS, no network) rendered from the
//! template `report.html` beside this file — the counts, the claims table (one line per claim,
//! its details folded in its row, filters by verdict and figure), each rule once, the paper,
//! each figure's picture (which carries its caption) and verdicts, the provenance — and the
//! data files `verdicts.json` (at most [`CHECKS_KEPT`] checks a claim) and `checks.json`
//! (every check). The page's script marks on `<body>` whether every picture loaded, runs the
//! filters and opens the details an anchor points to; without it the page reads the same,
//! unfiltered.
//!
//! Method: everything shown is a value computed elsewhere — the claims and their decisions
//! ([`Verdicts`] from `trirhythm_paper::verdict::claims::judge`), the figures' headings, the
//! run's [`Provenance`] — gathered into plain view structs and rendered by `minijinja`, whose
//! automatic escaping HTML-escapes every inserted value ([`escape`]). Undefined numbers are
//! written "undefined", never `NaN`, and decimals in sentences to significant digits
//! ([`tidy_numbers`]); paths are relative to the report's directory, or the pictures are
//! inside the page (`--single-file`).
//!
//! Tests: the unit tests below (escaping, number formatting, short reasons, one row per claim)
//! and `tests/report.rs` (the page of a real run parsed back and loaded in headless Chromium:
//! its length folded, its filters, the single-file page).

use crate::render::plot::Heading;
use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
use std::path::Path;
use trirhythm_paper::notes::sig;
use trirhythm_paper::verdict::claims::{ClaimVerdict, Verdicts};
use trirhythm_paper::verdict::{Check, Verdict};

/// The paper the report judges.
pub const PAPER_TITLE: &str = "Managing trirhythmicity and bifurcation in the fractional \
    biological vibro-impact system under correlated noise";

/// How one figure of the run went.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct FigureRun {
    /// The paper's figure number.
    pub figure: u32,
    /// `computed`, `read` (from `--from-data`) or `not in the data`.
    pub status: String,
    /// Seconds spent on it (computing or reading, judging, writing its files).
    pub seconds: f64,
    /// Its files, relative to the report's directory (`figures/fig04.csv`, …).
    pub files: Vec<String>,
}

/// What produced a report: the software, the options, the run.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Provenance {
    /// The version of trirhythm.
    pub trirhythm: String,
    /// The git commit trirhythm was built from (`unknown` when the build had no git).
    pub commit: String,
    /// Quick (coarse, for CI and previews) or full (paper) quality.
    pub quick: bool,
    /// The formula variant of the averaged theory (`paper` or `consistent`).
    pub variant: String,
    /// Whether the figures were read from figure data rather than computed.
    pub from_data: bool,
    /// The command line, with paths as the directory names only.
    pub command: String,
    /// Each figure of the run, by number.
    pub figures: Vec<FigureRun>,
    /// Seconds for the whole run.
    pub total_seconds: f64,
}

/// The verdicts counted as the page shows them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Counts {
    /// Judged claims confirmed by their rule.
    pub confirmed: usize,
    /// Judged claims refuted by their rule.
    pub refuted: usize,
    /// Judged claims the rule left undetermined.
    pub undetermined: usize,
    /// Claims whose figure was not in the data.
    pub not_judged: usize,
    /// Claims no code decides yet.
    pub not_computable: usize,
}

impl Counts {
    /// The counts of `verdicts`.
    pub fn of(verdicts: &Verdicts) -> Counts {
        let (confirmed, refuted, undetermined) = verdicts.counts();
        Counts {
            confirmed,
            refuted,
            undetermined,
            not_judged: verdicts.not_judged.len(),
            not_computable: verdicts.not_computable.len(),
        }
    }
}

/// One figure's section of the page.
pub struct Section {
    /// The paper's figure number.
    pub number: u32,
    /// What it shows (the registry's title).
    pub title: String,
    /// Its picture's heading (title and caption lines); `None`: the figure was not in the data.
    pub heading: Option<Heading>,
}

/// Everything the page shows.
pub struct Page<'a> {
    /// The verdicts.
    pub verdicts: &'a Verdicts,
    /// The figures, by number.
    pub sections: &'a [Section],
    /// The run.
    pub provenance: &'a Provenance,
    /// `--single-file`: the directory holding the figures' PNGs, each put in the page as a
    /// `data:` URI; `None`: the page links `figures/figNN.png`.
    pub inline_from: Option<&'a Path>,
}

/// How many checks a claim keeps in `verdicts.json`: all where it has at most this many, else
/// its first deciding ones ([`Decision::deciding`](trirhythm_paper::verdict::Decision)); every
/// check is in `checks.json`.
pub const CHECKS_KEPT: usize = 50;

/// `verdicts.json`: the verdicts (the `Verdicts` value, flattened, each claim's checks cut to
/// [`CHECKS_KEPT`] by [`summarised`]), their counts and the provenance.
#[derive(Serialize)]
pub struct VerdictsFile<'a> {
    /// What produced the verdicts.
    pub report: &'a Provenance,
    /// The counts the page shows.
    pub counts: Counts,
    /// The claims, their verdicts and numbers.
    #[serde(flatten)]
    pub verdicts: &'a Verdicts,
}

/// The verdicts with each claim's checks cut to its first [`CHECKS_KEPT`] deciding ones where
/// it has more (the tallies still count all of them).
pub fn summarised(verdicts: &Verdicts) -> Verdicts {
    let mut out = verdicts.clone();
    for c in &mut out.claims {
        if c.decision.checks.len() > CHECKS_KEPT {
            c.decision.checks = c
                .decision
                .deciding(CHECKS_KEPT)
                .into_iter()
                .cloned()
                .collect();
        }
    }
    out
}

/// `checks.json`: every check of every claim (`verdicts.json` keeps at most [`CHECKS_KEPT`] a
/// claim).
#[derive(Serialize)]
pub struct ChecksFile<'a> {
    /// The trirhythm version and commit of the report.
    pub report: ChecksSource<'a>,
    /// One entry per judged claim, in the order of `verdicts.json`.
    pub claims: Vec<ClaimChecks<'a>>,
}

/// What wrote a `checks.json`.
#[derive(Serialize)]
pub struct ChecksSource<'a> {
    /// The version of trirhythm.
    pub trirhythm: &'a str,
    /// The git commit it was built from.
    pub commit: &'a str,
}

/// One claim's checks.
#[derive(Serialize)]
pub struct ClaimChecks<'a> {
    /// The claim's id.
    pub id: &'a str,
    /// All its checks.
    pub checks: &'a [Check],
}

impl<'a> ChecksFile<'a> {
    /// Every check of `verdicts`, with the source of `provenance`.
    pub fn of(verdicts: &'a Verdicts, provenance: &'a Provenance) -> ChecksFile<'a> {
        ChecksFile {
            report: ChecksSource {
                trirhythm: &provenance.trirhythm,
                commit: &provenance.commit,
            },
            claims: verdicts
                .claims
                .iter()
                .map(|c| ClaimChecks {
                    id: &c.claim.id,
                    checks: &c.decision.checks,
                })
                .collect(),
        }
    }
}

/// `text` with `&`, `<`, `>`, `"` and `'` escaped (safe in element content and in quoted
/// attributes): the page's automatic escaping ([`environment`]).
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
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

/// A number to three significant digits, in words where it is not finite (the paper crate's
/// [`sig`]).
pub fn number(v: f64) -> String {
    sig(v, 3)
}

/// `text` with every stand-alone `nan` or `NaN` (a number printed inside a library's sentence)
/// written "undefined".
pub fn spell_undefined(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    let word = |c: Option<&char>| c.is_some_and(|c| c.is_alphanumeric() || *c == '_');
    while i < chars.len() {
        let is_nan = chars.len() - i >= 3
            && chars[i..i + 3]
                .iter()
                .collect::<String>()
                .eq_ignore_ascii_case("nan")
            && !word(i.checked_sub(1).and_then(|j| chars.get(j)))
            && !word(chars.get(i + 3));
        if is_nan {
            out.push_str("undefined");
            i += 3;
        } else {
            out.push(chars[i]);
            i += 1;
        }
    }
    out
}

/// Most significant digits a decimal in a sentence keeps on the page: past this a decimal is
/// the noise of binary floating point (`0.9844999999999999`), written again to this many
/// significant digits with its trailing zeros dropped (`0.9845`).
const PROSE_DIGITS: usize = 10;

/// `text` with every decimal number of more than [`PROSE_DIGITS`] significant digits written to
/// that many (`λ = 0.9844999999999999` → `λ = 0.9845`); shorter numbers, integers and numbers
/// in exponent notation are left as they are.
pub fn tidy_numbers(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < chars.len() {
        let starts = chars[i].is_ascii_digit()
            && !(i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '.'));
        if !starts {
            out.push(chars[i]);
            i += 1;
            continue;
        }
        let mut j = i;
        while j < chars.len() && chars[j].is_ascii_digit() {
            j += 1;
        }
        let decimal = j + 1 < chars.len() && chars[j] == '.' && chars[j + 1].is_ascii_digit();
        if decimal {
            j += 1;
            while j < chars.len() && chars[j].is_ascii_digit() {
                j += 1;
            }
        }
        let token: String = chars[i..j].iter().collect();
        let exponent = chars.get(j).is_some_and(|c| *c == 'e' || *c == 'E');
        let significant = token
            .chars()
            .filter(char::is_ascii_digit)
            .skip_while(|c| *c == '0')
            .count();
        match token.parse::<f64>() {
            Ok(v) if decimal && !exponent && significant > PROSE_DIGITS => {
                out.push_str(&sig(v, PROSE_DIGITS));
            }
            _ => out.push_str(&token),
        }
        i = j;
    }
    out
}

/// A text of the library as the page shows it: undefined numbers in words, decimals to
/// significant digits.
fn prose(text: &str) -> String {
    tidy_numbers(&spell_undefined(text))
}

/// `fig-04`-style anchor of figure `n`.
fn fig_id(n: u32) -> String {
    format!("fig-{n:02}")
}

/// The figure a claim id or a place names first (`fig05-…`, "Figs 10, 12, Eq. 36–37").
fn figure_named(text: &str) -> Option<u32> {
    if let Some(rest) = text.strip_prefix("fig") {
        return rest.get(..2).and_then(|d| d.parse().ok());
    }
    let at = text.find("Fig")?;
    let digits: String = text[at..]
        .chars()
        .skip_while(|c| !c.is_ascii_digit())
        .take_while(char::is_ascii_digit)
        .collect();
    digits.parse().ok()
}

/// The rules, each with its anchor, its name, one line and one paragraph (the texts of
/// docs/verdicts.md, shortened). A rule a claim names that is not here gets a section of its
/// own with the statistic as its claims state it.
const RULES: &[(&str, &str, &str, &str)] = &[
    (
        "trend",
        "Trend",
        "a claimed monotone change; every step and the change across the range tested",
        "A claimed monotone change (\"the trirhythmic zone shrinks as r drops\"). Each step \
         between neighbouring values, and the change across the whole plotted range, is a test. \
         With standard errors the statistic is z = Δ/√(se₁² + se₂²) (Student's t with \
         realisations − 1 degrees of freedom where few), two-sided at family-wise α = 0.05 with \
         the Holm–Bonferroni correction over every stochastic test of the claim. Exact \
         (deterministic) values compare exactly up to a relative tolerance of 10⁻⁹; brackets \
         change when they do not overlap. The share of a map's plane is a bracket from the \
         region's interior to its closure on the grid, so a change the grid does not resolve is \
         not significant. Refuted when any step or the range change is \
         significant against the claimed direction; confirmed when the range change of every \
         series is significant in the claimed direction; otherwise undetermined (not \
         significant, or a value undefined).",
    ),
    (
        "count",
        "Count",
        "claimed counts (roots, peaks, wells, barriers) against computed ones",
        "Claimed counts (roots of f, peaks of P(A), wells, barriers) against computed ones. \
         Exact counts (Sturm-certified roots, extrema of a theory function, the classes of a \
         grid) and mode counts of a stationary Monte Carlo histogram (a mode needs a prominence \
         of three standard errors) decide: refuted on any mismatch, confirmed when all match. A \
         count from an ensemble that failed the stationarity check (R̂, drift) makes the claim \
         undetermined: not stationary.",
    ),
    (
        "regime",
        "The Lyapunov claims by regime",
        "each attractor of Figs 17–19 on its own; D_c bracketed against the margin δ = 1/W",
        "Each curve of Figs 17–19 is one attractor of the noise-free system (rest on the wall, \
         or an inner / middle / outer cycle), found by following the starts without noise. A \
         point is called against the margin δ = 1/W (W the window: below it no e-fold within \
         the window) with one-sided Student's t on the realisations that did not merge, \
         Bonferroni over the curve's points at α = 0.05: chaotic (lower bound above δ), not \
         chaotic (upper bound below δ), synchronised (at least half the realisations merged: \
         their exponent is −∞) or undecided. D_c lies between the largest not-chaotic D and \
         the smallest chaotic D. In the rest regime, where the equation near the wall is \
         homogeneous, D_c = 0 when the exponent pooled over D ≤ 10⁻² (from 10⁻⁶) exceeds δ and \
         does not trend with log D. On a cycle, the phase-reduction prediction λ ≈ −c·D is \
         computed from the cycle's phase response and tested for equivalence within δ. The \
         sign-change claims: per value of the parameter, for when one of its regimes has a \
         located D_c, against when every regime it has has D_c = 0; refuted when a value is \
         against, confirmed when every value is for. Fig. 19's trends: the trend rule over each \
         attractor's brackets of D_c.",
    ),
    (
        "sign_change",
        "Sign change of the largest Lyapunov exponent (data of earlier versions)",
        "past a critical noise the exponent turns positive, on each curve",
        "\"Past a critical noise D_c the LLE turns positive\", on each curve of a panel. Every \
         point is tested with t = LLE/se and realisations − 1 degrees of freedom, two-sided, \
         Holm–Bonferroni at α = 0.05 over all points of the claim; a point whose exponent is not \
         finite is undefined and not tested. A curve is confirmed when a significant negative \
         value lies below a significant positive one in D and every significant negative lies \
         below every significant positive; refuted when a significant positive lies below a \
         significant negative; else undetermined. The claim is refuted when a curve is, \
         confirmed when every curve is.",
    ),
    (
        "agreement",
        "Agreement of theory and Monte Carlo",
        "the Hellinger distance of P(A) against its finite-sample floor",
        "The averaged theory's P(A) against an ensemble's amplitude histogram by the Hellinger \
         distance H, with its bootstrap standard error over paths. Even the exact density gives \
         H > 0 for a finite sample: the floor is √(bins/(8·ESS)). Confirmed when \
         H ≤ floor + 2·se(H), refuted when H exceeds it; an ensemble that failed the \
         stationarity check, or has no standard error, makes the comparison undetermined. The \
         claims compare the formulas as printed with Monte Carlo of Eq. 1.",
    ),
    (
        "closeness",
        "Closeness",
        "a relative difference within 5 %",
        "\"Align closely\", \"change very slightly\": the relative difference \
         |a − b|/max(|a|, |b|) below 5 % (the paper gives no number; 5 % is a stated choice, \
         the same for every closeness claim, and each check prints the difference). With \
         uncertainties the margin is 2 standard errors plus the half-width of any bracket: \
         confirmed when the difference plus the margin is within 5 %, refuted when the \
         difference minus the margin is beyond it, else undetermined.",
    ),
];

/// Longest short reason the claims table shows (the details hold the whole).
const SHORT_REASON: usize = 70;

/// `text` cut at a word to at most `max` characters, with "…" where cut.
fn shorten(text: &str, max: usize) -> String {
    let text = text.trim();
    if text.chars().count() <= max {
        return text.to_string();
    }
    let cut: String = text.chars().take(max).collect();
    let at = cut.rfind(' ').filter(|&i| i > max / 2).unwrap_or(cut.len());
    format!("{}…", cut[..at].trim_end_matches([',', ';', ':', ' ']))
}

/// `text` split on `sep` outside parentheses and brackets.
fn split_top(text: &str, sep: &str) -> Vec<String> {
    let mut parts = Vec::new();
    let mut depth = 0i32;
    let mut start = 0;
    let mut i = 0;
    while i < text.len() {
        let c = text[i..].chars().next().unwrap_or(' ');
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            _ => {}
        }
        if depth == 0 && text[i..].starts_with(sep) {
            parts.push(text[start..i].to_string());
            start = i + sep.len();
            i = start;
            continue;
        }
        i += c.len_utf8();
    }
    parts.push(text[start..].to_string());
    parts
}

/// `text` without its parenthesised asides.
fn without_asides(text: &str) -> String {
    let mut out = String::new();
    let mut depth = 0i32;
    for c in text.chars() {
        match c {
            '(' => depth += 1,
            ')' => depth = (depth - 1).max(0),
            c if depth == 0 => out.push(c),
            _ => {}
        }
    }
    out.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The reason of an undetermined verdict in a few words for the claims table: of each part
/// (`; `-separated, asides in parentheses left out) the clause after its label (`(b1) …: not
/// stationary` → `not stationary`), the distinct ones kept, the first shown ("…" when more),
/// at most [`SHORT_REASON`] characters.
pub fn short_reason(why: &str) -> String {
    let mut heads: Vec<String> = Vec::new();
    for part in split_top(why, "; ") {
        let part = without_asides(&part);
        let head = match part.split_once(": ") {
            Some((_, rest)) => rest.split(": ").next().unwrap_or(rest).to_string(),
            None => part,
        };
        let head = head.trim().trim_end_matches(['.', ',']).to_string();
        if !head.is_empty() && !heads.contains(&head) {
            heads.push(head);
        }
    }
    let Some(first) = heads.first() else {
        return shorten(why, SHORT_REASON);
    };
    let text = if heads.len() > 1 {
        format!("{first}; …")
    } else {
        first.clone()
    };
    shorten(&prose(&text), SHORT_REASON)
}

/// A check in one line for the claims table: the statistic against its threshold first, then
/// what was compared.
fn one_number(c: &Check) -> String {
    prose(&format!("{} · {}", c.statistic_words(), c.what))
}

/// How many deciding checks a claim's details list.
const DETAIL_CHECKS: usize = 5;

/// One row of the claims table, with its details.
#[derive(Serialize)]
struct Row {
    id: String,
    /// The figure's number as text (`""`: none).
    figure: String,
    fig_anchor: String,
    words: String,
    place: String,
    verdict: &'static str,
    /// The reason in a few words (undetermined only).
    short: String,
    /// The whole reason (undetermined only).
    why: String,
    /// One deciding number.
    number: String,
    /// The rule's anchor (`""`: none).
    rule: String,
    rule_name: String,
    checks: Vec<String>,
    tally: String,
    tally_data: String,
}

impl Row {
    fn judged(c: &ClaimVerdict) -> Row {
        let d = &c.decision;
        let why = match &d.verdict {
            Verdict::Undetermined { why } => why.as_str(),
            _ => "",
        };
        let deciding = d.deciding(DETAIL_CHECKS);
        let [f, a, n, u] = d.tally;
        let mut tally = format!("checks: {f} for, {a} against, {n} neither, {u} undefined");
        if d.tests > 0 {
            tally.push_str(&format!("; {} stochastic tests", d.tests));
        }
        if let Some(alpha) = d.alpha {
            tally.push_str(&format!(", α = {}", number(alpha)));
        }
        let shown = deciding.len();
        let all = f + a + n + u;
        if all > shown {
            tally.push_str(&format!("; {shown} of them below, all in checks.json"));
        }
        Row {
            id: c.claim.id.clone(),
            figure: c.claim.figure.to_string(),
            fig_anchor: fig_id(c.claim.figure),
            words: prose(&c.claim.words),
            place: c.claim.place_and_model(),
            verdict: d.verdict.tag(),
            short: if why.is_empty() {
                String::new()
            } else {
                short_reason(why)
            },
            why: prose(why),
            number: d.decisive().map(one_number).unwrap_or_else(|| "—".into()),
            rule: d.rule.clone(),
            rule_name: rule_name(&d.rule),
            checks: deciding.iter().map(|c| prose(&c.describe())).collect(),
            tally,
            tally_data: format!("{f} {a} {n} {u}"),
        }
    }

    fn other(
        id: &str,
        figure: Option<u32>,
        words: &str,
        place: &str,
        why: &str,
        short: &str,
    ) -> Row {
        Row {
            id: id.into(),
            figure: figure.map(|n| n.to_string()).unwrap_or_default(),
            fig_anchor: figure.map(fig_id).unwrap_or_default(),
            words: prose(words),
            place: place.into(),
            verdict: "undetermined",
            short: short.into(),
            why: prose(why),
            number: "—".into(),
            rule: String::new(),
            rule_name: String::new(),
            checks: vec![],
            tally: String::new(),
            tally_data: String::new(),
        }
    }
}

/// The name of rule `id` ([`RULES`]; the id itself for another).
fn rule_name(id: &str) -> String {
    RULES
        .iter()
        .find(|r| r.0 == id)
        .map(|r| r.1.to_string())
        .unwrap_or_else(|| id.to_string())
}

/// One rule of the page: its text and the statistics its claims state.
#[derive(Serialize)]
struct Rule {
    id: String,
    name: String,
    gist: String,
    text: String,
    applied: Vec<Applied>,
}

/// One statistic sentence and the claims that state it.
#[derive(Serialize)]
struct Applied {
    statistic: String,
    claims: Vec<String>,
}

fn rules(verdicts: &Verdicts) -> Vec<Rule> {
    let mut out: Vec<Rule> = RULES
        .iter()
        .map(|(id, name, gist, text)| Rule {
            id: id.to_string(),
            name: name.to_string(),
            gist: gist.to_string(),
            text: text.to_string(),
            applied: vec![],
        })
        .collect();
    for c in &verdicts.claims {
        let d = &c.decision;
        let i = match out.iter().position(|r| r.id == d.rule) {
            Some(i) => i,
            None => {
                out.push(Rule {
                    id: d.rule.clone(),
                    name: d.rule.clone(),
                    gist: String::new(),
                    text: String::new(),
                    applied: vec![],
                });
                out.len() - 1
            }
        };
        let statistic = prose(&d.statistic);
        let applied = &mut out[i].applied;
        match applied.iter_mut().find(|a| a.statistic == statistic) {
            Some(a) => a.claims.push(c.claim.id.clone()),
            None => applied.push(Applied {
                statistic,
                claims: vec![c.claim.id.clone()],
            }),
        }
    }
    out
}

/// A claim's verdict in a figure's section.
#[derive(Serialize)]
struct Mention {
    id: String,
    verdict: &'static str,
}

/// A data file of a figure: its name, and its link (none in a single-file page).
#[derive(Serialize)]
struct DataFile {
    name: String,
    href: Option<String>,
}

/// One figure's section.
#[derive(Serialize)]
struct Figure {
    number: u32,
    anchor: String,
    data_name: String,
    title: String,
    present: bool,
    src: String,
    svg: Option<String>,
    /// The caption: the picture's lines (parameters, method, seeds), shown under it.
    caption: Vec<String>,
    alt: String,
    claims: Vec<Mention>,
    data: Vec<DataFile>,
    run: String,
}

/// One figure of the provenance table.
#[derive(Serialize)]
struct RunRow {
    number: u32,
    anchor: String,
    status: String,
    seconds: String,
    seeds: Vec<String>,
}

/// The provenance as the page shows it.
#[derive(Serialize)]
struct Origin {
    trirhythm: String,
    commit: String,
    figures: &'static str,
    command: String,
    total: String,
    per_figure: Vec<RunRow>,
}

/// Everything the template reads.
#[derive(Serialize)]
struct View {
    paper: &'static str,
    trirhythm: String,
    quality: &'static str,
    quality_words: &'static str,
    variant: String,
    single_file: bool,
    counts: Counts,
    filter_figures: Vec<u32>,
    rows: Vec<Row>,
    rules: Vec<Rule>,
    sections: Vec<Figure>,
    prov: Origin,
}

/// The page's template (`report.html` beside this file).
const TEMPLATE: &str = include_str!("report.html");

/// The template environment: HTML escaping of every inserted value ([`escape`]: `/` is left as
/// it is, so that paths and `data:` URIs read plainly), strict about undefined names.
fn environment() -> Result<minijinja::Environment<'static>> {
    let mut env = minijinja::Environment::new();
    env.set_undefined_behavior(minijinja::UndefinedBehavior::Strict);
    env.set_formatter(|out, state, value| {
        let html = matches!(state.auto_escape(), minijinja::AutoEscape::Html);
        if html && !value.is_safe() && !value.is_undefined() && !value.is_none() {
            let text = match value.as_str() {
                Some(s) => escape(s),
                None => escape(&value.to_string()),
            };
            out.write_str(&text).map_err(|_| {
                minijinja::Error::new(minijinja::ErrorKind::WriteFailure, "writing the page")
            })
        } else {
            minijinja::escape_formatter(out, state, value)
        }
    });
    env.add_template("report.html", TEMPLATE)
        .context("the report's page template")?;
    Ok(env)
}

/// The page.
pub fn page(p: &Page) -> Result<String> {
    let prov = p.provenance;
    let counts = Counts::of(p.verdicts);
    let mut rows: Vec<Row> = p.verdicts.claims.iter().map(Row::judged).collect();
    for id in &p.verdicts.not_judged {
        rows.push(Row::other(
            id,
            figure_named(id),
            id,
            "",
            "not judged: its figure is not in the data",
            "not in the data",
        ));
    }
    for n in &p.verdicts.not_computable {
        rows.push(Row::other(
            &n.id,
            figure_named(&n.place),
            &n.words,
            &n.place,
            &format!("not decided by code: {}", n.needs),
            "not decided by code",
        ));
    }
    let mut sections = Vec::new();
    for s in p.sections {
        sections.push(figure(s, p)?);
    }
    let view = View {
        paper: PAPER_TITLE,
        trirhythm: prov.trirhythm.clone(),
        quality: if prov.quick { "quick" } else { "full" },
        quality_words: if prov.quick {
            "quick (coarse grids, few and short paths: for previews; its Monte Carlo verdicts \
             are mostly undetermined by construction)"
        } else {
            "full (the paper's grids and run sizes)"
        },
        variant: prov.variant.clone(),
        single_file: p.inline_from.is_some(),
        counts,
        filter_figures: p.sections.iter().map(|s| s.number).collect(),
        rows,
        rules: rules(p.verdicts),
        sections,
        prov: origin(p),
    };
    let env = environment()?;
    let template = env.get_template("report.html")?;
    template
        .render(minijinja::value::Serde(&view))
        .context("rendering the report's page")
}

/// The section of figure `s`.
fn figure(s: &Section, p: &Page) -> Result<Figure> {
    let stem = format!("figures/fig{:02}", s.number);
    let run = p.provenance.figures.iter().find(|f| f.figure == s.number);
    let mut out = Figure {
        number: s.number,
        anchor: fig_id(s.number),
        data_name: format!("fig{:02}.json", s.number),
        title: s.title.clone(),
        present: s.heading.is_some(),
        src: String::new(),
        svg: None,
        caption: vec![],
        alt: String::new(),
        claims: vec![],
        data: vec![],
        run: String::new(),
    };
    let Some(heading) = &s.heading else {
        return Ok(out);
    };
    out.caption = heading.lines.iter().map(|l| prose(l)).collect();
    out.alt = prose(
        &std::iter::once(heading.title.as_str())
            .chain(heading.lines.iter().map(String::as_str))
            .collect::<Vec<_>>()
            .join(" "),
    );
    match p.inline_from {
        Some(dir) => {
            use base64::Engine;
            let png = dir.join(format!("fig{:02}.png", s.number));
            let bytes = std::fs::read(&png)
                .with_context(|| format!("reading {} into the page", png.display()))?;
            out.src = format!(
                "data:image/png;base64,{}",
                base64::engine::general_purpose::STANDARD.encode(bytes)
            );
        }
        None => {
            out.src = format!("{stem}.png");
            out.svg = Some(format!("{stem}.svg"));
        }
    }
    out.claims = p
        .verdicts
        .claims
        .iter()
        .filter(|c| c.claim.figure == s.number)
        .map(|c| Mention {
            id: c.claim.id.clone(),
            verdict: c.decision.verdict.tag(),
        })
        .collect();
    if let Some(run) = run {
        out.data = run
            .files
            .iter()
            .filter(|f| f.ends_with(".csv") || f.ends_with(".json"))
            .map(|f| DataFile {
                name: f.rsplit('/').next().unwrap_or(f).to_string(),
                href: p.inline_from.is_none().then(|| f.clone()),
            })
            .collect();
        out.run = format!("{} in {} s.", run.status, number(run.seconds));
    }
    Ok(out)
}

fn origin(p: &Page) -> Origin {
    let prov = p.provenance;
    Origin {
        trirhythm: prov.trirhythm.clone(),
        commit: prov.commit.clone(),
        figures: if prov.from_data {
            "read from figure data (figNN.json)"
        } else {
            "computed by this run"
        },
        command: prov.command.clone(),
        total: number(prov.total_seconds),
        per_figure: p
            .sections
            .iter()
            .map(|s| {
                let run = prov.figures.iter().find(|f| f.figure == s.number);
                RunRow {
                    number: s.number,
                    anchor: fig_id(s.number),
                    status: run.map(|r| r.status.clone()).unwrap_or_default(),
                    seconds: run.map(|r| number(r.seconds)).unwrap_or_default(),
                    seeds: s
                        .heading
                        .iter()
                        .flat_map(|h| h.lines.iter())
                        .filter(|l| l.to_lowercase().contains("seed"))
                        .map(|l| prose(l))
                        .collect(),
                }
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use trirhythm_paper::verdict::claims::not_computable;

    #[test]
    fn escape_covers_markup_and_quotes() {
        assert_eq!(
            escape("<a href=\"x\">R&D's</a>"),
            "&lt;a href=&quot;x&quot;&gt;R&amp;D&#39;s&lt;/a&gt;"
        );
        assert_eq!(escape("μ0 ≈ 0.7"), "μ0 ≈ 0.7");
    }

    #[test]
    fn undefined_numbers_are_words() {
        assert_eq!(number(f64::NAN), "undefined");
        assert_eq!(number(f64::NEG_INFINITY), "−∞");
        assert_eq!(number(0.012345), "0.0123");
        assert_eq!(
            spell_undefined("D_c: nan in [nan, 0.5] → NaN; resonance, nanometre"),
            "D_c: undefined in [undefined, 0.5] → undefined; resonance, nanometre"
        );
    }

    #[test]
    fn float_noise_in_prose_is_cut_to_significant_digits() {
        assert_eq!(
            tidy_numbers("λ = 0.984375 → λ = 0.9844999999999999: 0.03073 → 0.02954"),
            "λ = 0.984375 → λ = 0.9845: 0.03073 → 0.02954"
        );
        assert_eq!(tidy_numbers("r = 0.40800000000000003,"), "r = 0.408,");
        // integers, short decimals, exponents and words are left alone
        assert_eq!(
            tidy_numbers("Fig. 13(b2), 12345678901234 paths, 1.23456789012345e-5, x2.5"),
            "Fig. 13(b2), 12345678901234 paths, 1.23456789012345e-5, x2.5"
        );
    }

    #[test]
    fn undetermined_reasons_are_short_in_the_table() {
        let why = "(b1) μ0 = 0.2, r = 0.999, MC of Eq. 1 (direct; the well decomposition \
                   refused), paper formulas: not stationary (R̂ = 3190); (b2) μ0 = 0.2, r = \
                   0.95, MC of Eq. 1 (direct), paper formulas: not stationary (R̂ = 252)";
        assert_eq!(short_reason(why), "not stationary");
        assert_eq!(
            short_reason(
                "trirhythmic: not significant: the change across the range is not \
                 significantly negative in every series"
            ),
            "not significant"
        );
        assert_eq!(
            short_reason(
                "τ is not printed in the paper; τ = 5 chosen, and the inner well exists only \
                 for τ ≳ 3 (with the values chosen: confirmed)"
            ),
            "τ is not printed in the paper; …"
        );
        let long = "a reason without any structure that goes on and on well past the width \
                    of one line of the table";
        let short = short_reason(long);
        assert!(short.chars().count() <= SHORT_REASON + 1 && short.ends_with('…'));
    }

    #[test]
    fn values_are_escaped_by_the_template() {
        let env = environment().unwrap();
        let t = env
            .template_from_named_str("t.html", "<p title=\"{{ x }}\">{{ x }}</p>")
            .unwrap();
        let out = t
            .render(minijinja::context! { x => "<b>R&D's \"x\"</b> figures/fig01.png" })
            .unwrap();
        assert_eq!(
            out,
            "<p title=\"&lt;b&gt;R&amp;D&#39;s &quot;x&quot;&lt;/b&gt; figures/fig01.png\">\
             &lt;b&gt;R&amp;D&#39;s &quot;x&quot;&lt;/b&gt; figures/fig01.png</p>"
        );
    }

    #[test]
    fn a_page_without_figures_lists_every_claim_once() {
        let verdicts = Verdicts {
            claims: vec![],
            not_judged: vec!["fig04-roots".into()],
            not_computable: not_computable(),
        };
        let prov = Provenance {
            trirhythm: "0".into(),
            commit: "<unknown>".into(),
            quick: true,
            variant: "paper".into(),
            from_data: true,
            command: "trirhythm report".into(),
            figures: vec![],
            total_seconds: 0.0,
        };
        let sections = [Section {
            number: 4,
            title: "f & roots".into(),
            heading: None,
        }];
        let html = page(&Page {
            verdicts: &verdicts,
            sections: &sections,
            provenance: &prov,
            inline_from: None,
        })
        .unwrap();
        assert_eq!(html.matches("data-claim=\"fig04-roots\"").count(), 1);
        assert!(html.contains("data-figure=\"4\""));
        assert!(!html.contains("<details open"));
        for n in not_computable() {
            assert_eq!(html.matches(&format!("data-claim=\"{}\"", n.id)).count(), 1);
        }
        assert!(html.contains("&lt;unknown&gt;") && !html.contains("<unknown>"));
        assert!(html.contains("f &amp; roots"));
        assert!(html.contains("data-missing=\"4\""));
    }
}

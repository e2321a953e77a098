//! The report's page: one static HTML5 document (inline CSS, no network, a few lines of
//! script that only mark on `<body>` whether every picture loaded) giving the verdict on each
//! of the paper's claims with its numbers, each figure with its caption and verdicts, and the
//! provenance of the run; and `verdicts.json`, the same verdicts as data.
//!
//! Method: everything shown is a value computed elsewhere — the claims and their decisions
//! ([`Verdicts`] from `trirhythm_paper::verdict::claims::judge`), the figures' headings
//! (their captions), the run's [`Provenance`]. Every text inserted is HTML-escaped
//! ([`escape`]); undefined numbers are written "undefined", never `NaN`; paths are relative to
//! the report's directory.
//!
//! Tests: the unit tests below (escaping, number formatting, one row per claim) and
//! `tests/report.rs` (the page of a real run parsed back, loaded in a headless browser).

use crate::render::plot::Heading;
use serde::{Deserialize, Serialize};
use trirhythm_paper::notes::sig;
use trirhythm_paper::verdict::claims::{ClaimVerdict, Verdicts};
use trirhythm_paper::verdict::Verdict;

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

/// `verdicts.json`: the verdicts (the `Verdicts` value, flattened), their counts and the
/// provenance.
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
}

/// `text` with `&`, `<`, `>`, `"` and `'` escaped (safe in element content and in quoted
/// attributes).
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

/// `figures/fig04.png`-style anchor of figure `n`.
fn fig_id(n: u32) -> String {
    format!("fig-{n:02}")
}

/// The rules, each with its anchor and one paragraph (the texts of docs/verdicts.md, shortened).
const RULES: &[(&str, &str, &str)] = &[
    (
        "trend",
        "Trend",
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
        "\"Align closely\", \"change very slightly\": the relative difference \
         |a − b|/max(|a|, |b|) below 5 % (the paper gives no number; 5 % is a stated choice, \
         the same for every closeness claim, and each check prints the difference). With \
         uncertainties the margin is 2 standard errors plus the half-width of any bracket: \
         confirmed when the difference plus the margin is within 5 %, refuted when the \
         difference minus the margin is beyond it, else undetermined.",
    ),
];

const STYLE: &str = "
body{font-family:DejaVu Sans,Verdana,sans-serif;line-height:1.45;margin:0 auto;max-width:72rem;\
padding:1rem 1.5rem;color:#222;background:#fff}
h1{font-size:1.6rem;margin-bottom:.2rem}h2{margin-top:2.2rem;border-bottom:1px solid #ccc}
code{font-size:.9em}
table{border-collapse:collapse;width:100%;font-size:.88rem}
th,td{border:1px solid #ccc;padding:.3rem .4rem;vertical-align:top;text-align:left}
th{background:#f2f2f2}
col.claim{width:27%}col.verdict{width:17%}col.rule{width:18%}col.fig{width:6%}
tr[data-verdict=confirmed] td.verdict{background:#e3f0f8;color:#005f93}
tr[data-verdict=refuted] td.verdict{background:#fbe9de;color:#a64700}
tr[data-verdict=undetermined] td.verdict{background:#eee;color:#444}
.confirmed{color:#0072b2;font-weight:bold}.refuted{color:#d55e00;font-weight:bold}
.undetermined{color:#5a5a5a;font-weight:bold}
.counts span{font-size:1.3rem;font-weight:bold}
ul.checks{margin:.2rem 0;padding-left:1.1rem}
figure{margin:1rem 0}figure img{max-width:100%;height:auto;border:1px solid #ddd}
.caption li{font-size:.9rem}
.muted{color:#666;font-size:.85rem}
section.figure{border-top:1px solid #eee;padding-top:.5rem}
";

const SCRIPT: &str = "window.addEventListener('load',function(){var im=document.images,bad=0;\
for(var i=0;i<im.length;i++){if(!im[i].complete||im[i].naturalWidth===0){bad++;}}\
document.body.setAttribute('data-images',bad===0?'loaded':'broken '+bad);\
document.body.setAttribute('data-image-count',String(im.length));});";

/// The page.
pub fn page(p: &Page) -> String {
    let mut h = String::new();
    let prov = p.provenance;
    let quality = if prov.quick {
        "quick (coarse grids, few and short paths: for previews; its Monte Carlo verdicts are \
         mostly undetermined by construction)"
    } else {
        "full (the paper's grids and run sizes)"
    };
    h.push_str(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n",
    );
    h.push_str(&format!(
        "<title>trirhythm report: {}</title>\n<style>{STYLE}</style>\n</head>\n\
         <body data-images=\"pending\">\n",
        escape(PAPER_TITLE)
    ));
    // title and the paper
    h.push_str(&format!(
        "<h1>The paper's claims, decided from its figures</h1>\n<p class=\"muted\">trirhythm \
         {} report, {} quality, {} formula variant</p>\n",
        escape(&prov.trirhythm),
        if prov.quick { "quick" } else { "full" },
        escape(&prov.variant)
    ));
    h.push_str(&format!(
        "<h2 id=\"paper\">The paper</h2>\n<p>“{}” studies a fractional-order vibro-impact \
         oscillator with several coexisting limit cycles (trirhythmicity), driven by correlated \
         noise (the paper's Eq. 1): D<sup>1+λ</sup>U − μ0 P(U) U̇ + ω0² U = η(t) for U &gt; 0, \
         with impacts U̇₊ = −r U̇₋ at the wall U = 0, the polynomial \
         P(U) = 1 − U² + α0U⁴ − β0U⁶ + γ0U⁸ − δ0U¹⁰, a Caputo derivative of order 1 + λ, \
         λ ∈ (0, 1], and η an Ornstein–Uhlenbeck noise with ⟨η(t)η(s)⟩ = (D/τ)e<sup>−|t−s|/τ</sup>. \
         Its claims concern the number of limit cycles (roots of the averaged drift, Eq. 18), \
         the pseudo-potential and its barriers, P-bifurcations of the stationary amplitude \
         density, the oscillation boundary and the largest Lyapunov exponent against the \
         noise.</p>\n",
        escape(PAPER_TITLE)
    ));
    h.push_str(
        "<h2 id=\"method\">What trirhythm is, and how the verdicts are decided</h2>\n\
         <p>trirhythm is a Rust library and command-line tool that reproduces the paper's 19 \
         figures: the stochastic averaging (as printed and corrected), the fractional system \
         itself (a predictor–corrector with a verified sum-of-exponentials memory and exact \
         impacts), Monte Carlo ensembles with error bars and stationarity checks, bifurcation \
         maps, oscillation boundaries and Lyapunov exponents. Each checkable claim of the paper \
         is decided from the figures' data by one of the stated rules below — never by typed \
         text: change a figure's data and the verdict follows. A verdict is <span \
         class=\"confirmed\">confirmed</span>, <span class=\"refuted\">refuted</span> or <span \
         class=\"undetermined\">undetermined</span> (with the reason: not stationary, not \
         significant, a parameter the paper does not print, …). Numbers carry their \
         uncertainty: exact (deterministic), a standard error (± se) or a bracket ([lo, hi]); \
         an undefined number is never read as a value.</p>\n",
    );
    for (id, name, text) in RULES {
        h.push_str(&format!(
            "<p id=\"rule-{id}\"><strong>{}</strong> (<code>{id}</code>). {}</p>\n",
            escape(name),
            escape(text)
        ));
    }
    // counts
    let counts = Counts::of(p.verdicts);
    h.push_str(&format!(
        "<h2 id=\"summary\">Summary</h2>\n<p class=\"counts\"><span class=\"confirmed\" \
         data-count=\"confirmed\">{}</span> confirmed · <span class=\"refuted\" \
         data-count=\"refuted\">{}</span> refuted · <span class=\"undetermined\" \
         data-count=\"undetermined\">{}</span> undetermined by their rule</p>\n\
         <p>Also undetermined: <span data-count=\"not-computable\">{}</span> claims no code \
         decides yet, and <span data-count=\"not-judged\">{}</span> claims whose figure is not \
         in the data. Quality of the run: <strong data-quality=\"{}\">{}</strong>.</p>\n",
        counts.confirmed,
        counts.refuted,
        counts.undetermined,
        counts.not_computable,
        counts.not_judged,
        if prov.quick { "quick" } else { "full" },
        escape(quality)
    ));
    // claims table
    h.push_str(
        "<h2 id=\"claims\">The claims</h2>\n<table>\n<colgroup><col class=\"claim\">\
         <col class=\"verdict\"><col class=\"rule\"><col><col class=\"fig\"></colgroup>\n<thead><tr><th>Claim</th><th>Verdict</th>\
         <th>Rule and statistic</th><th>Deciding numbers</th><th>Figure</th></tr></thead>\n\
         <tbody>\n",
    );
    for c in &p.verdicts.claims {
        h.push_str(&claim_row(c));
    }
    for id in &p.verdicts.not_judged {
        let figure = p
            .sections
            .iter()
            .find(|s| id.starts_with(&format!("fig{:02}", s.number)))
            .map(|s| s.number);
        h.push_str(&format!(
            "<tr data-claim=\"{}\" data-verdict=\"undetermined\"><td><code>{}</code></td>\
             <td class=\"verdict\">undetermined<br>not judged: its figure is not in the data</td>\
             <td></td><td></td><td>{}</td></tr>\n",
            escape(id),
            escape(id),
            figure
                .map(|n| format!("<a href=\"#{}\">Fig. {n}</a>", fig_id(n)))
                .unwrap_or_default()
        ));
    }
    for n in &p.verdicts.not_computable {
        h.push_str(&format!(
            "<tr data-claim=\"{}\" data-verdict=\"undetermined\"><td><code>{}</code><br>{}<br>\
             <span class=\"muted\">{}</span></td><td class=\"verdict\">undetermined<br>not \
             decided by code: {}</td><td></td><td></td><td>{}</td></tr>\n",
            escape(&n.id),
            escape(&n.id),
            escape(&n.words),
            escape(&n.place),
            escape(&n.needs),
            escape(&n.place)
        ));
    }
    h.push_str("</tbody>\n</table>\n");
    // figures
    h.push_str("<h2 id=\"figures\">The figures</h2>\n");
    for s in p.sections {
        h.push_str(&section(s, p));
    }
    // provenance
    h.push_str(&provenance(p));
    h.push_str(&format!("<script>{SCRIPT}</script>\n</body>\n</html>\n"));
    h
}

/// The verdict's tag and, when undetermined, why.
fn verdict_cell(v: &Verdict) -> String {
    let tag = v.tag();
    match v {
        Verdict::Undetermined { why } => format!(
            "<span class=\"{tag}\">{tag}</span><br>{}",
            escape(&spell_undefined(why))
        ),
        _ => format!("<span class=\"{tag}\">{tag}</span>"),
    }
}

/// The deciding checks (at most three), the tally, the tests and α.
fn numbers_cell(c: &ClaimVerdict) -> String {
    let d = &c.decision;
    let mut h = String::from("<ul class=\"checks\">");
    for check in d.deciding(3) {
        h.push_str(&format!("<li>{}</li>", escape(&check.describe())));
    }
    h.push_str("</ul>");
    let [f, a, n, u] = d.tally;
    h.push_str(&format!(
        "<span class=\"muted\" data-tally=\"{f} {a} {n} {u}\">checks: {f} for, {a} against, \
         {n} neither, {u} undefined; {} tests{}</span>",
        d.tests,
        d.alpha
            .map(|a| format!(", α = {}", number(a)))
            .unwrap_or_default()
    ));
    h
}

fn claim_row(c: &ClaimVerdict) -> String {
    let d = &c.decision;
    let rule = escape(&d.rule);
    format!(
        "<tr data-claim=\"{id}\" data-verdict=\"{tag}\"><td><code>{id}</code><br>{words}<br>\
         <span class=\"muted\">{place}</span></td><td class=\"verdict\">{verdict}</td>\
         <td><a href=\"#rule-{rule}\">{rule}</a><br><span class=\"muted\">{statistic}</span></td>\
         <td>{numbers}</td><td><a href=\"#{fig}\">Fig. {n}</a></td></tr>\n",
        id = escape(&c.claim.id),
        tag = d.verdict.tag(),
        words = escape(&c.claim.words),
        place = escape(&c.claim.place),
        verdict = verdict_cell(&d.verdict),
        statistic = escape(&d.statistic),
        numbers = numbers_cell(c),
        fig = fig_id(c.claim.figure),
        n = c.claim.figure,
    )
}

fn section(s: &Section, p: &Page) -> String {
    let id = fig_id(s.number);
    let run = p.provenance.figures.iter().find(|f| f.figure == s.number);
    let mut h = format!("<section class=\"figure\" id=\"{id}\">\n");
    let Some(heading) = &s.heading else {
        h.push_str(&format!(
            "<h3>Fig. {}: {}</h3>\n<p data-missing=\"{}\">Not in the data: \
             <code>fig{:02}.json</code> is not in the figure-data directory; the claims on this \
             figure are not judged.</p>\n</section>\n",
            s.number,
            escape(&s.title),
            s.number,
            s.number
        ));
        return h;
    };
    h.push_str(&format!("<h3>{}</h3>\n", escape(&heading.title)));
    h.push_str("<ul class=\"caption\">");
    for line in &heading.lines {
        h.push_str(&format!("<li>{}</li>", escape(line)));
    }
    h.push_str("</ul>\n");
    let stem = format!("figures/fig{:02}", s.number);
    h.push_str(&format!(
        "<figure><a href=\"{stem}.svg\"><img src=\"{stem}.png\" alt=\"{}\"></a>\
         <figcaption class=\"muted\">{} (click for the SVG)</figcaption></figure>\n",
        escape(&heading.title),
        escape(&s.title)
    ));
    let mine: Vec<&ClaimVerdict> = p
        .verdicts
        .claims
        .iter()
        .filter(|c| c.claim.figure == s.number)
        .collect();
    if mine.is_empty() {
        h.push_str("<p>No claim of the registry rests on this figure.</p>\n");
    } else {
        h.push_str("<ul>");
        for c in mine {
            let tag = c.decision.verdict.tag();
            h.push_str(&format!(
                "<li><code>{}</code>: <span class=\"{tag}\">{tag}</span> {}</li>",
                escape(&c.claim.id),
                escape(&detail(c))
            ));
        }
        h.push_str("</ul>\n");
    }
    if let Some(run) = run {
        let data: Vec<String> = run
            .files
            .iter()
            .filter(|f| f.ends_with(".csv") || f.ends_with(".json"))
            .map(|f| {
                let name = f.rsplit('/').next().unwrap_or(f);
                format!("<a href=\"{}\">{}</a>", escape(f), escape(name))
            })
            .collect();
        h.push_str(&format!(
            "<p class=\"muted\">Data: {}. {} in {} s.</p>\n",
            data.join(", "),
            escape(&run.status),
            number(run.seconds)
        ));
    }
    h.push_str("</section>\n");
    h
}

/// `ClaimVerdict::summary(2)` after the tag: why when undetermined, then the deciding
/// numbers, with undefined numbers spelled out.
fn detail(c: &ClaimVerdict) -> String {
    let d = &c.decision;
    let mut parts = Vec::new();
    if let Verdict::Undetermined { why } = &d.verdict {
        parts.push(format!("({})", spell_undefined(why)));
    }
    let shown: Vec<String> = d.deciding(2).into_iter().map(|c| c.describe()).collect();
    if !shown.is_empty() {
        parts.push(shown.join("; "));
    }
    parts.join(" ")
}

fn provenance(p: &Page) -> String {
    let prov = p.provenance;
    let mut h = String::from("<h2 id=\"provenance\">Provenance</h2>\n<table>\n");
    let row = |k: &str, v: String| format!("<tr><th>{}</th><td>{v}</td></tr>\n", escape(k));
    h.push_str(&row("trirhythm", escape(&prov.trirhythm)));
    h.push_str(&row(
        "git commit",
        format!("<code>{}</code>", escape(&prov.commit)),
    ));
    h.push_str(&row(
        "quality",
        if prov.quick { "quick" } else { "full" }.into(),
    ));
    h.push_str(&row("formula variant", escape(&prov.variant)));
    h.push_str(&row(
        "figures",
        if prov.from_data {
            "read from figure data (figNN.json)".into()
        } else {
            "computed by this run".into()
        },
    ));
    h.push_str(&row(
        "command",
        format!("<code>{}</code>", escape(&prov.command)),
    ));
    h.push_str(&row(
        "total run time",
        format!("{} s", number(prov.total_seconds)),
    ));
    h.push_str(&row(
        "verdicts as data",
        "<a href=\"verdicts.json\">verdicts.json</a>".into(),
    ));
    h.push_str("</table>\n");
    // seeds and run times per figure
    h.push_str(
        "<h3>Per figure</h3>\n<p class=\"muted\">Seeds and run sizes are stated in each \
         figure's caption; the lines naming seeds are repeated here.</p>\n<table>\n<thead><tr>\
         <th>Figure</th><th>Status</th><th>Time (s)</th><th>Seeds</th></tr></thead>\n<tbody>\n",
    );
    for s in p.sections {
        let run = prov.figures.iter().find(|f| f.figure == s.number);
        let seeds: Vec<String> = s
            .heading
            .iter()
            .flat_map(|h| h.lines.iter())
            .filter(|l| l.to_lowercase().contains("seed"))
            .map(|l| escape(l))
            .collect();
        h.push_str(&format!(
            "<tr><td><a href=\"#{}\">Fig. {}</a></td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
            fig_id(s.number),
            s.number,
            run.map(|r| escape(&r.status)).unwrap_or_default(),
            run.map(|r| number(r.seconds)).unwrap_or_default(),
            if seeds.is_empty() {
                "—".to_string()
            } else {
                seeds.join("<br>")
            }
        ));
    }
    h.push_str("</tbody>\n</table>\n");
    h
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
        });
        assert_eq!(html.matches("data-claim=\"fig04-roots\"").count(), 1);
        for n in not_computable() {
            assert_eq!(html.matches(&format!("data-claim=\"{}\"", n.id)).count(), 1);
        }
        assert!(html.contains("&lt;unknown&gt;") && !html.contains("<unknown>"));
        assert!(html.contains("f &amp; roots"));
        assert!(html.contains("data-missing=\"4\""));
    }
}

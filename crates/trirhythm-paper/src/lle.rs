//! The largest Lyapunov exponent against the noise intensity (Figs 17, 18) and what Fig. 19
//! shares with them: run sizes at quick or paper quality, panels of curves with error bars and
//! the words for a critical-noise search.
//!
//! Figs 17 and 18 are one computation, [`lle_against_noise_figure`], with two configurations
//! ([`LleNoiseFigure`]): two panels, each a set of curves (one per value of a parameter) of the
//! LLE against D, and per curve a verdict on the paper's claim that the LLE turns positive past
//! a critical D (a sign change by two standard errors).
//!
//! Method: [`largest_lyapunov`] with frozen noise: two trajectories with whole-memory
//! renormalisation, the finite-time exponent over a window after a transient, mean ± standard
//! error over noise realisations. Checked by the library's Lyapunov tests (a linear system's
//! exponent is its eigenvalue's real part) and `tests/figures.rs`.

use crate::notes::{caption, num, sig, symbol, table_notes, Caption};
use crate::table::Table;
use crate::{FigureOptions, Monitor};
use serde::{Deserialize, Serialize};
use trirhythm::analysis::lyapunov::{largest_lyapunov, CriticalNoise, LyapunovSpec, NoisePoint};
use trirhythm::engine::{ImpactMemory, PredictorCorrector, Problem};
use trirhythm::model::{preset, Params};
use trirhythm::monitor::OnlyCancel;
use trirhythm::Result;

/// Sizes of the runs behind one LLE.
pub struct Sizes {
    /// Paths, transient, window.
    pub spec: LyapunovSpec,
    /// The method.
    pub method: PredictorCorrector,
}

impl Sizes {
    /// Quick (CI) or paper quality.
    pub fn of(quick: bool) -> Sizes {
        let spec = if quick {
            LyapunovSpec {
                paths: 2,
                seed: 1,
                transient: 20.0,
                length: 100.0,
                ..Default::default()
            }
        } else {
            LyapunovSpec {
                paths: 8,
                seed: 1,
                transient: 500.0,
                length: 4000.0,
                ..Default::default()
            }
        };
        let method = PredictorCorrector {
            impact_memory: ImpactMemory::Restart,
            ..Default::default()
        };
        Sizes { spec, method }
    }

    /// One line for headings and notes.
    pub fn describe(&self) -> String {
        format!(
            "LLE with frozen noise, two trajectories with whole-memory renormalisation (d0 = {}, \
             every {} steps), predictor-corrector dt = {}, restart impact memory, U(0) = {}; \
             finite-time exponent over a window of {} after a transient of {}; mean ± standard \
             error over {} noise realisations (seed {})",
            num(self.spec.separation),
            self.spec.renormalise_every,
            num(self.method.dt),
            num(Problem::DEFAULT_START.0),
            num(self.spec.length),
            num(self.spec.transient),
            self.spec.paths,
            self.spec.seed
        )
    }
}

/// A point with its error bar (NaN y: nothing to draw there).
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct Point {
    /// Abscissa.
    pub x: f64,
    /// Ordinate (NaN when undefined, e.g. no sign change).
    #[serde(with = "trirhythm::non_finite")]
    pub y: f64,
    /// Lower end of the error bar.
    #[serde(with = "trirhythm::non_finite")]
    pub lo: f64,
    /// Upper end of the error bar.
    #[serde(with = "trirhythm::non_finite")]
    pub hi: f64,
}

/// One curve of a panel.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Curve {
    /// Legend text.
    pub label: String,
    /// Its points.
    pub points: Vec<Point>,
}

/// One panel.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Panel {
    /// Caption above the chart.
    pub caption: String,
    /// Key of the abscissa in the CSV.
    pub x_key: String,
    /// Axis descriptions.
    pub x_desc: String,
    /// Axis descriptions.
    pub y_desc: String,
    /// Key of the ordinate in the CSV.
    pub y_key: String,
    /// The curves.
    pub curves: Vec<Curve>,
    /// Short verdicts drawn inside the chart's top-left corner.
    pub verdicts: Vec<String>,
}

/// A panel of LLE against D, one curve per value of `key`, with its notes (a verdict per
/// curve on the paper's claim that the LLE turns positive past a critical D).
pub fn lle_against_noise(
    monitor: &dyn Monitor,
    caption: &str,
    base: &Params,
    key: &str,
    values: &[f64],
    noises: &[f64],
    sizes: &Sizes,
) -> Result<(Panel, Vec<String>)> {
    let mut curves = Vec::new();
    let mut notes = Vec::new();
    let (mut pos, mut neg, mut all, mut merged_points) = (0, 0, 0, 0);
    let total = values.len() * noises.len();
    for (i, &v) in values.iter().enumerate() {
        let mut points = Vec::new();
        for (k, &d) in noises.iter().enumerate() {
            crate::step(monitor, i * noises.len() + k, total)?;
            let p = base.with(key, v)?.with("D", d)?;
            let problem = Problem::from_params(&p)?;
            let r = largest_lyapunov(&problem, &sizes.method, &sizes.spec, &OnlyCancel(monitor))?;
            if r.merged > 0 {
                merged_points += 1;
                let when: Vec<String> = r
                    .per_path
                    .iter()
                    .filter_map(|q| {
                        q.merged_at
                            .map(|t| format!("{} at t = {}", q.path, sig(t, 4)))
                    })
                    .collect();
                notes.push(format!(
                    "{caption}, {} = {}, D = {}: LLE −∞, not drawn: {} of {} realisations merged (the copy became identical to its reference, both stuck at the wall on the same step with the memory restarted; path {}); the other {}: {}",
                    symbol(key),
                    num(v),
                    sig(d, 4),
                    r.merged,
                    r.per_path.len(),
                    when.join(", path "),
                    r.per_path.len() - r.merged,
                    if r.unmerged.value.is_finite() {
                        format!("{} ± {}", sig(r.unmerged.value, 3), sig(r.unmerged.stderr, 2))
                    } else {
                        "none".into()
                    }
                ));
            }
            let s = if r.lle.stderr.is_finite() {
                r.lle.stderr
            } else {
                0.0
            };
            points.push(Point {
                x: d,
                y: r.lle.value,
                lo: r.lle.value - s,
                hi: r.lle.value + s,
            });
        }
        // two standard errors; a −∞ point (merged realisations) has no sign
        let two_se = |q: &Point| (q.hi - q.lo) / 2.0 * 2.0;
        let p_count = points
            .iter()
            .filter(|q| q.y.is_finite() && q.y > two_se(q))
            .count();
        let n_count = points
            .iter()
            .filter(|q| q.y.is_finite() && q.y < -two_se(q))
            .count();
        pos += p_count;
        neg += n_count;
        all += points.len();
        let first_pos = points
            .iter()
            .find(|q| q.y.is_finite() && q.y > two_se(q))
            .map(|q| q.x);
        let neg_before = first_pos.is_some_and(|d0| {
            points
                .iter()
                .any(|q| q.x < d0 && q.y.is_finite() && q.y < -two_se(q))
        });
        notes.push(format!(
            "{caption}, {} = {}: LLE > 0 by 2 standard errors at {p_count} of {} D, < 0 at {n_count}; {}",
            symbol(key),
            num(v),
            points.len(),
            match (first_pos, neg_before) {
                (Some(d0), true) => format!("sign change negative → positive below D = {}: the paper's claim holds here", num(d0)),
                (Some(d0), false) => format!("positive from D = {} without a significantly negative LLE below: no critical noise in the range (the paper's claim not reproduced)", num(d0)),
                (None, _) if n_count > 0 => "never significantly positive: no transition to chaos in the range (the paper's claim not reproduced)".into(),
                (None, _) => "indistinguishable from 0 throughout".into(),
            }
        ));
        curves.push(Curve {
            label: format!("{} = {}", symbol(key), num(v)),
            points,
        });
    }
    let panel = Panel {
        caption: caption.into(),
        x_key: "D".into(),
        x_desc: "noise intensity D".into(),
        y_desc: "largest Lyapunov exponent".into(),
        y_key: "lle".into(),
        curves,
        verdicts: vec![if merged_points > 0 {
            format!(
                "LLE > 0 (2 s.e.) at {pos} of {all} points, < 0 at {neg}; −∞ (merged, not drawn) at {merged_points}"
            )
        } else {
            format!("LLE > 0 (2 s.e.) at {pos} of {all} points, < 0 at {neg}")
        }],
    };
    Ok((panel, notes))
}

/// The noise intensities D of a curve of Figs 17 and 18 (the paper does not print them).
pub fn noises(quick: bool) -> Vec<f64> {
    if quick {
        vec![0.05, 1.0, 2.0]
    } else {
        (0..9).map(|k| 0.05 + 0.24375 * k as f64).collect()
    }
}

/// One panel of an LLE-against-noise figure: a preset and the parameter its curves vary.
#[derive(Debug, Clone, Copy)]
pub struct NoisePanel {
    /// Caption, e.g. `(a) τ = 0.06`.
    pub caption: &'static str,
    /// The preset of the panel's base parameters.
    pub preset: &'static str,
    /// The parameter each curve sets.
    pub key: &'static str,
    /// Its values, one curve each.
    pub values: &'static [f64],
}

/// What distinguishes Fig. 17 from Fig. 18.
#[derive(Debug, Clone, Copy)]
pub struct LleNoiseFigure {
    /// The paper's figure number.
    pub number: u32,
    /// The figure's title (registry and table notes).
    pub title: &'static str,
    /// The caption's title.
    pub caption_title: &'static str,
    /// The two panels.
    pub panels: [NoisePanel; 2],
    /// The parameters the panels set (named in the caption, not listed with the shared ones).
    pub varying: &'static [&'static str],
    /// The values chosen where the paper prints none.
    pub choices: &'static str,
}

/// The data of an LLE-against-noise figure (Figs 17 and 18).
#[derive(Serialize, Deserialize)]
pub struct LleAgainstNoise {
    /// What the figure shows, shared parameters, variant, method.
    pub caption: Caption,
    /// Notes of the data table: method, choices, a verdict per curve, merged realisations.
    pub notes: Vec<String>,
    /// Panels (a) and (b).
    pub panels: Vec<Panel>,
}

/// Compute the LLE-against-noise figure `figure`.
pub fn lle_against_noise_figure(
    figure: &LleNoiseFigure,
    options: &FigureOptions,
    monitor: &dyn Monitor,
) -> Result<LleAgainstNoise> {
    let sz = Sizes::of(options.quick);
    let d = noises(options.quick);
    let mut panels = Vec::new();
    let mut notes = vec![
        sz.describe(),
        figure.choices.to_string(),
        "error bars: ± one standard error over noise realisations; the exponents are finite-time exponents over the window stated (λ < 1: Mittag-Leffler tails, README \"Lyapunov exponents\")".into(),
    ];
    let mut first = None;
    for panel in &figure.panels {
        let base = preset(panel.preset)?.params;
        let (p, n) = lle_against_noise(
            monitor,
            panel.caption,
            &base,
            panel.key,
            panel.values,
            &d,
            &sz,
        )?;
        first.get_or_insert(base);
        panels.push(p);
        notes.extend(n);
    }
    let base = first.expect("two panels");
    let caption = caption(
        figure.number,
        figure.caption_title,
        options,
        &base,
        figure.varying,
        vec![sz.describe()],
    );
    Ok(LleAgainstNoise {
        caption,
        notes: table_notes(figure.number, figure.title, options, &notes),
        panels,
    })
}

/// The LLE's sign over the evaluated D of a search without a sign change, D with a merged
/// realisation aside.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sign {
    /// Negative at every D.
    Negative,
    /// Positive at every D.
    Positive,
    /// Negative at every D without a merged realisation.
    NegativeOrMerged,
    /// Positive at every D without a merged realisation.
    PositiveOrMerged,
    /// A realisation merged at every D.
    AllMerged,
}

impl Sign {
    /// The sign of a search's evaluated points.
    pub fn of(c: &CriticalNoise) -> Self {
        let signed: Vec<f64> = c
            .evaluated
            .iter()
            .filter(|q| q.merged == 0)
            .map(|q| q.lle.value)
            .collect();
        let merged = signed.len() < c.evaluated.len();
        match (signed.is_empty(), signed.iter().all(|&v| v < 0.0), merged) {
            (true, _, _) => Sign::AllMerged,
            (false, true, false) => Sign::Negative,
            (false, false, false) => Sign::Positive,
            (false, true, true) => Sign::NegativeOrMerged,
            (false, false, true) => Sign::PositiveOrMerged,
        }
    }

    /// In a sentence: "LLE {words}".
    pub fn words(self) -> &'static str {
        match self {
            Sign::Negative => "negative throughout",
            Sign::Positive => "positive throughout",
            Sign::NegativeOrMerged => "negative at every D without a merged realisation",
            Sign::PositiveOrMerged => "positive at every D without a merged realisation",
            Sign::AllMerged => "without a sign: a realisation merged at every D",
        }
    }

    /// Short, for a figure's verdict line.
    pub fn tag(self) -> &'static str {
        match self {
            Sign::Negative => "LLE < 0",
            Sign::Positive => "LLE > 0",
            Sign::NegativeOrMerged => "LLE < 0 or a realisation merged",
            Sign::PositiveOrMerged => "LLE > 0 or a realisation merged",
            Sign::AllMerged => "a realisation merged at every D",
        }
    }
}

/// The evaluated D of a critical-noise search at which a realisation merged, in words.
pub fn merged_points_text(c: &CriticalNoise) -> Vec<String> {
    c.evaluated
        .iter()
        .filter(|q| q.merged > 0)
        .map(noise_point_text)
        .collect()
}

/// An evaluated D of a critical-noise search in words: "D: LLE ± s.e.", or the merged count.
pub fn noise_point_text(q: &NoisePoint) -> String {
    if q.merged > 0 {
        format!("{}: −∞ ({} merged)", sig(q.d, 4), q.merged)
    } else {
        format!(
            "{}: {} ± {}",
            sig(q.d, 4),
            sig(q.lle.value, 3),
            sig(q.lle.stderr, 2)
        )
    }
}

/// The table of panels: `panel,curve,X,Y,Y_lo,Y_hi` (points without a value are left out and
/// named in the header's notes by the figure).
pub fn panels_table(notes: &[String], panels: &[Panel]) -> Table {
    let mut csv = Table::new(
        notes,
        &["panel", "curve", "x_key", "x", "y_key", "y", "y_lo", "y_hi"],
    );
    for p in panels {
        for c in &p.curves {
            for q in c.points.iter().filter(|q| q.y.is_finite()) {
                csv.row([
                    p.caption
                        .split(')')
                        .next()
                        .unwrap_or("")
                        .trim_start_matches('(')
                        .into(),
                    c.label.replace(',', ";"),
                    p.x_key.clone(),
                    num(q.x),
                    p.y_key.clone(),
                    num(q.y),
                    num(q.lo),
                    num(q.hi),
                ]);
            }
        }
    }
    csv
}

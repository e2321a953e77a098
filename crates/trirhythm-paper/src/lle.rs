//! The largest Lyapunov exponent against the noise intensity (Figs 17, 18) and what Fig. 19
//! shares with them: run sizes at quick or paper quality, the step rule, the two starts, panels
//! of curves with error bars and the words for a critical-noise search.
//!
//! Figs 17 and 18 are one computation, [`lle_against_noise_figure`], with two configurations
//! ([`LleNoiseFigure`]): two panels, each a set of curves (one per value of a parameter and per
//! start) of the LLE against D on a log-spaced grid ([`noises`]). Every curve is computed from
//! two starts ([`StartKind`]): U(0) = 1 (the basin of rest) and U(0) = the outer stable cycle's
//! amplitude of the averaged theory at D = 0 for the curve's parameters ([`outer_amplitude`];
//! none: the curve says so and has no points). The verdicts (sign change by Student's t with
//! Holm–Bonferroni, `verdict::rules::sign_change`) are stated per start.
//!
//! Step: Δt = the largest of [`DT_LADDER`] not above τ/10 ([`dt_for`]): the coloured noise's
//! correlation time is resolved by at least ten steps (at Δt = 0.01 and τ = 0.025 the exponent
//! was ≈ 6 % low against Δt = 0.0025, an under-resolved noise at impacts).
//!
//! Method: [`largest_lyapunov`] with frozen noise: two trajectories with whole-memory
//! renormalisation, the finite-time exponent over a window after a transient, mean ± standard
//! error over noise realisations. Checked by the library's Lyapunov tests (a linear system's
//! exponent is its eigenvalue's real part) and `tests/figures.rs`.

use crate::notes::{caption, num, sig, symbol, table_notes, variant_line, Caption};
use crate::table::Table;
use crate::verdict::rules::{significance, LleCurve, LlePoint, PointSign};
use crate::{FigureOptions, Monitor};
use serde::{Deserialize, Serialize};
use trirhythm::analysis::lyapunov::{largest_lyapunov, CriticalNoise, LyapunovSpec, NoisePoint};
use trirhythm::engine::{ImpactMemory, PredictorCorrector, Problem};
use trirhythm::maths;
use trirhythm::model::{preset, Params};
use trirhythm::monitor::OnlyCancel;
use trirhythm::theory::averaging::{Theory, Variant};
use trirhythm::Result;

/// The steps Δt may take: whole fractions of the windows, from the figures' former 0.01 down.
pub const DT_LADDER: [f64; 8] = [0.01, 0.005, 0.0025, 0.002, 0.001, 0.0005, 0.00025, 0.0001];

/// The step for correlation time `tau`: the largest of [`DT_LADDER`] not above τ/10 (0.01 for
/// τ ≥ 0.1 and for white noise, τ = 0; the smallest rung below τ = 0.001).
pub fn dt_for(tau: f64) -> f64 {
    if tau <= 0.0 {
        return DT_LADDER[0];
    }
    DT_LADDER
        .iter()
        .copied()
        .find(|&dt| dt <= tau / 10.0 * (1.0 + 1e-12))
        .unwrap_or(DT_LADDER[DT_LADDER.len() - 1])
}

/// Sizes of the runs behind one LLE.
pub struct Sizes {
    /// Paths, transient, window.
    pub spec: LyapunovSpec,
}

impl Sizes {
    /// Quick (CI) or paper quality of Figs 17 and 18.
    pub fn of(quick: bool) -> Sizes {
        Sizes::with_window(quick, 100.0, 1500.0)
    }

    /// Quick (2 realisations, transient 20, window `quick_window`) or paper quality (8
    /// realisations, transient 200, window `full_window`), seed 1.
    pub fn with_window(quick: bool, quick_window: f64, full_window: f64) -> Sizes {
        let (paths, transient, length) = if quick {
            (2, 20.0, quick_window)
        } else {
            (8, 200.0, full_window)
        };
        Sizes {
            spec: LyapunovSpec {
                paths,
                seed: 1,
                transient,
                length,
                ..Default::default()
            },
        }
    }

    /// The integrator for correlation time `tau`: Δt from [`dt_for`], restart impact memory.
    pub fn method(&self, tau: f64) -> PredictorCorrector {
        PredictorCorrector {
            impact_memory: ImpactMemory::Restart,
            dt: dt_for(tau),
            ..Default::default()
        }
    }

    /// One line for headings and notes.
    pub fn describe(&self) -> String {
        format!(
            "LLE with frozen noise, two trajectories with whole-memory renormalisation (d0 = {}, \
             every {} steps), predictor-corrector with Δt = the largest of {{{}}} not above τ/10, \
             restart impact memory; finite-time exponent over a window of {} after a transient \
             of {}; mean ± standard error over {} noise realisations (seed {})",
            num(self.spec.separation),
            self.spec.renormalise_every,
            DT_LADDER[..5]
                .iter()
                .map(|&d| num(d))
                .collect::<Vec<_>>()
                .join(", "),
            num(self.spec.length),
            num(self.spec.transient),
            self.spec.paths,
            self.spec.seed
        )
    }
}

/// Where the paths of a curve start.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StartKind {
    /// U(0) = 1, U̇(0) = 0: the basin of the rest state where it is stable.
    Rest,
    /// U(0) = the outer stable cycle's amplitude of the averaged theory, U̇(0) = 0.
    Outer,
}

impl StartKind {
    /// Both, in drawing order.
    pub const BOTH: [StartKind; 2] = [StartKind::Rest, StartKind::Outer];

    /// Short name (CSV, legends).
    pub fn name(self) -> &'static str {
        match self {
            StartKind::Rest => "rest",
            StartKind::Outer => "outer",
        }
    }

    /// In words, for verdicts.
    pub fn words(self) -> &'static str {
        match self {
            StartKind::Rest => "from the rest basin (U(0) = 1)",
            StartKind::Outer => "from the outer cycle (U(0) = its averaged amplitude)",
        }
    }

    /// U(0) for `params` (D is ignored): 1, or the outer cycle's amplitude (`None`: no outer
    /// stable cycle).
    pub fn u0(self, params: &Params, variant: Variant) -> Result<Option<f64>> {
        match self {
            StartKind::Rest => Ok(Some(Problem::DEFAULT_START.0)),
            StartKind::Outer => outer_amplitude(params, variant),
        }
    }
}

/// The amplitude of the outer (largest) stable limit cycle of the averaged theory for `params`
/// at D = 0, or `None` when the averaged system has no stable cycle.
pub fn outer_amplitude(params: &Params, variant: Variant) -> Result<Option<f64>> {
    let p = params.with("D", 0.0)?;
    let theory = Theory::new(&p, variant)?;
    Ok(theory
        .limit_cycles()
        .into_iter()
        .filter(|c| c.stable && c.amplitude.is_finite())
        .map(|c| c.amplitude)
        .fold(None, |m: Option<f64>, a| Some(m.map_or(a, |m| m.max(a)))))
}

/// What a point of a curve holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Flag {
    /// A finite exponent with its standard error.
    #[default]
    Value,
    /// A realisation's copy merged with its reference: the mean is −∞ (no sign).
    Merged,
    /// No value (no standard error with one realisation, or a non-finite result).
    Undefined,
}

impl Flag {
    /// The flag of an exponent `y ± se` from realisations of which `merged` merged.
    pub fn of(merged: usize, y: f64, se: f64) -> Flag {
        if merged > 0 {
            Flag::Merged
        } else if y.is_finite() && se.is_finite() {
            Flag::Value
        } else {
            Flag::Undefined
        }
    }

    /// The CSV cell.
    pub fn name(self) -> &'static str {
        match self {
            Flag::Value => "",
            Flag::Merged => "merged",
            Flag::Undefined => "undefined",
        }
    }
}

/// A point with its error bar (NaN y: nothing to draw there).
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct Point {
    /// Abscissa.
    pub x: f64,
    /// Ordinate (NaN or −∞ when undefined: see `flag`).
    #[serde(with = "trirhythm::non_finite")]
    pub y: f64,
    /// Lower end of the error bar (y − se).
    #[serde(with = "trirhythm::non_finite")]
    pub lo: f64,
    /// Upper end of the error bar (y + se).
    #[serde(with = "trirhythm::non_finite")]
    pub hi: f64,
    /// Standard error over realisations (NaN where none).
    #[serde(with = "trirhythm::non_finite", default = "nan")]
    pub se: f64,
    /// Realisations behind the value (the t test has n − 1 degrees of freedom).
    #[serde(default)]
    pub n: usize,
    /// What the point holds.
    #[serde(default)]
    pub flag: Flag,
    /// The sign decided with significance over the panel and start (Holm–Bonferroni).
    #[serde(default = "undefined_sign")]
    pub sign: PointSign,
}

fn nan() -> f64 {
    f64::NAN
}

fn undefined_sign() -> PointSign {
    PointSign::Undefined
}

/// One curve of a panel.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Curve {
    /// Legend text.
    pub label: String,
    /// The parameter's value of the curve.
    #[serde(default = "nan", with = "trirhythm::non_finite")]
    pub value: f64,
    /// Where its paths start.
    #[serde(default = "rest")]
    pub start: StartKind,
    /// U(0) (NaN: no outer stable cycle, no points).
    #[serde(default = "nan", with = "trirhythm::non_finite")]
    pub u0: f64,
    /// The step Δt (NaN for a curve that is not an LLE run).
    #[serde(default = "nan", with = "trirhythm::non_finite")]
    pub dt: f64,
    /// Its points.
    pub points: Vec<Point>,
}

fn rest() -> StartKind {
    StartKind::Rest
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

/// Points at finite abscissae whose brackets [lo, hi] are in order.
fn points_in_order(field: &str, points: &[Point]) -> crate::validate::Valid {
    for (k, p) in points.iter().enumerate() {
        if !p.x.is_finite() || p.lo > p.hi || p.y.is_nan() && p.n > 1 && p.lo.is_finite() {
            return crate::validate::invalid(
                format!("{field}[{k}]"),
                format!(
                    "x = {}, y = {} in [{}, {}]: x must be finite and the bracket ordered",
                    p.x, p.y, p.lo, p.hi
                ),
            );
        }
    }
    Ok(())
}

impl Panel {
    /// Every curve's value finite and its points at finite abscissae with ordered brackets
    /// ([`crate::validate`]).
    pub fn validate(&self, field: &str) -> crate::validate::Valid {
        for (j, c) in self.curves.iter().enumerate() {
            let f = format!("{field}.curves[{j}]");
            // u0 is NaN where the start does not exist (no outer cycle)
            crate::validate::finite(&format!("{f}.value"), &[c.value])?;
            if !(c.dt > 0.0 && c.dt.is_finite()) {
                return crate::validate::invalid(
                    format!("{f}.dt"),
                    format!("{} is not a step", c.dt),
                );
            }
            points_in_order(&format!("{f}.points"), &c.points)?;
        }
        Ok(())
    }

    /// The curves of one start with their points as the sign-change rule reads them (a curve
    /// without points, no outer cycle, is left out).
    pub fn lle_curves(&self, start: StartKind) -> Vec<LleCurve> {
        self.curves
            .iter()
            .filter(|c| c.start == start && !c.points.is_empty())
            .map(lle_curve)
            .collect()
    }

    /// The labels of the curves of `start` without an outer stable cycle.
    pub fn without_cycle(&self, start: StartKind) -> Vec<String> {
        self.curves
            .iter()
            .filter(|c| c.start == start && c.points.is_empty())
            .map(|c| c.label.clone())
            .collect()
    }
}

/// A curve's points as the sign-change rule reads them: the value, its standard error and
/// realisations − 1 degrees of freedom (no test where the flag is not a value).
pub fn lle_curve(c: &Curve) -> LleCurve {
    LleCurve {
        label: c.label.clone(),
        points: c
            .points
            .iter()
            .map(|q| LlePoint {
                d: q.x,
                lle: if q.flag == Flag::Value { q.y } else { f64::NAN },
                se: q.se,
                dof: Some(q.n.saturating_sub(1).max(1) as f64),
            })
            .collect(),
    }
}

/// Decide every point's sign over `curves` (Holm–Bonferroni over all their points) and store
/// it in the points.
pub fn mark_signs(curves: &mut [&mut Curve]) {
    let rule: Vec<LleCurve> = curves.iter().map(|c| lle_curve(c)).collect();
    for (c, signs) in curves.iter_mut().zip(significance(&rule)) {
        for (q, s) in c.points.iter_mut().zip(signs) {
            q.sign = s;
        }
    }
}

/// One LLE at parameters `p` from `u0`: a point at abscissa `x` (merged realisations: −∞, flagged),
/// and a note when a realisation merged.
pub fn lle_point(
    monitor: &dyn Monitor,
    p: &Params,
    u0: f64,
    x: f64,
    sizes: &Sizes,
    what: &str,
) -> Result<(Point, Option<String>)> {
    let problem = Problem::from_params(p)?.with_start(u0, 0.0)?;
    let method = sizes.method(p.correlation_time);
    let r = largest_lyapunov(&problem, &method, &sizes.spec, &OnlyCancel(monitor))?;
    let mut note = None;
    if r.merged > 0 {
        let when: Vec<String> = r
            .per_path
            .iter()
            .filter_map(|q| {
                q.merged_at
                    .map(|t| format!("{} at t = {}", q.path, sig(t, 4)))
            })
            .collect();
        note = Some(format!(
            "{what}: LLE −∞, not drawn: {} of {} realisations merged (the copy became identical to its reference, both stuck at the wall on the same step with the memory restarted; path {}); the other {}: {}",
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
    let (y, se) = (r.lle.value, r.lle.stderr);
    let flag = Flag::of(r.merged, y, se);
    let point = if flag == Flag::Value {
        Point {
            x,
            y,
            lo: y - se,
            hi: y + se,
            se,
            n: r.per_path.len(),
            flag,
            sign: PointSign::Undefined,
        }
    } else {
        Point {
            x,
            y,
            lo: f64::NAN,
            hi: f64::NAN,
            se: f64::NAN,
            n: r.per_path.len(),
            flag,
            sign: PointSign::Undefined,
        }
    };
    Ok((point, note))
}

/// Counts of significant signs of a start's points, for a panel's verdict line.
fn sign_counts(curves: &[Curve], start: StartKind) -> String {
    let pts: Vec<&Point> = curves
        .iter()
        .filter(|c| c.start == start)
        .flat_map(|c| c.points.iter())
        .collect();
    let count = |s: PointSign| pts.iter().filter(|q| q.sign == s).count();
    let merged = pts.iter().filter(|q| q.flag == Flag::Merged).count();
    format!(
        "{}: + at {}, − at {}, n.s. at {}{} of {}",
        start.name(),
        count(PointSign::Positive),
        count(PointSign::Negative),
        count(PointSign::NotSignificant),
        if merged > 0 {
            format!(", merged at {merged}")
        } else {
            String::new()
        },
        pts.len()
    )
}

/// A panel of LLE against D, one curve per value of `key` and start, with its notes (per curve
/// the outcome of the sign-change rule, significance over the panel's curves of one start).
#[allow(clippy::too_many_arguments)]
pub fn lle_against_noise(
    monitor: &dyn Monitor,
    caption: &str,
    base: &Params,
    key: &str,
    values: &[f64],
    noises: &[f64],
    sizes: &Sizes,
    variant: Variant,
    (first, total): (usize, usize),
) -> Result<(Panel, Vec<String>)> {
    let mut curves = Vec::new();
    let mut notes = Vec::new();
    let mut step = first;
    for start in StartKind::BOTH {
        for &v in values {
            let p = base.with(key, v)?;
            let label = format!("{} = {}, {}", symbol(key), num(v), start.name());
            let dt = dt_for(p.correlation_time);
            let mut points = Vec::new();
            let u0 = start.u0(&p, variant)?;
            match u0 {
                None => {
                    notes.push(format!(
                        "{caption}, {} = {}: no outer stable cycle in the averaged theory ({} formulas): no outer-cycle start, no points",
                        symbol(key),
                        num(v),
                        variant.name()
                    ));
                    step += noises.len();
                }
                Some(u0) => {
                    for &d in noises {
                        crate::step(monitor, step, total)?;
                        step += 1;
                        let what = format!(
                            "{caption}, {} = {}, start U(0) = {}, D = {}",
                            symbol(key),
                            num(v),
                            sig(u0, 4),
                            sig(d, 4)
                        );
                        let (q, note) = lle_point(monitor, &p.with("D", d)?, u0, d, sizes, &what)?;
                        points.push(q);
                        notes.extend(note);
                    }
                }
            }
            curves.push(Curve {
                label,
                value: v,
                start,
                u0: u0.unwrap_or(f64::NAN),
                dt,
                points,
            });
        }
    }
    let mut verdicts = Vec::new();
    for start in StartKind::BOTH {
        let mut of_start: Vec<&mut Curve> =
            curves.iter_mut().filter(|c| c.start == start).collect();
        mark_signs(&mut of_start);
        verdicts.push(sign_counts(&curves, start));
        for c in curves
            .iter()
            .filter(|c| c.start == start && !c.points.is_empty())
        {
            let ds: Vec<f64> = c.points.iter().map(|q| q.x).collect();
            let signs: Vec<PointSign> = c.points.iter().map(|q| q.sign).collect();
            let located = crate::verdict::rules::locate(&ds, &signs);
            notes.push(format!(
                "{caption}, {} (U(0) = {}, Δt = {}): {} (Student's t, Holm–Bonferroni over the panel's {} points of this start)",
                c.label,
                sig(c.u0, 4),
                num(c.dt),
                located.words(ds[0]),
                curves
                    .iter()
                    .filter(|k| k.start == start)
                    .map(|k| k.points.len())
                    .sum::<usize>()
            ));
        }
    }
    let dts: Vec<String> = {
        let mut d: Vec<f64> = curves.iter().map(|c| c.dt).collect();
        d.sort_by(f64::total_cmp);
        d.dedup();
        d.iter().map(|&x| num(x)).collect()
    };
    verdicts.push(format!(
        "filled: rest start, open: outer cycle; Δt = {}",
        dts.join(", ")
    ));
    let panel = Panel {
        caption: caption.into(),
        x_key: "D".into(),
        x_desc: "noise intensity D (log scale)".into(),
        y_desc: "largest Lyapunov exponent".into(),
        y_key: "lle".into(),
        curves,
        verdicts,
    };
    Ok((panel, notes))
}

/// The noise intensities D of a curve of Figs 17 and 18 (the paper does not print them):
/// log-spaced from 0.001 to 2 (ten values; three at quick quality).
pub fn noises(quick: bool) -> Vec<f64> {
    if quick {
        vec![0.01, 0.3, 2.0]
    } else {
        log_spaced(0.001, 2.0, 10)
    }
}

/// `n` values log-spaced from `lo` to `hi`, both included, rounded to 3 significant digits.
pub fn log_spaced(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| {
            let t = k as f64 / (n - 1).max(1) as f64;
            // the library's platform-independent maths: the same noise levels everywhere
            let v = maths::exp(maths::ln(lo) + t * (maths::ln(hi) - maths::ln(lo)));
            sig(v, 3).parse().unwrap_or(v)
        })
        .collect()
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
    /// The representative point of the Δt-convergence check: (panel index, the panel's
    /// parameter value, D), from the rest start.
    pub dt_check: (usize, f64, f64),
}

/// The step multiples of a Δt-convergence check: 4Δt, 2Δt, Δt (the rule's) and Δt/2.
pub const DT_CHECK_FACTORS: [f64; 4] = [4.0, 2.0, 1.0, 0.5];

/// The exponent at one point of a figure at several Δt (rest start, the figure's run sizes).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct DtCheck {
    /// Which panel, parameter and D.
    pub what: String,
    /// The panel's caption letter.
    pub panel: String,
    /// Δt of the rule ([`dt_for`]) at this point.
    pub dt_rule: f64,
    /// One point per Δt (x = Δt), coarsest first.
    pub points: Vec<Point>,
}

impl DtCheck {
    /// Three lines: "Δt check at …:", then the exponents at the two coarser and at the two
    /// finer steps ("0.01: 0.078 ± 0.001; …", the rule's Δt starred).
    pub fn lines(&self) -> Vec<String> {
        let cell = |q: &Point| {
            format!(
                "Δt = {}{}: {}",
                num(q.x),
                if q.x == self.dt_rule { "*" } else { "" },
                if q.flag == Flag::Value {
                    format!("{} ± {}", sig(q.y, 3), sig(q.se, 2))
                } else {
                    q.flag.name().to_string()
                }
            )
        };
        let mut lines = vec![format!(
            "Δt check at {}, {} realisations (* = the rule's Δt):",
            self.what,
            self.points.first().map_or(0, |q| q.n)
        )];
        for pair in self.points.chunks(2) {
            lines.push(pair.iter().map(cell).collect::<Vec<_>>().join("; "));
        }
        lines
    }
}

/// Realisations of a Δt check at full quality (four times a curve's point: the differences
/// between steps are a few per cent of the exponent).
pub const DT_CHECK_PATHS: usize = 32;

/// The exponent of `figure` at its Δt-check point for each of [`DT_CHECK_FACTORS`].
pub fn dt_check(figure: &LleNoiseFigure, sizes: &Sizes, monitor: &dyn Monitor) -> Result<DtCheck> {
    let (k, v, d) = figure.dt_check;
    let panel = &figure.panels[k];
    let p = preset(panel.preset)?
        .params
        .with(panel.key, v)?
        .with("D", d)?;
    let dt_rule = dt_for(p.correlation_time);
    let letter: String = panel
        .caption
        .split(')')
        .next()
        .unwrap_or("")
        .trim_start_matches('(')
        .into();
    let what = format!(
        "({letter}) {} = {}, D = {}, U(0) = 1",
        symbol(panel.key),
        num(v),
        num(d)
    );
    let problem = Problem::from_params(&p)?.with_start(Problem::DEFAULT_START.0, 0.0)?;
    let spec = LyapunovSpec {
        paths: if sizes.spec.paths > 2 {
            DT_CHECK_PATHS
        } else {
            sizes.spec.paths
        },
        ..sizes.spec.clone()
    };
    let mut points = Vec::new();
    for f in DT_CHECK_FACTORS {
        let dt = dt_rule * f;
        let method = PredictorCorrector {
            dt,
            ..sizes.method(p.correlation_time)
        };
        let r = largest_lyapunov(&problem, &method, &spec, &OnlyCancel(monitor))?;
        let (y, se) = (r.lle.value, r.lle.stderr);
        let flag = Flag::of(r.merged, y, se);
        let ok = flag == Flag::Value;
        points.push(Point {
            x: dt,
            y,
            lo: if ok { y - se } else { f64::NAN },
            hi: if ok { y + se } else { f64::NAN },
            se: if ok { se } else { f64::NAN },
            n: r.per_path.len(),
            flag,
            sign: PointSign::Undefined,
        });
    }
    Ok(DtCheck {
        what,
        panel: letter,
        dt_rule,
        points,
    })
}

/// The table of a Δt check: `dt,lle,se,n,flag,used` (suffix `_dt`).
pub fn dt_check_table(notes: &[String], check: &DtCheck) -> Table {
    let mut t = Table::new(notes, &["dt", "lle", "se", "n", "flag", "used"]).named("_dt");
    for q in &check.points {
        let ok = q.flag == Flag::Value;
        t.row([
            num(q.x),
            if ok { num(q.y) } else { String::new() },
            if ok { num(q.se) } else { String::new() },
            q.n.to_string(),
            q.flag.name().into(),
            (q.x == check.dt_rule).to_string(),
        ]);
    }
    t
}

/// The data of an LLE-against-noise figure (Figs 17 and 18).
#[derive(Serialize, Deserialize)]
pub struct LleAgainstNoise {
    /// What the figure shows, shared parameters, method.
    pub caption: Caption,
    /// Notes of the data table: method, choices, a verdict per curve, merged realisations.
    pub notes: Vec<String>,
    /// Panels (a) and (b).
    pub panels: Vec<Panel>,
    /// The exponent at one representative point at 4Δt, 2Δt, Δt and Δt/2.
    pub dt_check: DtCheck,
}

impl LleAgainstNoise {
    /// The figure's tables: the panels and the Δt check (`_dt`).
    /// The panels and the step check ([`crate::validate`]).
    pub fn validate(&self) -> crate::validate::Valid {
        for (i, p) in self.panels.iter().enumerate() {
            p.validate(&format!("panels[{i}]"))?;
        }
        points_in_order("dt_check.points", &self.dt_check.points)
    }

    pub fn tables(&self) -> Vec<Table> {
        vec![
            panels_table(&self.notes, &self.panels),
            dt_check_table(
                &[
                    format!("Δt convergence of the exponent at {}", self.dt_check.what),
                    "used: the step of the rule (the largest of the ladder not above τ/10)".into(),
                ],
                &self.dt_check,
            ),
        ]
    }
}

/// A caption without the formula-variant line (the Lyapunov figures use no averaged formula
/// but the outer start, stated with it).
pub fn lyapunov_caption(
    n: u32,
    title: &str,
    options: &FigureOptions,
    base: &Params,
    varying: &[&str],
    extra: Vec<String>,
) -> Caption {
    let mut c = caption(n, title, options, base, varying, extra);
    let v = variant_line(options.variant);
    c.lines.retain(|l| *l != v);
    c
}

/// The starts in one line, for captions.
pub fn starts_line(variant: Variant) -> String {
    format!(
        "two starts per curve: U(0) = 1 (rest basin; filled markers) and U(0) = the outer stable cycle's amplitude of the averaged theory at D = 0 (--variant {}; open markers); verdicts per start",
        variant.name()
    )
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
        starts_line(options.variant),
        figure.choices.to_string(),
        format!(
            "D: {} values log-spaced in [{}, {}]: {}",
            d.len(),
            num(d[0]),
            num(d[d.len() - 1]),
            d.iter().map(|&x| num(x)).collect::<Vec<_>>().join(", ")
        ),
        "error bars: ± one standard error over noise realisations; signs: z = LLE/se, Student's t with realisations − 1 degrees of freedom, two-sided at 0.05 with Holm–Bonferroni over a panel's points of one start; the exponents are finite-time exponents over the window stated (λ < 1: Mittag-Leffler tails, README \"Lyapunov exponents\")".into(),
    ];
    let per_panel: Vec<usize> = figure
        .panels
        .iter()
        .map(|p| 2 * p.values.len() * d.len())
        .collect();
    let total: usize = per_panel.iter().sum();
    let mut first = None;
    let mut done = 0;
    for (panel, count) in figure.panels.iter().zip(per_panel) {
        let base = preset(panel.preset)?.params;
        let (p, n) = lle_against_noise(
            monitor,
            panel.caption,
            &base,
            panel.key,
            panel.values,
            &d,
            &sz,
            options.variant,
            (done, total),
        )?;
        done += count;
        first.get_or_insert(base);
        panels.push(p);
        notes.extend(n);
    }
    let base = first.expect("two panels");
    let check = dt_check(figure, &sz, monitor)?;
    let lines = check.lines();
    notes.push(format!("{} {}", lines[0], lines[1..].join("; ")));
    if let Some(p) = panels
        .iter_mut()
        .find(|p| p.caption.starts_with(&format!("({})", check.panel)))
    {
        p.verdicts.extend(check.lines());
    }
    let caption = lyapunov_caption(
        figure.number,
        figure.caption_title,
        options,
        &base,
        figure.varying,
        vec![sz.describe(), starts_line(options.variant)],
    );
    Ok(LleAgainstNoise {
        caption,
        notes: table_notes(figure.number, figure.title, options, &notes),
        panels,
        dt_check: check,
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

/// The table of panels: `panel,curve,start,u0,dt,x_key,x,y_key,y,y_lo,y_hi,se,n,sign,flag`;
/// every point is a row, one without a value (merged realisations, undefined) with `y`,
/// `y_lo`, `y_hi`, `se` empty and its `flag` set (`merged`, `undefined`).
pub fn panels_table(notes: &[String], panels: &[Panel]) -> Table {
    let mut csv = Table::new(
        notes,
        &[
            "panel", "curve", "start", "u0", "dt", "x_key", "x", "y_key", "y", "y_lo", "y_hi",
            "se", "n", "sign", "flag",
        ],
    );
    let cell = |v: f64, flag: Flag| {
        if flag == Flag::Value {
            num(v)
        } else {
            String::new()
        }
    };
    for p in panels {
        for c in &p.curves {
            for q in &c.points {
                csv.row([
                    p.caption
                        .split(')')
                        .next()
                        .unwrap_or("")
                        .trim_start_matches('(')
                        .into(),
                    c.label.replace(',', ";"),
                    c.start.name().into(),
                    num(c.u0),
                    num(c.dt),
                    p.x_key.clone(),
                    num(q.x),
                    p.y_key.clone(),
                    cell(q.y, q.flag),
                    cell(q.lo, q.flag),
                    cell(q.hi, q.flag),
                    cell(q.se, q.flag),
                    q.n.to_string(),
                    sign_name(q.sign).into(),
                    q.flag.name().into(),
                ]);
            }
        }
    }
    csv
}

/// The CSV cell of a point's sign.
pub fn sign_name(s: PointSign) -> &'static str {
    match s {
        PointSign::Positive => "+",
        PointSign::Negative => "-",
        PointSign::NotSignificant => "ns",
        PointSign::Undefined => "",
    }
}

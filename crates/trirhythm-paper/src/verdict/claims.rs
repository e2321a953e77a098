//! The paper's checkable claims, each with its words, its place, the rule that decides it and
//! the function computing its [`Decision`] from the figures' data.
//!
//! [`registry`] lists the claims with stable ids (`fig04-roots`, …); [`judge`] decides every
//! claim whose figure is in a [`Figures`] value and returns [`Verdicts`] (serde): the claims,
//! their verdicts and numbers, and the claims that the figure data cannot decide yet
//! ([`not_computable`]). Nothing here is typed text about the outcome: change a figure's data
//! and the verdict follows (tested in `tests/verdicts.rs`).

use super::rules::{
    agreement, closeness, count, sign_change, trend, Comparison, Count, CountSource, Direction,
    LleCurve, LlePoint, Series, CLOSENESS_REL_TOL,
};
use super::{all_of, Decision, Measured};
use crate::fig01_phase_recurrence::Fig01;
use crate::fig02_rhythmicity_planes::Fig02;
use crate::fig03_restitution_planes::{Fig03, R_VALUES as FIG03_R};
use crate::fig04_drift::Fig04;
use crate::fig05_branches::Fig05;
use crate::fig06_fractional_planes::{Fig06, LAMBDA_VALUES as FIG06_LAMBDA};
use crate::fig07_pseudo_potential::{Curve as UeffCurve, Fig07};
use crate::fig08_barriers::Fig08;
use crate::fig09_barrier_surfaces::Fig09;
use crate::fig10_pbif_lambda_tau::{Fig10, D_VALUES as FIG10_D};
use crate::fig11_amplitude_lambda::Fig11;
use crate::fig12_pbif_maps::Fig12;
use crate::fig13_pdf_restitution::Fig13;
use crate::fig17_lle_noise::Fig17;
use crate::fig18_lle_noise_fractional::Fig18;
use crate::fig19_critical_noise::{Fig19, PANELS as FIG19_PANELS};
use crate::lle::Panel as LlePanel;
use crate::maps::MapPanel;
use crate::montecarlo::AmplitudePanel;
use crate::{Figure, FigureOptions, Monitor};
use serde::{Deserialize, Serialize};
use trirhythm::theory::bifurcation::BranchDiagram;
use trirhythm::Result;

/// The figures' data a set of verdicts is computed from; a claim whose figure is absent is
/// not judged.
#[derive(Default)]
#[allow(missing_docs)]
pub struct Figures {
    pub fig01: Option<Fig01>,
    pub fig02: Option<Fig02>,
    pub fig03: Option<Fig03>,
    pub fig04: Option<Fig04>,
    pub fig05: Option<Fig05>,
    pub fig06: Option<Fig06>,
    pub fig07: Option<Fig07>,
    pub fig08: Option<Fig08>,
    pub fig09: Option<Fig09>,
    pub fig10: Option<Fig10>,
    pub fig11: Option<Fig11>,
    pub fig12: Option<Fig12>,
    pub fig13: Option<Fig13>,
    pub fig17: Option<Fig17>,
    pub fig18: Option<Fig18>,
    pub fig19: Option<Fig19>,
}

/// The figures that claims are computed from (Figs 14–16 carry none yet).
pub const JUDGED_FIGURES: [u32; 16] = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 17, 18, 19];

/// The theory figures, cheap and deterministic (seconds in quick mode).
pub const THEORY_FIGURES: [u32; 11] = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12];

impl Figures {
    /// Compute the figures numbered `numbers` (those of [`JUDGED_FIGURES`]; others are
    /// ignored).
    pub fn compute(
        options: &FigureOptions,
        monitor: &dyn Monitor,
        numbers: &[u32],
    ) -> Result<Figures> {
        fn get<F: Figure>(
            numbers: &[u32],
            o: &FigureOptions,
            m: &dyn Monitor,
        ) -> Result<Option<F>> {
            if numbers.contains(&F::NUMBER) {
                F::compute(o, m).map(Some)
            } else {
                Ok(None)
            }
        }
        let (o, m) = (options, monitor);
        Ok(Figures {
            fig01: get(numbers, o, m)?,
            fig02: get(numbers, o, m)?,
            fig03: get(numbers, o, m)?,
            fig04: get(numbers, o, m)?,
            fig05: get(numbers, o, m)?,
            fig06: get(numbers, o, m)?,
            fig07: get(numbers, o, m)?,
            fig08: get(numbers, o, m)?,
            fig09: get(numbers, o, m)?,
            fig10: get(numbers, o, m)?,
            fig11: get(numbers, o, m)?,
            fig12: get(numbers, o, m)?,
            fig13: get(numbers, o, m)?,
            fig17: get(numbers, o, m)?,
            fig18: get(numbers, o, m)?,
            fig19: get(numbers, o, m)?,
        })
    }
}

/// A claim of the paper: its id, words, place and rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Claim {
    /// Stable id (`fig04-roots`).
    pub id: String,
    /// The figure it rests on.
    pub figure: u32,
    /// Where the paper makes it (figure, section, equation).
    pub place: String,
    /// The paper's words (a short quote or a close paraphrase, marked as such).
    pub words: String,
    /// The rule that decides it (`trend`, `count`, `sign_change`, `agreement`, `closeness`).
    pub rule: String,
}

/// A claim with its decision.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClaimVerdict {
    /// The claim.
    pub claim: Claim,
    /// The verdict and its numbers.
    pub decision: Decision,
}

/// A claim the figure data cannot decide yet, and what it needs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NotComputable {
    /// Id.
    pub id: String,
    /// Where the paper makes it.
    pub place: String,
    /// The claim in words.
    pub words: String,
    /// What the figure data lacks.
    pub needs: String,
}

/// The verdicts on every claim judged.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Verdicts {
    /// Claims judged, in registry order.
    pub claims: Vec<ClaimVerdict>,
    /// Claims of the registry whose figure was not in the data.
    pub not_judged: Vec<String>,
    /// Claims the figure data cannot decide yet.
    pub not_computable: Vec<NotComputable>,
}

impl Verdicts {
    /// (confirmed, refuted, undetermined) among the judged claims.
    pub fn counts(&self) -> (usize, usize, usize) {
        let n = |t: &str| {
            self.claims
                .iter()
                .filter(|c| c.decision.verdict.tag() == t)
                .count()
        };
        (n("confirmed"), n("refuted"), n("undetermined"))
    }

    /// The verdict on claim `id`.
    pub fn get(&self, id: &str) -> Option<&ClaimVerdict> {
        self.claims.iter().find(|c| c.claim.id == id)
    }
}

type Judge = fn(&Figures) -> Option<Decision>;

struct Spec {
    id: &'static str,
    figure: u32,
    place: &'static str,
    words: &'static str,
    rule: &'static str,
    judge: Judge,
}

fn specs() -> Vec<Spec> {
    vec![
        Spec {
            id: "fig01-align",
            figure: 1,
            place: "Fig. 1, Sec. 2",
            words: "\"The approximative solution seems to align closely with the results of the numerical predictor-corrector simulations\"",
            rule: "closeness",
            judge: |f| f.fig01.as_ref().map(fig01_align),
        },
        Spec {
            id: "fig02-regions",
            figure: 2,
            place: "Fig. 2(ii), Sec. 3",
            words: "mono-, bi- and trirhythmic regions in the (γ0, δ0) plane (paraphrase: \"displaying trirhythmicity depicted in Fig.2(ii)\")",
            rule: "count",
            judge: |f| f.fig02.as_ref().map(|x| fig02_regions(&x.0.panels)),
        },
        Spec {
            id: "fig03-tri-shrinks",
            figure: 3,
            place: "Fig. 3, Sec. 3",
            words: "\"a decreasing value of r reduces the trirhythmic zone\"",
            rule: "trend",
            judge: |f| {
                f.fig03
                    .as_ref()
                    .map(|x| share_trend(&x.0.panels, &FIG03_R, "r", 3, Direction::Decreases))
            },
        },
        Spec {
            id: "fig04-roots",
            figure: 4,
            place: "Fig. 4, Sec. 3",
            words: "\"we detect five roots\" (r ≈ 1); \"the roots are still five\" (r = 0.98); \"three roots\" (r = 0.96); \"the number of roots is zero\" (r = 0.90)",
            rule: "count",
            judge: |f| f.fig04.as_ref().map(fig04_roots),
        },
        Spec {
            id: "fig05-tri-all-r",
            figure: 5,
            place: "Fig. 5, Sec. 3",
            words: "trirhythmic for all r at μ0 = 0.7 (paraphrase of the text on Fig. 5(e))",
            rule: "count",
            judge: |f| f.fig05.as_ref().map(fig05_tri_all_r),
        },
        Spec {
            id: "fig06-mono-grows",
            figure: 6,
            place: "Fig. 6, Sec. 3",
            words: "\"the monorhythmic zone expands when λ drops\"",
            rule: "trend",
            judge: |f| {
                f.fig06.as_ref().map(|x| {
                    share_trend(&x.0.panels, &FIG06_LAMBDA, "λ", 1, Direction::Increases)
                })
            },
        },
        Spec {
            id: "fig06-bi-tri-shrink",
            figure: 6,
            place: "Fig. 6, Sec. 3",
            words: "\"whereas the birhythmic and trirhythmic zones reduce\"",
            rule: "trend",
            judge: |f| {
                f.fig06.as_ref().map(|x| {
                    all_of(
                        "trend",
                        vec![
                            (
                                "birhythmic".into(),
                                share_trend(&x.0.panels, &FIG06_LAMBDA, "λ", 2, Direction::Decreases),
                            ),
                            (
                                "trirhythmic".into(),
                                share_trend(&x.0.panels, &FIG06_LAMBDA, "λ", 3, Direction::Decreases),
                            ),
                        ],
                    )
                })
            },
        },
        Spec {
            id: "fig07-inner-well",
            figure: 7,
            place: "Fig. 7, Sec. 3",
            words: "\"when r decreases, the potential well in A01 tends to disappear … the quasi-same phenomena is observed with the variation of λ\"",
            rule: "trend",
            judge: |f| f.fig07.as_ref().map(|x| fig07_depths(x, true)),
        },
        Spec {
            id: "fig07-outer-well",
            figure: 7,
            place: "Fig. 7, Sec. 3",
            words: "\"that one in A05 increases in depth\" (as r, and λ, decrease)",
            rule: "trend",
            judge: |f| f.fig07.as_ref().map(|x| fig07_depths(x, false)),
        },
        Spec {
            id: "fig07-wells-move",
            figure: 7,
            place: "Fig. 7, Sec. 3",
            words: "\"the amplitudes A01, A03 and A05 change very slightly when r or λ increases\"",
            rule: "closeness",
            judge: |f| f.fig07.as_ref().map(fig07_wells_move),
        },
        Spec {
            id: "fig08-four-barriers",
            figure: 8,
            place: "Fig. 8, Sec. 3",
            words: "four energy barriers ΔU1–ΔU4 of U_eff at D = 0.24 (Fig. 8)",
            rule: "count",
            judge: |f| f.fig08.as_ref().map(fig08_barriers),
        },
        Spec {
            id: "fig09-lambda",
            figure: 9,
            place: "Fig. 9, Sec. 3",
            words: "\"for the increasing value of λ, ΔU1, ΔU3, ΔU4 are increasing while ΔU2 is decreasing. This is found for all values of correlation time\"",
            rule: "trend",
            judge: |f| f.fig09.as_ref().map(fig09_lambda),
        },
        Spec {
            id: "fig09-r",
            figure: 9,
            place: "Fig. 9, Sec. 3",
            words: "\"excluding ΔU3, the energy is lowered when r falls\"",
            rule: "trend",
            judge: |f| f.fig09.as_ref().map(fig09_r),
        },
        Spec {
            id: "fig10-trimodal-shrinks",
            figure: 10,
            place: "Fig. 10, Sec. 4",
            words: "\"The trirhythmic region in the parameters (λ, τ)-plane decreases with increasing correlated noise\"",
            rule: "trend",
            judge: |f| {
                f.fig10
                    .as_ref()
                    .map(|x| share_trend(&x.0.panels, &FIG10_D, "D", 3, Direction::Decreases))
            },
        },
        Spec {
            id: "fig11b-agreement",
            figure: 11,
            place: "Fig. 11(b), Sec. 4",
            words: "the averaged theory's P(A) (Eq. 27, as printed) agrees with Monte Carlo of Eq. 1 as λ varies",
            rule: "agreement",
            judge: |f| f.fig11.as_ref().map(|x| agreement_of(&x.panels, "Eq. 1", "paper")),
        },
        Spec {
            id: "fig12-omega-mu0-r",
            figure: 12,
            place: "Fig. 12(a, b), Sec. 4",
            words: "\"decreasing ω0 decreases the trirhythmic section in the variable plane (μ0, r)\"",
            rule: "trend",
            judge: |f| f.fig12.as_ref().map(|x| fig12_omega(&x.0.panels, ["b", "a"], Direction::Decreases)),
        },
        Spec {
            id: "fig12-omega-lambda-r",
            figure: 12,
            place: "Fig. 12(c, d), Sec. 4",
            words: "\"and increases the trirhythmic portion in the parameter plane (λ, r)\"",
            rule: "trend",
            judge: |f| f.fig12.as_ref().map(|x| fig12_omega(&x.0.panels, ["d", "c"], Direction::Increases)),
        },
        Spec {
            id: "fig13a-agreement",
            figure: 13,
            place: "Fig. 13(a), Sec. 4, Eq. 26–27",
            words: "the theory's P(A) (as printed) agrees with Monte Carlo of Eq. 1 at μ0 = 0.005, r = 0.99, 0.97, 0.96, 0.84",
            rule: "agreement",
            judge: |f| f.fig13.as_ref().map(|x| agreement_of(&x.panels[..4.min(x.panels.len())], "Eq. 1", "paper")),
        },
        Spec {
            id: "fig13b-agreement",
            figure: 13,
            place: "Fig. 13(b), Sec. 4",
            words: "the same at μ0 = 0.2, r between 0.7 and 0.999",
            rule: "agreement",
            judge: |f| f.fig13.as_ref().map(|x| agreement_of(x.panels.get(4..).unwrap_or(&[]), "Eq. 1", "paper")),
        },
        Spec {
            id: "fig13a-peaks",
            figure: 13,
            place: "Fig. 13(a), Sec. 4",
            words: "\"P_r(A) exhibits three peaks at r = 0.99 … when r = 0.97 or 0.96, we notice two peaks … when r = 0.84 … only one peak\"",
            rule: "count",
            judge: |f| f.fig13.as_ref().map(fig13_peaks),
        },
        Spec {
            id: "fig17a-lle-sign-change",
            figure: 17,
            place: "Fig. 17(a), Sec. 5",
            words: "\"When the noise level reaches the critical value D_c, the maximum Lyapunov exponent turns positive\" (μ0 varied)",
            rule: "sign_change",
            judge: |f| f.fig17.as_ref().and_then(|x| x.0.panels.first().map(lle_sign_change)),
        },
        Spec {
            id: "fig17b-lle-sign-change",
            figure: 17,
            place: "Fig. 17(b), Sec. 5",
            words: "the same, τ varied",
            rule: "sign_change",
            judge: |f| f.fig17.as_ref().and_then(|x| x.0.panels.get(1).map(lle_sign_change)),
        },
        Spec {
            id: "fig18a-lle-sign-change",
            figure: 18,
            place: "Fig. 18(a), Sec. 5",
            words: "the same, λ varied",
            rule: "sign_change",
            judge: |f| f.fig18.as_ref().and_then(|x| x.0.panels.first().map(lle_sign_change)),
        },
        Spec {
            id: "fig18b-lle-sign-change",
            figure: 18,
            place: "Fig. 18(b), Sec. 5",
            words: "the same, r varied",
            rule: "sign_change",
            judge: |f| f.fig18.as_ref().and_then(|x| x.0.panels.get(1).map(lle_sign_change)),
        },
        Spec {
            id: "fig18b-impact-loss",
            figure: 18,
            place: "Fig. 18(b), Sec. 5",
            words: "more impact loss (smaller r) makes chaos likelier: the LLE grows as r falls (paraphrase)",
            rule: "trend",
            judge: |f| f.fig18.as_ref().and_then(|x| x.0.panels.get(1).map(fig18_impact_loss)),
        },
        Spec {
            id: "fig19a-dc-mu0",
            figure: 19,
            place: "Fig. 19(a), Sec. 5",
            words: "\"the critical value decreases with higher nonlinear parameter\"",
            rule: "trend",
            judge: |f| f.fig19.as_ref().map(|x| fig19_trend(x, 0)),
        },
        Spec {
            id: "fig19b-dc-tau",
            figure: 19,
            place: "Fig. 19(b), Sec. 5",
            words: "\"and increases with rising correlation time\"",
            rule: "trend",
            judge: |f| f.fig19.as_ref().map(|x| fig19_trend(x, 1)),
        },
        Spec {
            id: "fig19c-dc-lambda",
            figure: 19,
            place: "Fig. 19(c), Sec. 5",
            words: "\"fractional-order\" (D_c increases with λ)",
            rule: "trend",
            judge: |f| f.fig19.as_ref().map(|x| fig19_trend(x, 2)),
        },
        Spec {
            id: "fig19d-dc-r",
            figure: 19,
            place: "Fig. 19(d), Sec. 5",
            words: "D_c increases with r (the same sentence)",
            rule: "trend",
            judge: |f| f.fig19.as_ref().map(|x| fig19_trend(x, 3)),
        },
    ]
}

/// Every claim the figure data decides, in order.
pub fn registry() -> Vec<Claim> {
    specs().iter().map(claim_of).collect()
}

fn claim_of(s: &Spec) -> Claim {
    Claim {
        id: s.id.into(),
        figure: s.figure,
        place: s.place.into(),
        words: s.words.into(),
        rule: s.rule.into(),
    }
}

/// The claims of the paper that the figure data cannot decide yet, with what each needs.
pub fn not_computable() -> Vec<NotComputable> {
    let n = |id: &str, place: &str, words: &str, needs: &str| NotComputable {
        id: id.into(),
        place: place.into(),
        words: words.into(),
        needs: needs.into(),
    };
    vec![
        n("fig05-interval-mu0", "Fig. 5", "the trirhythmic interval in r depends on μ0",
          "a stated statistic for \"depends on\" (e.g. the trirhythmic r-interval per panel with the fold positions as exact numbers); the fold points are in the data, the rule is not"),
        n("fig10-eq37-misprint", "Figs 10, 12, Eq. 36–37", "Eq. 36–37 give the P-bifurcation set",
          "a distance between the printed Eq. 36–37 curves and the exact fold curves (both are in the map data as polylines; a curve-distance rule with a tolerance is not written yet)"),
        n("fig14-crater", "Fig. 14", "the joint PDF turns from a crater into four separate peaks",
          "a peak count of the 2-D joint densities (theory and Monte Carlo) with a prominence rule, and the Monte Carlo standard errors per cell; the data holds the densities, the Hellinger distance without its standard error, and R̂"),
        n("fig15-omega", "Fig. 15", "the oscillation boundary changes significantly with ω0",
          "a stated effect size for \"changes significantly\"; the simulated boundaries and their brackets are in the data"),
        n("fig15-16-averaged-boundary", "Figs 15–16", "the averaged oscillation boundary",
          "the closeness rule over the simulated brackets against the averaged curve at each abscissa (data present; not wired yet)"),
        n("fig16-rest-grows", "Fig. 16", "the rest region grows as r and λ decrease",
          "the trend rule over the simulated boundary brackets per family member (data present; not wired yet)"),
        n("eq26-28-misprints", "Eq. 26–28, theory", "Eq. 26–28 as printed (coloured noise, impact term)",
          "not figure data: a derivation (σ1 for coloured noise, the (1+τ²) factor); decided in docs/theory.md"),
    ]
}

/// Decide every registry claim whose figure is in `figures`.
pub fn judge(figures: &Figures) -> Verdicts {
    let mut claims = Vec::new();
    let mut not_judged = Vec::new();
    for s in specs() {
        match (s.judge)(figures) {
            Some(decision) => claims.push(ClaimVerdict {
                claim: claim_of(&s),
                decision,
            }),
            None => not_judged.push(s.id.to_string()),
        }
    }
    Verdicts {
        claims,
        not_judged,
        not_computable: not_computable(),
    }
}

// ---- the claims' computations ----

fn fig01_align(f: &Fig01) -> Decision {
    let pairs: Vec<(String, Measured, Measured)> = match (f.panels.first(), f.panels.get(1)) {
        (Some(a), Some(b)) => vec![(
            "mean amplitude, Eq. 1 against Eq. 5".into(),
            Measured::exact(a.amplitude),
            Measured::exact(b.amplitude),
        )],
        _ => Vec::new(),
    };
    closeness(&pairs, CLOSENESS_REL_TOL)
}

/// Share (per cent of the grid) of grid points with count `k`.
fn share(p: &MapPanel, k: usize) -> f64 {
    let h = p.histogram();
    let total: usize = h.iter().sum();
    100.0 * h[k.min(4)] as f64 / total.max(1) as f64
}

fn fig02_regions(panels: &[MapPanel]) -> Decision {
    let Some(p) = panels.iter().find(|p| p.label == "ii").or(panels.get(1)) else {
        return count(&[]);
    };
    let items: Vec<Count> = [(1, "monorhythmic"), (2, "birhythmic"), (3, "trirhythmic")]
        .into_iter()
        .map(|(k, name)| Count {
            what: format!(
                "{name} region present in panel {} ({:.1} % of the grid)",
                p.label,
                share(p, k)
            ),
            claimed: 1,
            computed: u32::from(share(p, k) > 0.0),
            source: CountSource::Exact,
        })
        .collect();
    count(&items).undetermined_because(
        "λ and r are not printed for Fig. 2; λ = 1, r = 1 chosen, and a monorhythmic region appears for λ < 1 or r < 1 (Figs 3, 6)",
    )
}

fn share_trend(
    panels: &[MapPanel],
    xs: &[f64],
    x_name: &str,
    k: usize,
    direction: Direction,
) -> Decision {
    let label = ["zero", "one", "two", "three"][k.min(3)];
    let series = Series {
        label: format!("share of grid points with count {label} (%)"),
        x_name: x_name.into(),
        points: panels
            .iter()
            .zip(xs)
            .map(|(p, &x)| (x, Measured::exact(share(p, k))))
            .collect(),
    };
    trend(&[series], direction)
}

/// The root counts the paper's text gives for Fig. 4 (a)–(d).
pub const FIG04_CLAIMED_ROOTS: [u32; 4] = [5, 5, 3, 0];

fn fig04_roots(f: &Fig04) -> Decision {
    let items: Vec<Count> = f
        .panels
        .iter()
        .zip(FIG04_CLAIMED_ROOTS)
        .map(|(p, claimed)| Count {
            what: format!("positive roots of f, panel {} (r = {})", p.label, p.r),
            claimed,
            computed: p.cycles.len() as u32,
            source: CountSource::Exact,
        })
        .collect();
    count(&items)
}

/// Stable branches of a branch diagram crossing parameter value `x`.
fn stable_at(bd: &BranchDiagram, x: f64) -> u32 {
    let mut n = 0;
    for b in &bd.branches {
        for w in b.points.windows(2) {
            let (lo, hi) = if w[0].param <= w[1].param {
                (w[0].param, w[1].param)
            } else {
                (w[1].param, w[0].param)
            };
            if lo <= x && x < hi && w[0].stable && w[1].stable {
                n += 1;
            }
        }
    }
    n
}

fn fig05_tri_all_r(f: &Fig05) -> Decision {
    let Some((label, mu0, bd)) = f.panels.iter().find(|p| (p.1 - 0.7).abs() < 1e-12) else {
        return count(&[]);
    };
    let n = 20;
    let items: Vec<Count> = (0..n)
        .map(|j| {
            let r = bd.start + (bd.stop - bd.start) * (j as f64 + 0.5) / n as f64;
            Count {
                what: format!(
                    "stable cycles at r = {}, panel {label} (μ0 = {mu0})",
                    crate::notes::num(r)
                ),
                claimed: 3,
                computed: stable_at(bd, r),
                source: CountSource::Exact,
            }
        })
        .collect();
    count(&items)
}

/// (inner A01 well depth, outer well depth, well amplitudes) of a U_eff curve: the depth to
/// the crest beside the well; the inner depth is 0 where U_eff has fewer than three wells
/// (the A01 well has disappeared).
fn wells(cv: &UeffCurve) -> (f64, Option<f64>, Vec<f64>) {
    let ex: Vec<_> = cv.extrema.iter().filter(|e| e.amplitude > 0.0).collect();
    let minima: Vec<f64> = ex
        .iter()
        .filter(|e| e.minimum)
        .map(|e| e.amplitude)
        .collect();
    let depth = |i: usize, j: Option<usize>| {
        j.and_then(|j| ex.get(j))
            .filter(|c| !c.minimum)
            .map(|c| c.potential - ex[i].potential)
    };
    let first = ex.iter().position(|e| e.minimum);
    let last = ex.iter().rposition(|e| e.minimum);
    let inner = first
        .filter(|_| minima.len() >= 3)
        .and_then(|i| depth(i, Some(i + 1)))
        .unwrap_or(0.0);
    let outer = last.and_then(|i| depth(i, i.checked_sub(1)));
    (inner, outer, minima)
}

fn fig07_depths(f: &Fig07, inner: bool) -> Decision {
    // curves are listed from the largest r (λ) down: the claim's order
    let series: Vec<Series> = f
        .panels
        .iter()
        .map(|p| {
            let (x_name, pick): (&str, fn(&(f64, f64)) -> f64) = if p.id == "a" {
                ("r", |q| q.0)
            } else {
                ("λ", |q| q.1)
            };
            Series {
                label: format!(
                    "panel {}: depth of the {} well",
                    p.id,
                    if inner { "inner (A01)" } else { "outer" }
                ),
                x_name: x_name.into(),
                points: p
                    .curves
                    .iter()
                    .zip(&p.params)
                    .map(|(cv, q)| {
                        let (i, o, _) = wells(cv);
                        let v = if inner { i } else { o.unwrap_or(f64::NAN) };
                        (pick(q), Measured::exact(v))
                    })
                    .collect(),
            }
        })
        .collect();
    trend(
        &series,
        if inner {
            Direction::Decreases
        } else {
            Direction::Increases
        },
    )
}

fn fig07_wells_move(f: &Fig07) -> Decision {
    let mut pairs = Vec::new();
    for p in &f.panels {
        let all: Vec<Vec<f64>> = p.curves.iter().map(|c| wells(c).2).collect();
        let Some(first) = all.first() else { continue };
        for (cv, w) in p.curves.iter().zip(&all).skip(1) {
            if w.len() != first.len() {
                continue;
            }
            for (k, (a, b)) in first.iter().zip(w).enumerate() {
                pairs.push((
                    format!("panel {}, well {} at {}", p.id, k + 1, cv.label),
                    Measured::exact(*b),
                    Measured::exact(*a),
                ));
            }
        }
    }
    closeness(&pairs, CLOSENESS_REL_TOL)
}

fn fig08_barriers(f: &Fig08) -> Decision {
    count(&[Count {
        what: "energy barriers of U_eff".into(),
        claimed: 4,
        computed: f.barriers.len() as u32,
        source: CountSource::Exact,
    }])
    .undetermined_because(
        "τ is not printed in the paper; τ = 5 chosen, and the inner well exists only for τ ≳ 3",
    )
}

fn fig09_lambda(f: &Fig09) -> Decision {
    let mut up = Vec::new();
    let mut down = Vec::new();
    for s in &f.surfaces {
        for i in 0..4 {
            for ix in 0..s.x.count {
                // runs of grid points with three wells along λ (ascending)
                let mut run: Vec<(f64, Measured)> = Vec::new();
                let mut flush = |run: &mut Vec<(f64, Measured)>| {
                    if run.len() >= 2 {
                        let series = Series {
                            label: format!(
                                "ΔU{} at r = {}, τ = {}",
                                i + 1,
                                s.r,
                                crate::notes::num(s.x.value(ix))
                            ),
                            x_name: "λ".into(),
                            points: std::mem::take(run),
                        };
                        if i == 1 {
                            down.push(series);
                        } else {
                            up.push(series);
                        }
                    }
                    run.clear();
                };
                for iy in 0..s.y.count {
                    match s.heights[iy * s.x.count + ix][i] {
                        Some(h) => run.push((s.y.value(iy), Measured::exact(h))),
                        None => flush(&mut run),
                    }
                }
                flush(&mut run);
            }
        }
    }
    all_of(
        "trend",
        vec![
            (
                "ΔU1, ΔU3, ΔU4 increase with λ".into(),
                trend(&up, Direction::Increases),
            ),
            (
                "ΔU2 decreases with λ".into(),
                trend(&down, Direction::Decreases),
            ),
        ],
    )
}

fn fig09_r(f: &Fig09) -> Decision {
    let (Some(hi), Some(lo)) = (
        f.surfaces.iter().find(|s| (s.r - 0.998).abs() < 1e-9),
        f.surfaces.iter().find(|s| (s.r - 0.990).abs() < 1e-9),
    ) else {
        return trend(&[], Direction::Decreases);
    };
    let mut parts = Vec::new();
    for i in [0usize, 1, 3] {
        let mut series = Vec::new();
        for (k, (a, b)) in hi.heights.iter().zip(&lo.heights).enumerate() {
            if let (Some(a), Some(b)) = (a[i], b[i]) {
                let (ix, iy) = (k % hi.x.count, k / hi.x.count);
                series.push(Series {
                    label: format!(
                        "τ = {}, λ = {}",
                        crate::notes::num(hi.x.value(ix)),
                        crate::notes::num(hi.y.value(iy))
                    ),
                    x_name: "r".into(),
                    points: vec![(hi.r, Measured::exact(a)), (lo.r, Measured::exact(b))],
                });
            }
        }
        parts.push((
            format!("ΔU{} falls as r falls", i + 1),
            trend(&series, Direction::Decreases),
        ));
    }
    all_of("trend", parts)
}

fn fig12_omega(panels: &[MapPanel], order: [&str; 2], direction: Direction) -> Decision {
    let pick: Vec<&MapPanel> = order
        .iter()
        .filter_map(|l| panels.iter().find(|p| p.label == *l))
        .collect();
    let omega = |p: &MapPanel| {
        if p.label == "a" || p.label == "c" {
            0.9
        } else {
            1.0
        }
    };
    let series = Series {
        label: format!("trimodal share (%) of panels {} → {}", order[0], order[1]),
        x_name: "ω0".into(),
        points: pick
            .iter()
            .map(|p| (omega(p), Measured::exact(share(p, 3))))
            .collect(),
    };
    trend(&[series], direction)
}

fn agreement_of(panels: &[AmplitudePanel], system: &str, variant: &str) -> Decision {
    let mut items = Vec::new();
    for p in panels {
        for r in p.runs.iter().filter(|r| r.system == system) {
            if let Some(d) = r.distances.iter().find(|d| d.variant == variant) {
                items.push(Comparison {
                    what: format!("{}, MC of {}, {} formulas", p.caption, r.system, variant),
                    hellinger: d.hellinger,
                    se: d.hellinger_stderr,
                    bins: r.edges.len().saturating_sub(1),
                    ess: r.ess,
                    stationary: r.stationary,
                    r_hat: r.r_hat,
                });
            }
        }
    }
    agreement(&items)
}

/// The peak counts the paper's text gives for Fig. 13 (a1)–(a4).
pub const FIG13_CLAIMED_PEAKS: [u32; 4] = [3, 2, 2, 1];

fn fig13_peaks(f: &Fig13) -> Decision {
    let mut items = Vec::new();
    for (p, claimed) in f.panels.iter().zip(FIG13_CLAIMED_PEAKS) {
        if let Some(r) = p.runs.iter().find(|r| r.system == "Eq. 1") {
            if let Some(d) = r.distances.first() {
                items.push(Count {
                    what: format!("peaks of the Monte Carlo P(A) of Eq. 1, {}", p.caption),
                    claimed,
                    computed: d.modes_mc as u32,
                    source: CountSource::Ensemble {
                        stationary: r.stationary,
                        r_hat: r.r_hat,
                    },
                });
            }
        }
    }
    count(&items)
}

fn lle_curves(p: &LlePanel) -> Vec<LleCurve> {
    p.curves
        .iter()
        .map(|c| LleCurve {
            label: c.label.clone(),
            points: c
                .points
                .iter()
                .map(|q| LlePoint {
                    d: q.x,
                    lle: q.y,
                    se: (q.hi - q.lo) / 2.0,
                })
                .collect(),
        })
        .collect()
}

fn lle_sign_change(p: &LlePanel) -> Decision {
    sign_change(&lle_curves(p))
}

fn fig18_impact_loss(p: &LlePanel) -> Decision {
    // curves are r = 0.998, 0.95, 0.9, 0.8: the claim's order (more loss); one series per D
    let curves = lle_curves(p);
    let r_of = |label: &str| {
        label
            .rsplit("= ")
            .next()
            .and_then(|s| s.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    let n = curves.iter().map(|c| c.points.len()).min().unwrap_or(0);
    let series: Vec<Series> = (0..n)
        .map(|k| Series {
            label: format!("LLE at D = {}", crate::notes::num(curves[0].points[k].d)),
            x_name: "r".into(),
            points: curves
                .iter()
                .map(|c| {
                    let q = c.points[k];
                    (r_of(&c.label), Measured::with_se(q.lle, q.se))
                })
                .collect(),
        })
        .collect();
    trend(&series, Direction::Increases)
}

fn fig19_trend(f: &Fig19, panel: usize) -> Decision {
    let Some(p) = f.panels.get(panel) else {
        return trend(&[], Direction::Increases);
    };
    let direction = if FIG19_PANELS[panel].3 == "decreases" {
        Direction::Decreases
    } else {
        Direction::Increases
    };
    let points: Vec<(f64, Measured)> = p
        .curves
        .first()
        .map(|c| {
            c.points
                .iter()
                .map(|q| (q.x, Measured::bracket(q.y, q.lo, q.hi)))
                .collect()
        })
        .unwrap_or_default();
    let missing: Vec<String> = points
        .iter()
        .filter(|q| !q.1.value.is_finite())
        .map(|q| crate::notes::num(q.0))
        .collect();
    let d = trend(
        &[Series {
            label: "D_c".into(),
            x_name: p.x_key.clone(),
            points,
        }],
        direction,
    );
    if missing.is_empty() || d.verdict == super::Verdict::Refuted {
        d
    } else {
        Decision {
            verdict: super::Verdict::undetermined(format!(
                "no negative → positive sign change of the LLE in range (no D_c) at {} = {}",
                p.x_key,
                missing.join(", ")
            )),
            ..d
        }
    }
}

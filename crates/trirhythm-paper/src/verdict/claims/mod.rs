//! The paper's checkable claims, each with its words, its place, the rule that decides it and
//! the function computing its [`Decision`] from the figures' data.
//!
//! [`registry`] lists the claims with stable ids (`fig04-roots`, …); [`judge`] decides every
//! claim whose figure is in a [`Figures`] value and returns [`Verdicts`] (serde): the claims,
//! their verdicts and numbers, and the claims that the figure data cannot decide yet
//! ([`not_computable`]). Nothing here is typed text about the outcome: change a figure's data
//! and the verdict follows (tested in `tests/verdicts.rs`).

mod sequences;
mod stochastic;
mod theory;

pub use sequences::{visible_peaks, FIG05_EXCEPTED_MU0, SETTLED_SPREAD};
pub use stochastic::{FIG13B_CLAIMED_PEAKS, FIG13_CLAIMED_PEAKS, FIG14_CLAIMED_MAXIMA};
pub use theory::FIG04_CLAIMED_ROOTS;

use super::rules::{closeness, Direction, CLOSENESS_REL_TOL};
use super::{all_of, Decision};
use crate::fig01_phase_recurrence::Fig01;
use crate::fig02_rhythmicity_planes::Fig02;
use crate::fig03_restitution_planes::{Fig03, R_VALUES as FIG03_R};
use crate::fig04_drift::Fig04;
use crate::fig05_branches::Fig05;
use crate::fig06_fractional_planes::{Fig06, LAMBDA_VALUES as FIG06_LAMBDA};
use crate::fig07_pseudo_potential::Fig07;
use crate::fig08_barriers::Fig08;
use crate::fig09_barrier_surfaces::Fig09;
use crate::fig10_pbif_lambda_tau::{Fig10, D_VALUES as FIG10_D};
use crate::fig11_amplitude_lambda::Fig11;
use crate::fig12_pbif_maps::Fig12;
use crate::fig13_pdf_restitution::Fig13;
use crate::fig14_joint_pdf::Fig14;
use crate::fig15_oscillation_boundaries::Fig15;
use crate::fig16_oscillation_regions::Fig16;
use crate::fig17_lle_noise::Fig17;
use crate::fig18_lle_noise_fractional::Fig18;
use crate::fig19_critical_noise::Fig19;
use crate::{Figure, FigureOptions, Monitor};
use sequences::*;
use serde::{Deserialize, Serialize};
use stochastic::*;
use theory::*;
use trirhythm::Result;

/// The figures' data a set of verdicts is computed from; a claim whose figure is absent is
/// not judged.
#[derive(Default)]
#[allow(missing_docs)]
pub struct Figures {
    /// The options the figures were computed with (quick or full quality; the Lyapunov
    /// figures carry their realisations per point, for the degrees of freedom).
    pub options: FigureOptions,
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
    pub fig14: Option<Fig14>,
    pub fig15: Option<Fig15>,
    pub fig16: Option<Fig16>,
    pub fig17: Option<Fig17>,
    pub fig18: Option<Fig18>,
    pub fig19: Option<Fig19>,
}

/// The figures that claims are computed from.
pub const JUDGED_FIGURES: [u32; 19] = [
    1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19,
];

/// The theory figures, cheap and deterministic (seconds in quick mode).
pub const THEORY_FIGURES: [u32; 11] = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12];

impl Figures {
    /// Compute the figures numbered `numbers` (1 to 19; others are ignored).
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
            options: *options,
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
            fig14: get(numbers, o, m)?,
            fig15: get(numbers, o, m)?,
            fig16: get(numbers, o, m)?,
            fig17: get(numbers, o, m)?,
            fig18: get(numbers, o, m)?,
            fig19: get(numbers, o, m)?,
        })
    }
}

/// A figure's place in [`Figures`]: how one figure's data is judged on its own
/// ([`judge_figure`]).
pub trait Slot: Figure {
    /// The figure's field of `figures`.
    fn slot(figures: &mut Figures) -> &mut Option<Self>;
}

macro_rules! slots {
    ($($figure:ty => $field:ident),* $(,)?) => {
        $(impl Slot for $figure {
            fn slot(figures: &mut Figures) -> &mut Option<Self> {
                &mut figures.$field
            }
        })*
    };
}

slots!(
    Fig01 => fig01, Fig02 => fig02, Fig03 => fig03, Fig04 => fig04, Fig05 => fig05,
    Fig06 => fig06, Fig07 => fig07, Fig08 => fig08, Fig09 => fig09, Fig10 => fig10,
    Fig11 => fig11, Fig12 => fig12, Fig13 => fig13, Fig14 => fig14, Fig15 => fig15,
    Fig16 => fig16, Fig17 => fig17, Fig18 => fig18, Fig19 => fig19,
);

/// The verdicts on the claims that rest on one figure, from its data alone (computed with
/// `options`); the data is handed back. Empty for a figure that carries no claim.
pub fn judge_figure<F: Slot>(data: F, options: &FigureOptions) -> (F, Vec<ClaimVerdict>) {
    let mut figures = Figures {
        options: *options,
        ..Default::default()
    };
    *F::slot(&mut figures) = Some(data);
    let verdicts = judge(&figures)
        .claims
        .into_iter()
        .filter(|c| c.claim.figure == F::NUMBER)
        .collect();
    let data = F::slot(&mut figures)
        .take()
        .expect("the slot was filled above");
    (data, verdicts)
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
    /// The model the verdict holds for: the averaged theory (with its equation), Eq. 5 (the
    /// equivalent integer-order system) or Eq. 1 (the fractional system, simulated), or two
    /// of them compared.
    #[serde(default)]
    pub model: String,
}

impl Claim {
    /// Where the paper makes the claim and the model its verdict holds for, in one line
    /// (`Fig. 5, Sec. 3 · averaged theory (Eq. 18)`).
    pub fn place_and_model(&self) -> String {
        if self.model.is_empty() {
            self.place.clone()
        } else {
            format!("{} · {}", self.place, self.model)
        }
    }
}

/// A claim with its decision.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClaimVerdict {
    /// The claim.
    pub claim: Claim,
    /// The verdict and its numbers.
    pub decision: Decision,
}

impl ClaimVerdict {
    /// One line: the verdict, why when undetermined, and the deciding numbers (at most
    /// `numbers` of the checks that decided it), e.g. for a picture or a table row.
    pub fn summary(&self, numbers: usize) -> String {
        let d = &self.decision;
        let mut line = d.verdict.tag().to_string();
        if let super::Verdict::Undetermined { why } = &d.verdict {
            line.push_str(&format!(" ({why})"));
        }
        let shown = d.deciding(numbers);
        if !shown.is_empty() {
            line.push_str(": ");
            line.push_str(
                &shown
                    .iter()
                    .map(|c| c.describe())
                    .collect::<Vec<_>>()
                    .join("; "),
            );
        }
        line
    }
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
    model: &'static str,
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
            model: "Eq. 1 against Eq. 5 (both by the predictor–corrector)",
            judge: |f| f.fig01.as_ref().map(fig01_align),
        },
        Spec {
            id: "fig01-recurrence",
            figure: 1,
            place: "Fig. 1, Sec. 2",
            words: "the recurrence plots of Eq. 1 and Eq. 5 align closely (\"the phase portraits and recurrence plots are presented … The approximative solution seems to align closely\"): their recurrence rate RR and determinism DET",
            rule: "closeness",
            model: "Eq. 1 against Eq. 5 (both by the predictor–corrector)",
            judge: |f| f.fig01.as_ref().map(fig01_recurrence),
        },
        Spec {
            id: "fig02-regions",
            figure: 2,
            place: "Fig. 2(ii), Sec. 3",
            words: "\"The saddle-node bifurcations correspond to L1, L2, and L3 in Figs.2 (i) and (ii) that enclose the birhythmic and trirhythmic areas\" (Fig. 2(ii): \"displaying trirhythmicity\")",
            rule: "count",
            model: "averaged theory (Eq. 18)",
            judge: |f| f.fig02.as_ref().map(|x| fig02_regions(&x.0.panels)),
        },
        Spec {
            id: "fig03-tri-shrinks",
            figure: 3,
            place: "Fig. 3, Sec. 3",
            words: "\"a decreasing value of r reduces the trirhythmic zone\"",
            rule: "trend",
            model: "averaged theory (Eq. 18)",
            judge: |f| {
                f.fig03
                    .as_ref()
                    .map(|x| exact_share_trend(&x.0.panels, "fig3", &FIG03_R, "r", 3, Direction::Decreases, f.options.variant))
            },
        },
        Spec {
            id: "fig03-birhythmic",
            figure: 3,
            place: "Fig. 3, Sec. 3",
            words: "\"and if this coefficient reaches a certain value, the system evolves into birhythmic\"",
            rule: "count",
            model: "averaged theory (Eq. 18)",
            judge: |f| f.fig03.as_ref().map(|x| fig03_birhythmic(x, f.options.variant)),
        },
        Spec {
            id: "fig04-roots",
            figure: 4,
            place: "Fig. 4, Sec. 3",
            words: "\"we detect five roots\" (r ≈ 1); \"the roots are still five\" (r = 0.98); \"three roots\" (r = 0.96); \"the number of roots is zero\" (r = 0.90)",
            rule: "count",
            model: "averaged theory (Eq. 18)",
            judge: |f| f.fig04.as_ref().map(fig04_roots),
        },
        Spec {
            id: "fig05-tri-all-r",
            figure: 5,
            place: "Fig. 5, Sec. 3",
            words: "trirhythmic for all r at μ0 = 0.7 (paraphrase of the text on Fig. 5(e))",
            rule: "count",
            model: "averaged theory (Eq. 18)",
            judge: |f| f.fig05.as_ref().map(fig05_tri_all_r),
        },
        Spec {
            id: "fig05-interval-mu0",
            figure: 5,
            place: "Fig. 5, Sec. 3",
            words: "the trirhythmic interval in r depends on μ0 (paraphrase of the text on Fig. 5(a)–(e); averaged theory, Eq. 18)",
            rule: "dependence",
            model: "averaged theory (Eq. 18)",
            judge: |f| f.fig05.as_ref().map(fig05_interval_mu0),
        },
        Spec {
            id: "fig05-tri-bi-mono",
            figure: 5,
            place: "Fig. 5, Sec. 3",
            words: "\"the system has progressed from trirhythmic to birhythmic and, subsequently, to monorhythmic with decreasing r\" (every panel but (e), which the text excepts)",
            rule: "count",
            model: "averaged theory (Eq. 18)",
            judge: |f| f.fig05.as_ref().map(|x| fig05_sequence(x, f.options.variant)),
        },
        Spec {
            id: "fig06-mono-grows",
            figure: 6,
            place: "Fig. 6, Sec. 3",
            words: "\"the monorhythmic zone expands when λ drops\"",
            rule: "trend",
            model: "averaged theory (Eq. 18)",
            judge: |f| {
                f.fig06.as_ref().map(|x| {
                    exact_share_trend(&x.0.panels, "fig6", &FIG06_LAMBDA, "λ", 1, Direction::Increases, f.options.variant)
                })
            },
        },
        Spec {
            id: "fig06-bi-tri-shrink",
            figure: 6,
            place: "Fig. 6, Sec. 3",
            words: "\"whereas the birhythmic and trirhythmic zones reduce\"",
            rule: "trend",
            model: "averaged theory (Eq. 18)",
            judge: |f| {
                f.fig06.as_ref().map(|x| {
                    all_of(
                        "trend",
                        vec![
                            (
                                "birhythmic".into(),
                                exact_share_trend(&x.0.panels, "fig6", &FIG06_LAMBDA, "λ", 2, Direction::Decreases, f.options.variant),
                            ),
                            (
                                "trirhythmic".into(),
                                exact_share_trend(&x.0.panels, "fig6", &FIG06_LAMBDA, "λ", 3, Direction::Decreases, f.options.variant),
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
            model: "averaged theory (Eq. 23)",
            judge: |f| f.fig07.as_ref().map(|x| fig07_depths(x, true)),
        },
        Spec {
            id: "fig07-outer-well",
            figure: 7,
            place: "Fig. 7, Sec. 3",
            words: "\"that one in A05 increases in depth\" (as r, and λ, decrease)",
            rule: "trend",
            model: "averaged theory (Eq. 23)",
            judge: |f| f.fig07.as_ref().map(|x| fig07_depths(x, false)),
        },
        Spec {
            id: "fig07-wells-move",
            figure: 7,
            place: "Fig. 7, Sec. 3",
            words: "\"the amplitudes A01, A03 and A05 change very slightly when r or λ increases\"",
            rule: "closeness",
            model: "averaged theory (Eq. 23)",
            judge: |f| f.fig07.as_ref().map(|x| fig07_wells_move(x, f.options.variant)),
        },
        Spec {
            id: "fig08-four-barriers",
            figure: 8,
            place: "Fig. 8, Sec. 3",
            words: "four energy barriers ΔU1–ΔU4 of U_eff at D = 0.24 (Fig. 8)",
            rule: "count",
            model: "averaged theory (Eq. 23)",
            judge: |f| f.fig08.as_ref().map(fig08_barriers),
        },
        Spec {
            id: "fig09-lambda",
            figure: 9,
            place: "Fig. 9, Sec. 3",
            words: "\"for the increasing value of λ, ΔU1, ΔU3, ΔU4 are increasing while ΔU2 is decreasing. This is found for all values of correlation time\"",
            rule: "trend",
            model: "averaged theory (Eq. 23)",
            judge: |f| f.fig09.as_ref().map(fig09_lambda),
        },
        Spec {
            id: "fig09-r",
            figure: 9,
            place: "Fig. 9, Sec. 3",
            words: "\"excluding ΔU3, the energy is lowered when r falls\"",
            rule: "trend",
            model: "averaged theory (Eq. 23)",
            judge: |f| f.fig09.as_ref().map(fig09_r),
        },
        Spec {
            id: "fig10-trimodal-shrinks",
            figure: 10,
            place: "Fig. 10, Sec. 4",
            words: "\"The trirhythmic region in the parameters (λ, τ)-plane decreases with increasing correlated noise\"",
            rule: "trend",
            model: "averaged theory (Eq. 26–28, 35)",
            judge: |f| {
                f.fig10
                    .as_ref()
                    .map(|x| share_trend(&x.0.panels, &FIG10_D, "D", 3, Direction::Decreases))
            },
        },
        Spec {
            id: "fig10-eq37-misprint",
            figure: 10,
            place: "Fig. 10, Eq. 35–37, Sec. 4",
            words: "Eq. 36–37 (as printed) give the P-bifurcation set of the averaged theory's P(A) in the (λ, τ) plane (the dashed curves against the exact m1 = ∂m1/∂A = 0)",
            rule: "curve_distance",
            model: "averaged theory (Eq. 35–37 against the exact fold of Eq. 27)",
            judge: |f| {
                f.fig10
                    .as_ref()
                    .map(|x| eq37_curves(&[("Fig. 10", &x.0.panels[..])]))
            },
        },
        Spec {
            id: "fig12-eq37-misprint",
            figure: 12,
            place: "Fig. 12, Eq. 35–37, Sec. 4",
            words: "the same in the (μ0, r) and (λ, r) planes (\"From equations (36) and (37) we find … the areas of the parameter plane (r, μ0), (λ, r)\")",
            rule: "curve_distance",
            model: "averaged theory (Eq. 35–37 against the exact fold of Eq. 27)",
            judge: |f| {
                f.fig12
                    .as_ref()
                    .map(|x| eq37_curves(&[("Fig. 12", &x.0.panels[..])]))
            },
        },
        Spec {
            id: "fig11b-agreement",
            figure: 11,
            place: "Fig. 11(b), Sec. 4",
            words: "the averaged theory's P(A) (Eq. 27, as printed) agrees with Monte Carlo of Eq. 1 as λ varies",
            rule: "agreement",
            model: "averaged theory (Eq. 27) against Eq. 1 (Monte Carlo)",
            judge: |f| f.fig11.as_ref().map(|x| agreement_of(&x.panels, "Eq. 1", "paper")),
        },
        Spec {
            id: "fig11a-amplitudes",
            figure: 11,
            place: "Fig. 11(a), Sec. 4",
            words: "the averaged theory's limit-cycle amplitudes (solid) against the predictor–corrector simulations of Eq. 1 (dotted) as λ varies (\"we discover that the number of limit cycles alters with the shift of λ\"; the agreement is the abstract's \"strong alignment between the theoretical and numerical solutions obtained from the predictor-corrector algorithm\")",
            rule: "closeness",
            model: "averaged theory (Eq. 18) against Eq. 1 (predictor–corrector, no noise)",
            judge: |f| f.fig11.as_ref().map(|x| fig11a_amplitudes(x, f.options.variant)),
        },
        Spec {
            id: "fig11b-peaks",
            figure: 11,
            place: "Fig. 11(b), Sec. 4",
            words: "\"The PDF … for amplitude may have one, two, or three peak levels, demonstrating the shift between one peak and three peaks with modifying λ\"",
            rule: "count",
            model: "averaged theory (Eq. 27) and Eq. 1 (Monte Carlo)",
            judge: |f| f.fig11.as_ref().map(|x| fig11b_peaks(x, f.options.variant)),
        },
        Spec {
            id: "abstract-lambda-r-alone",
            figure: 12,
            place: "Abstract (Fig. 12)",
            words: "\"Simply altering the fractional order or restriction variable causes the probability density function to move between unimodal, bimodal, and trimodal distributions\"",
            rule: "count",
            model: "averaged theory (Eq. 27, exact P-bifurcation maps)",
            judge: |f| {
                f.fig12.as_ref().map(|x| lambda_or_r_alone(&x.0.panels))
            },
        },
        Spec {
            id: "fig12-omega-mu0-r",
            figure: 12,
            place: "Fig. 12(a, b), Sec. 4",
            words: "\"decreasing ω0 decreases the trirhythmic section in the variable plane (μ0, r)\"",
            rule: "trend",
            model: "averaged theory (Eq. 26–28, 35)",
            judge: |f| f.fig12.as_ref().map(|x| fig12_omega(&x.0.panels, ["b", "a"], Direction::Decreases)),
        },
        Spec {
            id: "fig12-omega-lambda-r",
            figure: 12,
            place: "Fig. 12(c, d), Sec. 4",
            words: "\"and increases the trirhythmic portion in the parameter plane (λ, r)\"",
            rule: "trend",
            model: "averaged theory (Eq. 26–28, 35)",
            judge: |f| f.fig12.as_ref().map(|x| fig12_omega(&x.0.panels, ["d", "c"], Direction::Increases)),
        },
        Spec {
            id: "fig13a-agreement",
            figure: 13,
            place: "Fig. 13(a), Sec. 4, Eq. 26–27",
            words: "the theory's P(A) (as printed) agrees with Monte Carlo of Eq. 1 at μ0 = 0.005, r = 0.99, 0.97, 0.96, 0.84",
            rule: "agreement",
            model: "averaged theory (Eq. 27) against Eq. 1 (Monte Carlo)",
            judge: |f| f.fig13.as_ref().map(|x| agreement_of(&x.panels[..4.min(x.panels.len())], "Eq. 1", "paper")),
        },
        Spec {
            id: "fig13b-agreement",
            figure: 13,
            place: "Fig. 13(b), Sec. 4",
            words: "the same at μ0 = 0.2, r between 0.7 and 0.999",
            rule: "agreement",
            model: "averaged theory (Eq. 27) against Eq. 1 (Monte Carlo)",
            judge: |f| f.fig13.as_ref().map(|x| agreement_of(x.panels.get(4..).unwrap_or(&[]), "Eq. 1", "paper")),
        },
        Spec {
            id: "fig13a-peaks",
            figure: 13,
            place: "Fig. 13(a), Sec. 4",
            words: "\"P_r(A) exhibits three peaks at r = 0.99 … when r = 0.97 or 0.96, we notice two peaks … when r = 0.84 … only one peak\"",
            rule: "count",
            model: "averaged theory (Eq. 27) and Eq. 1 (Monte Carlo)",
            judge: |f| f.fig13.as_ref().map(fig13_peaks),
        },
        Spec {
            id: "fig13b-peaks",
            figure: 13,
            place: "Fig. 13(b), Sec. 4",
            words: "\"when μ0 = 0.2, we change r between 0.7 and 0.999 and we note that the three peaks endure\"",
            rule: "count",
            model: "averaged theory (Eq. 27) and Eq. 1 (Monte Carlo)",
            judge: |f| f.fig13.as_ref().map(fig13b_peaks),
        },
        Spec {
            id: "eq26-28-misprints",
            figure: 13,
            place: "Eq. 26–28, Sec. 4 (Fig. 13)",
            words: "Eq. 26–28 as printed (m1, σ1 of Eq. 26; P(A) of Eq. 27–28) give the stationary amplitude density of Eq. 5 with coloured noise and impacts (the project's derivation, docs/theory.md, corrects σ1 for coloured noise and the impact term's (1+τ²))",
            rule: "agreement",
            model: "averaged theory (Eq. 26–28) against Eq. 5 (Monte Carlo)",
            judge: |f| f.fig13.as_ref().map(eq26_28),
        },
        Spec {
            id: "fig14-crater",
            figure: 14,
            place: "Fig. 14, Sec. 4",
            words: "the joint density P(U, dU/dt) turns from \"a vast crater\" (r = 0.92) into \"four separate peaks\" (r = 0.999)",
            rule: "count",
            model: "averaged theory (Eq. 30–31) and Eq. 1 (Monte Carlo)",
            judge: |f| f.fig14.as_ref().map(fig14_crater),
        },
        Spec {
            id: "fig14-shift",
            figure: 14,
            place: "Fig. 14, Sec. 4",
            words: "\"a greater restitution coefficient causes the distribution to move to a lower Z value for a given number of enzyme molecules U\"",
            rule: "trend",
            model: "averaged theory (Eq. 30–31) and Eq. 1 (Monte Carlo)",
            judge: |f| f.fig14.as_ref().map(fig14_shift),
        },
        Spec {
            id: "fig15-omega",
            figure: 15,
            place: "Fig. 15, Sec. 5",
            words: "\"with decreasing ω0 the separation between oscillation and no oscillation changes significantly\" (the simulated boundary of Eq. 1)",
            rule: "dependence",
            model: "Eq. 1 (simulation)",
            judge: |f| f.fig15.as_ref().map(fig15_omega),
        },
        Spec {
            id: "fig16-rest-grows",
            figure: 16,
            place: "Fig. 16(b, d), Sec. 5",
            words: "the rest (no-oscillation) region grows as r and λ decrease (\"This emphasizes the impact of λ and r on these domains\"; paraphrase of the figure)",
            rule: "trend",
            model: "Eq. 1 (simulation)",
            judge: |f| {
                f.fig16.as_ref().map(|x| {
                    let parts = x
                        .panels
                        .iter()
                        .filter(|p| p.curves.iter().any(|c| c.member.is_some()))
                        .map(|p| (format!("panel {}", p.label), fig16_family(p)))
                        .collect();
                    all_of("trend", parts)
                })
            },
        },
        Spec {
            id: "sec5-supercritical-hopf",
            figure: 16,
            place: "Sec. V (Figs 15–16)",
            words: "\"a supercritical Hopf bifurcation is defined by a stable limit cycle emerging from zero amplitude and increasing in magnitude\" (at the boundary between rest and oscillation)",
            rule: "count",
            model: "averaged theory (Eq. 18, at its boundary f′(0) = 0)",
            judge: |f| f.fig16.as_ref().map(|x| hopf_supercritical(x, f.options.variant)),
        },
        Spec {
            id: "fig16-averaged-boundary",
            figure: 16,
            place: "Abstract, judged on Figs 15–16 (Fig. 16(a, c))",
            words: "\"The strong alignment between the theoretical and numerical solutions obtained from the predictor-corrector algorithm … confirms the accuracy of our conclusions\", at the boundary between oscillation and rest: the averaged f′(0) = 0 of Eq. 18 against the simulated boundary of Eq. 1",
            rule: "closeness",
            model: "averaged theory (Eq. 18) against Eq. 1 (simulation)",
            judge: |f| {
                f.fig16.as_ref().map(|x| {
                    let pairs: Vec<_> = x
                        .panels
                        .iter()
                        .filter(|p| p.curves.iter().all(|c| c.member.is_none()))
                        .flat_map(fig16_averaged)
                        .collect();
                    closeness(&pairs, CLOSENESS_REL_TOL)
                })
            },
        },
        Spec {
            id: "fig17a-lle-sign-change",
            figure: 17,
            place: "Fig. 17(a), Sec. 5",
            words: "\"When the noise level reaches the critical value D_c, the maximum Lyapunov exponent turns positive\" (μ0 varied)",
            rule: "sign_change",
            model: "Eq. 1 (simulation)",
            judge: |f| f.fig17.as_ref().and_then(|x| x.0.panels.first().map(lle_sign_change)),
        },
        Spec {
            id: "fig17b-lle-sign-change",
            figure: 17,
            place: "Fig. 17(b), Sec. 5",
            words: "the same, τ varied",
            rule: "sign_change",
            model: "Eq. 1 (simulation)",
            judge: |f| f.fig17.as_ref().and_then(|x| x.0.panels.get(1).map(lle_sign_change)),
        },
        Spec {
            id: "fig18a-lle-sign-change",
            figure: 18,
            place: "Fig. 18(a), Sec. 5",
            words: "the same, λ varied",
            rule: "sign_change",
            model: "Eq. 1 (simulation)",
            judge: |f| f.fig18.as_ref().and_then(|x| x.0.panels.first().map(lle_sign_change)),
        },
        Spec {
            id: "fig18b-lle-sign-change",
            figure: 18,
            place: "Fig. 18(b), Sec. 5",
            words: "the same, r varied",
            rule: "sign_change",
            model: "Eq. 1 (simulation)",
            judge: |f| f.fig18.as_ref().and_then(|x| x.0.panels.get(1).map(lle_sign_change)),
        },
        Spec {
            id: "fig18b-impact-loss",
            figure: 18,
            place: "Fig. 18(b), Sec. 5",
            words: "more impact loss (smaller r) makes chaos likelier: the LLE grows as r falls (paraphrase)",
            rule: "trend",
            model: "Eq. 1 (simulation)",
            judge: |f| f.fig18.as_ref().and_then(|x| x.0.panels.get(1).map(fig18_impact_loss)),
        },
        Spec {
            id: "fig17-disorder",
            figure: 17,
            place: "Sec. V (Fig. 17)",
            words: "\"As correlated noise intensity increases, it is evident that the model experiences a progressive increases in disorder\" (the exponents of Fig. 17)",
            rule: "trend",
            model: "Eq. 1 (simulation)",
            judge: |f| {
                f.fig17.as_ref().map(|x| {
                    let panels: Vec<(&str, &crate::lle::Panel)> =
                        x.0.panels.iter().map(|p| ("Fig. 17", p)).collect();
                    noise_disorder(&panels)
                })
            },
        },
        Spec {
            id: "fig18-disorder",
            figure: 18,
            place: "Sec. V (Fig. 18)",
            words: "the same sentence, on the exponents of Fig. 18",
            rule: "trend",
            model: "Eq. 1 (simulation)",
            judge: |f| {
                f.fig18.as_ref().map(|x| {
                    let panels: Vec<(&str, &crate::lle::Panel)> =
                        x.0.panels.iter().map(|p| ("Fig. 18", p)).collect();
                    noise_disorder(&panels)
                })
            },
        },
        Spec {
            id: "fig19a-dc-mu0",
            figure: 19,
            place: "Fig. 19(a), Sec. 5",
            words: "\"the critical value decreases with higher nonlinear parameter\"",
            rule: "trend",
            model: "Eq. 1 (simulation)",
            judge: |f| f.fig19.as_ref().map(|x| fig19_trend(x, 0)),
        },
        Spec {
            id: "fig19b-dc-tau",
            figure: 19,
            place: "Fig. 19(b), Sec. 5",
            words: "\"and increases with rising correlation time\"",
            rule: "trend",
            model: "Eq. 1 (simulation)",
            judge: |f| f.fig19.as_ref().map(|x| fig19_trend(x, 1)),
        },
        Spec {
            id: "fig19c-dc-lambda",
            figure: 19,
            place: "Fig. 19(c), Sec. 5",
            words: "\"fractional-order\" (D_c increases with λ)",
            rule: "trend",
            model: "Eq. 1 (simulation)",
            judge: |f| f.fig19.as_ref().map(|x| fig19_trend(x, 2)),
        },
        Spec {
            id: "fig19d-dc-r",
            figure: 19,
            place: "Fig. 19(d), Sec. 5",
            words: "D_c increases with r (the same sentence)",
            rule: "trend",
            model: "Eq. 1 (simulation)",
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
        model: s.model.into(),
    }
}

/// The claims of the paper that the figure data cannot decide yet, with what each needs.
pub fn not_computable() -> Vec<NotComputable> {
    // every claim of the registry has a rule now (issue 34); the list stays for claims a
    // later reading of the paper finds and no rule decides yet
    Vec::new()
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

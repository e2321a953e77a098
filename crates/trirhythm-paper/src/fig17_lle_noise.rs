//! Fig. 17: the largest Lyapunov exponent (frozen noise) against the noise intensity D for four
//! μ0 at τ = 0.06 (a) and four τ at μ0 = 0.001 (b), with error bars, and the paper's claim (the
//! LLE turns positive past a critical D) checked curve by curve.
//!
//! One configuration ([`FIG17`]) of the LLE-against-noise computation it shares with
//! Fig. 18 ([`crate::lle`]). Checked by `tests/figures.rs`.

use crate::lle::{lle_against_noise_figure, LleAgainstNoise, LleNoiseFigure, NoisePanel};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
use trirhythm::Result;

/// Fig. 17's panels and the values chosen where the paper prints none.
pub const FIG17: LleNoiseFigure = LleNoiseFigure {
    number: 17,
    title: "largest Lyapunov exponent against noise for several μ0 and τ",
    caption_title: "largest Lyapunov exponent (frozen noise) against D",
    panels: [
        NoisePanel {
            caption: "(a) τ = 0.06",
            preset: "fig17a",
            key: "mu0",
            values: &[0.001, 0.01, 0.05, 0.1],
        },
        NoisePanel {
            caption: "(b) μ0 = 0.001",
            preset: "fig17b",
            key: "tau",
            values: &[0.06, 0.25, 0.5, 1.0],
        },
    ],
    varying: &["mu0", "tau", "D"],
    choices: "the paper does not print the four μ0 and τ values nor the D range: μ0 ∈ {0.001, 0.01, 0.05, 0.1}, τ ∈ {0.06, 0.25, 0.5, 1}, D: ten values log-spaced in [0.001, 2] chosen",
    dt_check: (0, 0.001, 0.1),
};

/// Fig. 17's data.
#[derive(Serialize, Deserialize)]
#[serde(transparent)]
pub struct Fig17(pub LleAgainstNoise);

impl Figure for Fig17 {
    const NUMBER: u32 = 17;
    const TITLE: &'static str = FIG17.title;

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig17> {
        lle_against_noise_figure(&FIG17, options, monitor).map(Fig17)
    }

    fn validate(&self) -> crate::validate::Valid {
        self.0.validate()
    }

    fn tables(&self) -> Vec<Table> {
        self.0.tables()
    }
}

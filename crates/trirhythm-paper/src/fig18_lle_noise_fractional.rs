//! Fig. 18: the largest Lyapunov exponent (frozen noise) against the noise intensity D for four
//! λ at r = 0.998 (a) and four r at λ = 0.998 (b), μ0 = 0.001, τ = 0.025, with error bars, and the
//! paper's claims (the LLE turns positive past a critical D; more impact loss, more chaos)
//! checked curve by curve.
//!
//! One configuration ([`FIG18`]) of the LLE-against-noise computation it shares with
//! Fig. 17 ([`crate::lle`]). Checked by `tests/figures.rs`.

use crate::lle::{lle_against_noise_figure, LleAgainstNoise, LleNoiseFigure, NoisePanel};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
use trirhythm::Result;

/// Fig. 18's panels and the values chosen where the paper prints none.
pub const FIG18: LleNoiseFigure = LleNoiseFigure {
    number: 18,
    title: "largest Lyapunov exponent against noise for several λ and r",
    caption_title: "largest Lyapunov exponent (frozen noise) against D, fractional order and restitution",
    panels: [
        NoisePanel {
            caption: "(a) r = 0.998",
            preset: "fig18a",
            key: "lambda",
            values: &[0.95, 0.98, 0.995, 1.0],
        },
        NoisePanel {
            caption: "(b) λ = 0.998",
            preset: "fig18b",
            key: "r",
            values: &[0.998, 0.95, 0.9, 0.8],
        },
    ],
    varying: &["lambda", "r", "D"],
    choices: "the paper does not print the four λ and r values, ω0 nor the D range: λ ∈ {0.95, 0.98, 0.995, 1}, r ∈ {0.998, 0.95, 0.9, 0.8}, ω0 = 0.9, D: ten values log-spaced in [0.001, 2] chosen",
    dt_check: (1, 0.9, 0.1),
};

/// Fig. 18's data.
#[derive(Serialize, Deserialize)]
#[serde(transparent)]
pub struct Fig18(pub LleAgainstNoise);

impl Figure for Fig18 {
    const NUMBER: u32 = 18;
    const TITLE: &'static str = FIG18.title;

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig18> {
        lle_against_noise_figure(&FIG18, options, monitor).map(Fig18)
    }

    fn validate(&self) -> crate::validate::Valid {
        self.0.validate()
    }

    fn tables(&self) -> Vec<Table> {
        self.0.tables()
    }
}

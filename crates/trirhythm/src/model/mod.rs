//! The model: parameters of Eq. (1), their validation, and the paper's parameter sets; the
//! model description of the whole class ([`Model`], its terms in [`terms`], its TOML file).
//!
//! Equation (Eq. 1 of the paper):
//! D^{1+λ}U − μ0 P(U) U̇ + ω0² U = η(t) for U > 0, U̇₊ = −r U̇₋ at U = 0,
//! P(U) = Σ_k c_k U^{2k}; the paper's P(U) = 1 − U² + α0U⁴ − β0U⁶ + γ0U⁸ − δ0U¹⁰,
//! ⟨η(t)η(s)⟩ = (D/τ) e^{−|t−s|/τ} (τ = 0: white noise, ⟨η(t)η(s)⟩ = 2D δ(t−s)).
//!
//! Method: plain data with validation at construction ([`Params::validate`] is called by every
//! constructor of the crate that consumes parameters), presets for every figure of the paper
//! with the choices the paper leaves open documented in [`Preset::notes`].
//!
//! Tests: `tests/averaging.rs::invalid_parameters_are_rejected_with_their_name` (proptest: every
//! invalid value is rejected, the message names the parameter and its range) and the unit tests
//! below (keys round-trip, presets validate).

mod class;
mod equivalents;
mod file;
pub mod terms;

pub use class::{GeneralTerms, Model, PaperFamily};
pub use equivalents::Equivalents;
pub use file::FORMAT;
pub use terms::{
    Dissipation, Fractional, Harmonic, Keep, Leading, NoiseTerm, Noises, Restitution, Restoring,
    SpeedRestitution, Start, Wall,
};

use crate::error::{Error, Result};

/// The damping polynomial P(U) = Σ_k c_k U^{2k} of Eq. (1), of any even degree.
///
/// The paper's polynomial is `[1, −1, α0, −β0, γ0, −δ0]` ([`Damping::paper`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Damping {
    /// c_k, the coefficient of U^{2k}; c_0 multiplies the linear (negative-damping) term.
    pub coefficients: Vec<f64>,
}

impl Damping {
    /// The paper's polynomial 1 − U² + α0U⁴ − β0U⁶ + γ0U⁸ − δ0U¹⁰ (Eq. 1).
    pub fn paper(alpha0: f64, beta0: f64, gamma0: f64, delta0: f64) -> Self {
        Damping {
            coefficients: vec![1.0, -1.0, alpha0, -beta0, gamma0, -delta0],
        }
    }

    /// P(U) at `u`.
    #[inline]
    pub fn eval(&self, u: f64) -> f64 {
        let u2 = u * u;
        self.coefficients
            .iter()
            .rev()
            .fold(0.0, |acc, &c| acc * u2 + c)
    }

    /// Coefficient of U^{2k} (zero beyond the stored degree).
    pub fn coefficient(&self, k: usize) -> f64 {
        self.coefficients.get(k).copied().unwrap_or(0.0)
    }

    /// Set the coefficient of U^{2k}, growing the polynomial if needed; k < [`MAX_COEFFICIENTS`]
    /// (the value itself is checked by [`Params::validate`]).
    pub fn set_coefficient(&mut self, k: usize, value: f64) -> Result<()> {
        if k >= MAX_COEFFICIENTS {
            return Err(Error::invalid(
                format!("c{k}"),
                value,
                format!(
                    "keys c0 … c{} only (P of degree ≤ {} in U)",
                    MAX_COEFFICIENTS - 1,
                    2 * (MAX_COEFFICIENTS - 1)
                ),
            ));
        }
        if self.coefficients.len() <= k {
            self.coefficients.resize(k + 1, 0.0);
        }
        self.coefficients[k] = value;
        Ok(())
    }

    /// The paper's control parameters (α0, β0, γ0, δ0) read back from the coefficients.
    pub fn control_parameters(&self) -> [f64; 4] {
        [
            self.coefficient(2),
            -self.coefficient(3),
            self.coefficient(4),
            -self.coefficient(5),
        ]
    }
}

/// Parameters of Eq. (1).
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    /// Nonlinearity μ0 > 0 multiplying the damping polynomial (Eq. 1).
    pub mu0: f64,
    /// Natural frequency ω0 > 0 (Eq. 1).
    pub omega0: f64,
    /// Fractional order λ ∈ (0, 1]; the derivative is the Caputo D^{1+λ} (Eq. 1, 3).
    pub lambda: f64,
    /// Restitution coefficient r ∈ [0, 1] of the impact law U̇₊ = −r U̇₋ (Eq. 1).
    pub restitution: f64,
    /// Damping polynomial P(U) (Eq. 1).
    pub damping: Damping,
    /// Noise intensity D ≥ 0: ⟨η(t)η(s)⟩ = (D/τ) e^{−|t−s|/τ} (Eq. 1, 21).
    pub noise_intensity: f64,
    /// Noise correlation time τ ≥ 0 (τ = 0: white noise of intensity D).
    pub correlation_time: f64,
}

/// The paper's standard control parameters (α0, β0, γ0, δ0) = (0.144, 0.005, 5.862e-5, 2.13e-7).
pub const STANDARD_CONTROL: [f64; 4] = [0.144, 0.005, 5.862e-5, 2.13e-7];

impl Default for Params {
    /// Fig. 4(c)'s set with r = 1, D = 0, τ = 0: μ0 = 0.01, ω0 = 1, λ = 0.998, standard control.
    fn default() -> Self {
        let [a, b, g, d] = STANDARD_CONTROL;
        Params {
            mu0: 0.01,
            omega0: 1.0,
            lambda: 0.998,
            restitution: 1.0,
            damping: Damping::paper(a, b, g, d),
            noise_intensity: 0.0,
            correlation_time: 0.0,
        }
    }
}

/// Upper end of μ0 and ω0 (the paper uses μ0 ≤ 0.7, ω0 ≤ 1): beyond it the equivalents and
/// the averaged integrals overflow or the quadratures' work grows without bound.
pub const MAX_SCALE: f64 = 1e3;
/// Lower end of ω0 (the paper's smallest is 0.3): σ1 ∝ 1/ω0² overflows for ω0 → 0, and a
/// vanishing restoring force leaves the averaging's oscillation without a period.
pub const MIN_FREQUENCY: f64 = 1e-6;
/// Upper end of D and τ.
pub const MAX_NOISE: f64 = 1e6;
/// Largest |c_k| of the damping polynomial (the paper's are ≤ 1).
pub const MAX_COEFFICIENT: f64 = 1e20;
/// Most coefficients c0 … c20 (P of degree ≤ 40 in U; the paper's has six).
pub const MAX_COEFFICIENTS: usize = 21;

/// The keys users set parameters by, in display order.
pub const KEYS: [&str; 10] = [
    "mu0", "omega0", "lambda", "r", "alpha0", "beta0", "gamma0", "delta0", "D", "tau",
];

impl Params {
    /// Check every field; the error names the parameter, its value and the allowed range.
    pub fn validate(&self) -> Result<()> {
        fn check(name: &str, v: f64, ok: bool, allowed: &str) -> Result<()> {
            if v.is_finite() && ok {
                Ok(())
            } else {
                Err(Error::invalid(name, v, allowed))
            }
        }
        check(
            "mu0",
            self.mu0,
            self.mu0 > 0.0 && self.mu0 <= MAX_SCALE,
            "(0, 1e3]",
        )?;
        check(
            "omega0",
            self.omega0,
            (MIN_FREQUENCY..=MAX_SCALE).contains(&self.omega0),
            "[1e-6, 1e3]",
        )?;
        check(
            "lambda",
            self.lambda,
            self.lambda > 0.0 && self.lambda <= 1.0,
            "(0, 1]",
        )?;
        check(
            "r",
            self.restitution,
            (0.0..=1.0).contains(&self.restitution),
            "[0, 1]",
        )?;
        check(
            "D",
            self.noise_intensity,
            (0.0..=MAX_NOISE).contains(&self.noise_intensity),
            "[0, 1e6]",
        )?;
        check(
            "tau",
            self.correlation_time,
            (0.0..=MAX_NOISE).contains(&self.correlation_time),
            "[0, 1e6]",
        )?;
        if self.damping.coefficients.is_empty() {
            return Err(Error::invalid(
                "c0",
                f64::NAN,
                "a damping polynomial with at least one coefficient",
            ));
        }
        if self.damping.coefficients.len() > MAX_COEFFICIENTS {
            let k = self.damping.coefficients.len() - 1;
            return Err(Error::invalid(
                format!("c{k}"),
                self.damping.coefficients[k],
                format!(
                    "coefficients c0 … c{} only (P of degree ≤ {} in U)",
                    MAX_COEFFICIENTS - 1,
                    2 * (MAX_COEFFICIENTS - 1)
                ),
            ));
        }
        for (k, &c) in self.damping.coefficients.iter().enumerate() {
            let (name, value) = coefficient_name(k, c);
            check(&name, value, c.abs() <= MAX_COEFFICIENT, "[-1e20, 1e20]")?;
        }
        Ok(())
    }

    /// The value of a parameter by key (see [`KEYS`]; `c<k>` reads the coefficient of U^{2k}).
    pub fn get(&self, key: &str) -> Result<f64> {
        Ok(match key {
            "mu0" => self.mu0,
            "omega0" => self.omega0,
            "lambda" => self.lambda,
            "r" => self.restitution,
            "alpha0" => self.damping.coefficient(2),
            "beta0" => -self.damping.coefficient(3),
            "gamma0" => self.damping.coefficient(4),
            "delta0" => -self.damping.coefficient(5),
            "D" => self.noise_intensity,
            "tau" => self.correlation_time,
            _ => match coefficient_index(key) {
                Some(k) => self.damping.coefficient(k),
                None => return Err(unknown_key(key)),
            },
        })
    }

    /// Set a parameter by key without validating (call [`Params::validate`] after a batch, or
    /// use [`Params::with`]).
    pub fn set(&mut self, key: &str, value: f64) -> Result<()> {
        match key {
            "mu0" => self.mu0 = value,
            "omega0" => self.omega0 = value,
            "lambda" => self.lambda = value,
            "r" => self.restitution = value,
            "alpha0" => self.damping.set_coefficient(2, value)?,
            "beta0" => self.damping.set_coefficient(3, -value)?,
            "gamma0" => self.damping.set_coefficient(4, value)?,
            "delta0" => self.damping.set_coefficient(5, -value)?,
            "D" => self.noise_intensity = value,
            "tau" => self.correlation_time = value,
            _ => match coefficient_index(key) {
                Some(k) if k < MAX_COEFFICIENTS => self.damping.set_coefficient(k, value)?,
                Some(_) => {
                    return Err(Error::invalid(
                        key,
                        value,
                        format!(
                            "keys c0 … c{} only (P of degree ≤ {} in U)",
                            MAX_COEFFICIENTS - 1,
                            2 * (MAX_COEFFICIENTS - 1)
                        ),
                    ))
                }
                None => return Err(unknown_key(key)),
            },
        }
        Ok(())
    }

    /// A copy with one parameter changed, validated.
    pub fn with(&self, key: &str, value: f64) -> Result<Params> {
        let mut p = self.clone();
        p.set(key, value)?;
        p.validate()?;
        Ok(p)
    }

    /// All parameters as `(key, value)` pairs in [`KEYS`] order, then any coefficient beyond
    /// U¹⁰ as `c<k>`.
    pub fn key_values(&self) -> Vec<(String, f64)> {
        let mut out: Vec<(String, f64)> = KEYS
            .iter()
            .map(|k| (k.to_string(), self.get(k).expect("known key")))
            .collect();
        if self.damping.coefficient(0) != 1.0 || self.damping.coefficient(1) != -1.0 {
            out.push(("c0".into(), self.damping.coefficient(0)));
            out.push(("c1".into(), self.damping.coefficient(1)));
        }
        for k in 6..self.damping.coefficients.len() {
            out.push((format!("c{k}"), self.damping.coefficient(k)));
        }
        out
    }

    /// `key=value` pairs joined by spaces, for headers and captions.
    pub fn describe(&self) -> String {
        self.key_values()
            .iter()
            .map(|(k, v)| format!("{k}={}", crate::error::Exact(*v)))
            .collect::<Vec<_>>()
            .join(" ")
    }
}

/// k of a key `c<k>` (any number of digits; `c99999999999999999999` is a coefficient key out
/// of range, not an unknown key).
/// The user's name and value for coefficient c_k of U^{2k} holding `c`: α0 = c2, β0 = −c3,
/// γ0 = c4, δ0 = −c5, `c<k>` otherwise.
pub fn coefficient_name(k: usize, c: f64) -> (String, f64) {
    match k {
        2 => ("alpha0".to_string(), c),
        3 => ("beta0".to_string(), -c),
        4 => ("gamma0".to_string(), c),
        5 => ("delta0".to_string(), -c),
        _ => (format!("c{k}"), c),
    }
}

fn coefficient_index(key: &str) -> Option<usize> {
    let digits = key.strip_prefix('c')?;
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some(digits.parse::<usize>().unwrap_or(usize::MAX))
}

fn unknown_key(key: &str) -> Error {
    Error::Unknown {
        kind: "parameter",
        name: key.to_string(),
        expected: format!("{} or c<k> (coefficient of U^(2k))", KEYS.join(", ")),
    }
}

/// A named parameter set of one of the paper's figures.
#[derive(Debug, Clone)]
pub struct Preset {
    /// Name users type, e.g. `fig4c`.
    pub name: &'static str,
    /// What the set is for.
    pub description: &'static str,
    /// The parameters.
    pub params: Params,
    /// Values the paper leaves out or prints inconsistently, and what the project chose.
    pub notes: &'static [&'static str],
}

#[allow(clippy::too_many_arguments)]
fn set(mu0: f64, omega0: f64, lambda: f64, r: f64, control: [f64; 4], d: f64, tau: f64) -> Params {
    let [a, b, g, dl] = control;
    Params {
        mu0,
        omega0,
        lambda,
        restitution: r,
        damping: Damping::paper(a, b, g, dl),
        noise_intensity: d,
        correlation_time: tau,
    }
}

const C: [f64; 4] = STANDARD_CONTROL;
const C_FIG4AB: [f64; 4] = [0.144, 0.005, 5.7e-5, 2.1e-7];
const C_FIG4D: [f64; 4] = [0.144, 0.005, 4.3e-5, 1.1e-7];
const C_FIG2I: [f64; 4] = [0.144, 0.005, 0.0, 0.0];

const LAMBDA_CHOSEN: &str = "λ is not printed; λ = 1 chosen (the integer-order limit)";
const OMEGA_CHOSEN: &str = "ω0 is not printed; ω0 = 1 chosen (as in Figs 2-6)";
const GAMMA_TYPO: &str =
    "the caption prints γ0 = 5.82e-5 where every other figure has 5.862e-5: treated as a typo";

/// Every figure's parameter set. Where a figure sweeps a parameter, the preset holds one
/// representative value and the figure command sweeps it.
pub fn presets() -> Vec<Preset> {
    vec![
        Preset {
            name: "fig1",
            description: "Fig. 1: fractional vs integer-order limit cycles",
            params: set(0.002, 0.9, 0.997, 1.0, C, 0.0, 0.0),
            notes: &[],
        },
        Preset {
            name: "fig2i",
            description: "Fig. 2(i): (α0, β0) plane, γ0 = δ0 = 0",
            params: set(0.01, 1.0, 1.0, 1.0, C_FIG2I, 0.0, 0.0),
            notes: &[LAMBDA_CHOSEN],
        },
        Preset {
            name: "fig2ii",
            description: "Fig. 2(ii): (γ0, δ0) plane at (α0, β0) = (0.144, 0.005)",
            params: set(0.01, 1.0, 1.0, 1.0, C, 0.0, 0.0),
            notes: &[LAMBDA_CHOSEN],
        },
        Preset {
            name: "fig3",
            description: "Fig. 3: (γ0, δ0) plane for several r (r swept)",
            params: set(0.01, 1.0, 0.999, 1.0, C, 0.0, 0.0),
            notes: &[
                "the four r values are not printed; the figure command chooses and prints them",
            ],
        },
        Preset {
            name: "fig4a",
            description: "Fig. 4(a): f(A0) at r ≈ 1",
            params: set(0.01, 1.0, 0.998, 1.0, C_FIG4AB, 0.0, 0.0),
            notes: &["the text says r ≈ 1; r = 1 chosen"],
        },
        Preset {
            name: "fig4b",
            description: "Fig. 4(b): f(A0) at r = 0.98",
            params: set(0.01, 1.0, 0.998, 0.98, C_FIG4AB, 0.0, 0.0),
            notes: &[],
        },
        Preset {
            name: "fig4c",
            description: "Fig. 4(c): f(A0) at r = 0.96",
            params: set(0.01, 1.0, 0.998, 0.96, C, 0.0, 0.0),
            notes: &[],
        },
        Preset {
            name: "fig4d",
            description: "Fig. 4(d): f(A0) at r = 0.90",
            params: set(0.01, 1.0, 0.998, 0.90, C_FIG4D, 0.0, 0.0),
            notes: &[],
        },
        Preset {
            name: "fig5",
            description: "Fig. 5: A0 vs r (r swept; μ0 ∈ {0.001, 0.01, 0.04, 0.3, 0.7})",
            params: set(0.01, 1.0, 1.0, 1.0, C, 0.0, 0.0),
            notes: &[],
        },
        Preset {
            name: "fig6",
            description: "Fig. 6: (γ0, δ0) plane for several λ (λ swept)",
            params: set(0.01, 1.0, 0.999, 0.998, C, 0.0, 0.0),
            notes: &[
                "the four λ values are not printed; the figure command chooses and prints them",
            ],
        },
        Preset {
            name: "fig7a",
            description: "Fig. 7(a): U_eff for several r at λ = 0.998",
            params: set(0.01, 1.0, 0.998, 0.998, C, 0.0, 0.0),
            notes: &[
                OMEGA_CHOSEN,
                "the r values are not printed; the figure command chooses and prints them",
            ],
        },
        Preset {
            name: "fig7b",
            description: "Fig. 7(b): U_eff for several λ at r = 0.998",
            params: set(0.01, 1.0, 0.998, 0.998, C, 0.0, 0.0),
            notes: &[
                OMEGA_CHOSEN,
                "the λ values are not printed; the figure command chooses and prints them",
            ],
        },
        Preset {
            name: "fig8",
            description: "Fig. 8: energy barriers of U_eff",
            params: set(0.01, 1.0, 0.999, 0.999, C, 0.24, 5.0),
            notes: &[
                OMEGA_CHOSEN,
                "τ is not printed; τ = 5 chosen: at D = 0.24 the inner well A01 (and with it ΔU1, ΔU2) exists only for τ ≳ 3 (paper variant) or τ ≳ 2 (consistent)",
            ],
        },
        Preset {
            name: "fig9",
            description: "Fig. 9: barriers over (τ, λ) (τ, λ swept; r ∈ {0.998, 0.990})",
            params: set(0.01, 1.0, 0.998, 0.998, C, 0.25, 0.5),
            notes: &[OMEGA_CHOSEN, GAMMA_TYPO],
        },
        Preset {
            name: "fig10",
            description: "Fig. 10: P-bifurcation map in (λ, τ) (D ∈ {0.05, 0.3, 0.7, 1.2})",
            params: set(0.01, 0.9, 0.998, 0.998, C, 0.05, 0.5),
            notes: &["r is not printed; r = 0.998 chosen"],
        },
        Preset {
            name: "fig11",
            description: "Fig. 11: amplitude and P(A) vs λ, theory vs simulation",
            params: set(0.01, 1.0, 0.998, 0.998, C, 0.1, 0.5),
            notes: &["μ0, ω0, r are not printed; μ0 = 0.01, ω0 = 1, r = 0.998 chosen"],
        },
        Preset {
            name: "fig12a",
            description: "Fig. 12(a): (μ0, r) plane at λ = 0.995, ω0 = 0.9",
            params: set(0.01, 0.9, 0.995, 0.998, C, 0.1, 0.5),
            notes: &[],
        },
        Preset {
            name: "fig12b",
            description: "Fig. 12(b): (μ0, r) plane at λ = 0.995, ω0 = 1.0",
            params: set(0.01, 1.0, 0.995, 0.998, C, 0.1, 0.5),
            notes: &["the caption prints ω0 = 0.9 twice; 1.0 is used for panels b and d"],
        },
        Preset {
            name: "fig12c",
            description: "Fig. 12(c): (λ, r) plane at μ0 = 0.01, ω0 = 0.9",
            params: set(0.01, 0.9, 0.995, 0.998, C, 0.1, 0.5),
            notes: &[],
        },
        Preset {
            name: "fig12d",
            description: "Fig. 12(d): (λ, r) plane at μ0 = 0.01, ω0 = 1.0",
            params: set(0.01, 1.0, 0.995, 0.998, C, 0.1, 0.5),
            notes: &["the caption prints ω0 = 0.9 twice; 1.0 is used for panels b and d"],
        },
        Preset {
            name: "fig13a",
            description: "Fig. 13(a): P(A) for several r at μ0 = 0.005",
            params: set(0.005, 1.0, 0.998, 0.99, C, 0.1, 0.5),
            notes: &["λ and ω0 are not printed; λ = 0.998, ω0 = 1 chosen"],
        },
        Preset {
            name: "fig13b",
            description: "Fig. 13(b): P(A) for several r at μ0 = 0.2",
            params: set(0.2, 1.0, 0.998, 0.999, C, 0.1, 0.5),
            notes: &["λ and ω0 are not printed; λ = 0.998, ω0 = 1 chosen"],
        },
        Preset {
            name: "fig14",
            description: "Fig. 14: joint PDF P(U, U̇) for several r",
            params: set(0.05, 1.0, 0.998, 0.999, C, 0.25, 0.5),
            notes: &[
                "λ and ω0 are not printed; λ = 0.998, ω0 = 1 chosen",
                GAMMA_TYPO,
            ],
        },
        Preset {
            name: "fig15",
            description: "Fig. 15: oscillation boundary μ0 vs λ and r (ω0 ∈ {0.9, 0.5, 0.3})",
            params: set(0.01, 0.9, 0.998, 0.998, C, 0.0, 0.0),
            notes: &[],
        },
        Preset {
            name: "fig16",
            description:
                "Fig. 16: oscillation regions in (μ0, λ) at r = 0.99 and (μ0, r) at λ = 0.999",
            params: set(0.01, 1.0, 0.999, 0.99, C, 0.0, 0.0),
            notes: &[OMEGA_CHOSEN],
        },
        Preset {
            name: "fig17a",
            description: "Fig. 17(a): LLE vs D for several μ0 at τ = 0.06",
            params: set(0.001, 0.9, 0.995, 0.998, C, 0.1, 0.06),
            notes: &[],
        },
        Preset {
            name: "fig17b",
            description: "Fig. 17(b): LLE vs D for several τ at μ0 = 0.001",
            params: set(0.001, 0.9, 0.995, 0.998, C, 0.1, 0.06),
            notes: &[],
        },
        Preset {
            name: "fig18a",
            description: "Fig. 18(a): LLE vs D for several λ at r = 0.998",
            params: set(0.001, 0.9, 0.998, 0.998, C, 0.1, 0.025),
            notes: &["ω0 is not printed; ω0 = 0.9 chosen (as in Fig. 17)"],
        },
        Preset {
            name: "fig18b",
            description: "Fig. 18(b): LLE vs D for several r at λ = 0.998",
            params: set(0.001, 0.9, 0.998, 0.998, C, 0.1, 0.025),
            notes: &["ω0 is not printed; ω0 = 0.9 chosen (as in Fig. 17)"],
        },
        Preset {
            name: "fig19",
            description: "Fig. 19: critical noise D_c vs μ0, τ, λ, r",
            params: set(0.01, 0.9, 0.998, 0.998, C, 0.1, 0.5),
            notes: &[
                "the caption prints r = 9.998: 0.998 is meant",
                "ω0 is not printed; ω0 = 0.9 chosen (as in Fig. 17)",
            ],
        },
    ]
}

/// Look a preset up by name.
pub fn preset(name: &str) -> Result<Preset> {
    let all = presets();
    let names: Vec<&str> = all.iter().map(|p| p.name).collect();
    let expected = names.join(", ");
    all.into_iter()
        .find(|p| p.name == name)
        .ok_or(Error::Unknown {
            kind: "preset",
            name: name.to_string(),
            expected,
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_validates_and_names_are_unique() {
        let all = presets();
        for p in &all {
            p.params
                .validate()
                .unwrap_or_else(|e| panic!("{}: {e}", p.name));
        }
        let mut names: Vec<_> = all.iter().map(|p| p.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), all.len());
    }

    #[test]
    fn keys_round_trip() {
        let mut p = Params::default();
        for (i, key) in KEYS.iter().enumerate() {
            let v = 0.1 + i as f64 * 0.01;
            p.set(key, v).unwrap();
            assert_eq!(p.get(key).unwrap(), v, "{key}");
        }
        p.set("c7", 3e-12).unwrap();
        assert_eq!(p.damping.coefficients.len(), 8);
        assert_eq!(p.get("c7").unwrap(), 3e-12);
        assert!(p.set("nope", 1.0).is_err());
    }

    #[test]
    fn paper_polynomial_evaluates() {
        let d = Damping::paper(0.144, 0.005, 5.862e-5, 2.13e-7);
        let u: f64 = 2.0;
        let expect = 1.0 - u.powi(2) + 0.144 * u.powi(4) - 0.005 * u.powi(6) + 5.862e-5 * u.powi(8)
            - 2.13e-7 * u.powi(10);
        assert!((d.eval(u) - expect).abs() < 1e-14);
    }
}

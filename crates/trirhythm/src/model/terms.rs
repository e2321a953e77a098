//! The terms of the model class, each a small value that validates itself.
//!
//! Equation (the class of which the paper's Eq. 1 is one value):
//! D^{1+λ}U + Σ_{j≤2} K_j D^{α_j}U − h(U, U̇)·U̇ + k(U) = F cos(Ωt + φ) + η_a(t) + U·η_m(t),
//! h = μ0·P(U) + Σ_{k≥1} d_k U̇^{2k}, P(U) = Σ_k c_k U^{2k}, k(U) = ω0²U + k3U³ + k5U⁵,
//! walls U = δ with U̇₊ = −r(|U̇₋|)·U̇₋, r constant or r(v) = r_fast + (r0 − r_fast)e^{−v/v_s};
//! each noise white (⟨η(t)η(s)⟩ = 2Dδ(t − s)) or Ornstein–Uhlenbeck
//! (⟨η(t)η(s)⟩ = (D/τ)e^{−|t−s|/τ}), the two with correlation coefficient c.
//!
//! Method: plain serde data, one struct per table of the model file (`docs/model-file.md`);
//! each term's `validate(prefix)` checks its own ranges and names the dotted field
//! (`wall.1.restitution.speed`), its value and the allowed range. Cross-field checks are
//! [`super::Model::validate`]'s.
//!
//! Reference: the class is issue 36's (a survey of the family's stochastic papers); the paper's
//! Eq. (1) is the value with λ as printed, no Rayleigh, Duffing, fractional, forcing or
//! multiplicative term and one wall at 0.
//!
//! Tests: `tests/model_file.rs` (every range refused with the field named; the round trip).

use super::{MAX_COEFFICIENT, MAX_COEFFICIENTS, MAX_NOISE, MAX_SCALE, MIN_FREQUENCY};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// Largest |δ| of a wall and |U(0)|, |U̇(0)| of the start.
pub const MAX_POSITION: f64 = 1e6;
/// Most Rayleigh coefficients d_1 … d_20 (terms up to U̇⁴⁰).
pub const MAX_RAYLEIGH: usize = 20;
/// Most fractional terms K_j D^{α_j}U.
pub const MAX_FRACTIONAL: usize = 2;
/// Most walls.
pub const MAX_WALLS: usize = 2;

/// `Ok` when `v` is finite and `ok`, else the error naming `name`, `v` and `allowed`.
pub(crate) fn check(name: &str, v: f64, ok: bool, allowed: &str) -> Result<()> {
    if v.is_finite() && ok {
        Ok(())
    } else {
        Err(Error::invalid(name, v, allowed))
    }
}

/// The leading derivative D^{1+λ}U (Caputo).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Leading {
    /// Fractional order λ ∈ (0, 1] of D^{1+λ} (λ = 1: Ü) (Eq. 1, 3).
    pub lambda: f64,
}

impl Leading {
    /// λ ∈ (0, 1].
    pub fn validate(&self) -> Result<()> {
        check(
            "leading.lambda",
            self.lambda,
            self.lambda > 0.0 && self.lambda <= 1.0,
            "(0, 1]",
        )
    }
}

/// The damping h(U, U̇) = μ0·P(U) + Σ_{k≥1} d_k U̇^{2k} of the term −h·U̇.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Dissipation {
    /// μ0 > 0 multiplying P(U) (Eq. 1).
    pub mu0: f64,
    /// c_k, the coefficient of U^{2k} in P(U) (k = 0 … 20); default the paper's
    /// [1, −1, α0, −β0, γ0, −δ0] with the standard control parameters.
    #[serde(default = "paper_coefficients")]
    pub coefficients: Vec<f64>,
    /// d_k, the coefficient of U̇^{2k} (k = 1 … 20: `rayleigh[0]` multiplies U̇²); default none.
    #[serde(default)]
    pub rayleigh: Vec<f64>,
}

/// The paper's P(U) with the standard control parameters (0.144, 0.005, 5.862e-5, 2.13e-7).
pub fn paper_coefficients() -> Vec<f64> {
    let [a, b, g, d] = super::STANDARD_CONTROL;
    super::Damping::paper(a, b, g, d).coefficients
}

impl Dissipation {
    /// μ0 ∈ (0, 1e3], 1 to 21 coefficients c_k and at most 20 d_k, each |·| ≤ 1e20.
    pub fn validate(&self) -> Result<()> {
        check(
            "damping.mu0",
            self.mu0,
            self.mu0 > 0.0 && self.mu0 <= MAX_SCALE,
            "(0, 1e3]",
        )?;
        let n = self.coefficients.len();
        if n == 0 || n > MAX_COEFFICIENTS {
            return Err(Error::invalid(
                "damping.coefficients",
                n as f64,
                format!(
                    "1 to {MAX_COEFFICIENTS} coefficients c0 … c{} (P of degree ≤ {} in U)",
                    MAX_COEFFICIENTS - 1,
                    2 * (MAX_COEFFICIENTS - 1)
                ),
            ));
        }
        for (k, &c) in self.coefficients.iter().enumerate() {
            check(
                &format!("damping.coefficients.{k}"),
                c,
                c.abs() <= MAX_COEFFICIENT,
                "[-1e20, 1e20]",
            )?;
        }
        if self.rayleigh.len() > MAX_RAYLEIGH {
            return Err(Error::invalid(
                "damping.rayleigh",
                self.rayleigh.len() as f64,
                format!("at most {MAX_RAYLEIGH} coefficients (terms up to U̇^40)"),
            ));
        }
        for (k, &d) in self.rayleigh.iter().enumerate() {
            check(
                &format!("damping.rayleigh.{k}"),
                d,
                d.abs() <= MAX_COEFFICIENT,
                "[-1e20, 1e20]",
            )?;
        }
        Ok(())
    }

    /// Whether a Rayleigh term is present (a non-zero d_k).
    pub fn has_rayleigh(&self) -> bool {
        self.rayleigh.iter().any(|&d| d != 0.0)
    }
}

/// The restoring force k(U) = ω0²U + k3U³ + k5U⁵.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Restoring {
    /// Natural frequency ω0 ∈ [1e-6, 1e3] (Eq. 1).
    pub omega0: f64,
    /// k3, the coefficient of U³ (Duffing); default 0.
    #[serde(default)]
    pub cubic: f64,
    /// k5, the coefficient of U⁵; default 0.
    #[serde(default)]
    pub quintic: f64,
}

impl Restoring {
    /// ω0 ∈ [1e-6, 1e3], |k3|, |k5| ≤ 1e20.
    pub fn validate(&self) -> Result<()> {
        check(
            "restoring.omega0",
            self.omega0,
            (MIN_FREQUENCY..=MAX_SCALE).contains(&self.omega0),
            "[1e-6, 1e3]",
        )?;
        check(
            "restoring.cubic",
            self.cubic,
            self.cubic.abs() <= MAX_COEFFICIENT,
            "[-1e20, 1e20]",
        )?;
        check(
            "restoring.quintic",
            self.quintic,
            self.quintic.abs() <= MAX_COEFFICIENT,
            "[-1e20, 1e20]",
        )
    }
}

/// A fractional term K·D^α U (Caputo; fractional damping).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Fractional {
    /// K ∈ [0, 1e3].
    pub coefficient: f64,
    /// α ∈ (0, 1].
    pub order: f64,
}

impl Fractional {
    /// K ∈ [0, 1e3], α ∈ (0, 1]; `index` is the term's place in the file's `fractional` list.
    pub fn validate(&self, index: usize) -> Result<()> {
        check(
            &format!("fractional.{index}.coefficient"),
            self.coefficient,
            (0.0..=MAX_SCALE).contains(&self.coefficient),
            "[0, 1e3]",
        )?;
        check(
            &format!("fractional.{index}.order"),
            self.order,
            self.order > 0.0 && self.order <= 1.0,
            "(0, 1]",
        )
    }
}

/// Which side of a wall the motion keeps to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Keep {
    /// U ≥ δ (the paper's wall: U ≥ 0).
    Above,
    /// U ≤ δ.
    Below,
}

impl Keep {
    /// `above` or `below`, as in the file.
    pub fn name(self) -> &'static str {
        match self {
            Keep::Above => "above",
            Keep::Below => "below",
        }
    }
}

/// The restitution law U̇₊ = −r(|U̇₋|)·U̇₋ of a wall.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Restitution {
    /// A constant r ∈ [0, 1] (Eq. 1): `restitution = 0.99`.
    Constant(f64),
    /// r(v) = r_fast + (r0 − r_fast)·e^{−v/speed} of the impact speed v = |U̇₋|: r0 at
    /// grazing impacts, r_fast at fast ones: `restitution = { r0, r_fast, speed }`.
    Speed(SpeedRestitution),
}

/// The speed-dependent law r(v) = r_fast + (r0 − r_fast)·e^{−v/speed}.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpeedRestitution {
    /// r(0) ∈ [0, 1].
    pub r0: f64,
    /// r(∞) ∈ [0, 1].
    pub r_fast: f64,
    /// The speed scale v_s ∈ (0, 1e6].
    pub speed: f64,
}

impl Restitution {
    /// r(v) at the impact speed v = |U̇₋|.
    pub fn at(&self, speed: f64) -> f64 {
        match *self {
            Restitution::Constant(r) => r,
            Restitution::Speed(s) => {
                s.r_fast + (s.r0 - s.r_fast) * crate::maths::exp(-speed.abs() / s.speed)
            }
        }
    }

    fn validate(&self, name: &str) -> Result<()> {
        match *self {
            Restitution::Constant(r) => check(name, r, (0.0..=1.0).contains(&r), "[0, 1]"),
            Restitution::Speed(s) => {
                check(
                    &format!("{name}.r0"),
                    s.r0,
                    (0.0..=1.0).contains(&s.r0),
                    "[0, 1]",
                )?;
                check(
                    &format!("{name}.r_fast"),
                    s.r_fast,
                    (0.0..=1.0).contains(&s.r_fast),
                    "[0, 1]",
                )?;
                check(
                    &format!("{name}.speed"),
                    s.speed,
                    s.speed > 0.0 && s.speed <= MAX_NOISE,
                    "(0, 1e6]",
                )
            }
        }
    }
}

/// A rigid wall at U = δ with its impact law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Wall {
    /// δ, |δ| ≤ 1e6 (the paper: 0).
    pub position: f64,
    /// The side the motion keeps to.
    pub keep: Keep,
    /// U̇₊ = −r U̇₋ (Eq. 1), r constant or speed-dependent.
    pub restitution: Restitution,
}

impl Wall {
    /// δ finite within ±1e6, the restitution law's ranges; `index` is the wall's place in the
    /// file's `wall` list.
    pub fn validate(&self, index: usize) -> Result<()> {
        check(
            &format!("wall.{index}.position"),
            self.position,
            self.position.abs() <= MAX_POSITION,
            "[-1e6, 1e6]",
        )?;
        self.restitution
            .validate(&format!("wall.{index}.restitution"))
    }

    /// Whether U is on the allowed side of (or at) the wall.
    pub fn allows(&self, u: f64) -> bool {
        match self.keep {
            Keep::Above => u >= self.position,
            Keep::Below => u <= self.position,
        }
    }
}

/// Harmonic forcing F cos(Ωt + φ).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Harmonic {
    /// F ∈ [0, 1e6].
    pub amplitude: f64,
    /// Ω ∈ (0, 1e3].
    pub frequency: f64,
    /// φ (radians), |φ| ≤ 1e6; default 0.
    #[serde(default)]
    pub phase: f64,
}

impl Harmonic {
    /// F ∈ [0, 1e6], Ω ∈ (0, 1e3], |φ| ≤ 1e6.
    pub fn validate(&self) -> Result<()> {
        check(
            "forcing.amplitude",
            self.amplitude,
            (0.0..=MAX_NOISE).contains(&self.amplitude),
            "[0, 1e6]",
        )?;
        check(
            "forcing.frequency",
            self.frequency,
            self.frequency > 0.0 && self.frequency <= MAX_SCALE,
            "(0, 1e3]",
        )?;
        check(
            "forcing.phase",
            self.phase,
            self.phase.abs() <= MAX_POSITION,
            "[-1e6, 1e6]",
        )
    }
}

/// One noise source: white (τ = 0, ⟨η(t)η(s)⟩ = 2Dδ(t − s)) or Ornstein–Uhlenbeck
/// (τ > 0, ⟨η(t)η(s)⟩ = (D/τ)e^{−|t−s|/τ}, which tends to 2Dδ as τ → 0) (Eq. 1, 21).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NoiseTerm {
    /// D ∈ [0, 1e6].
    pub intensity: f64,
    /// τ ∈ [0, 1e6]; 0 (or absent): white.
    #[serde(default)]
    pub correlation_time: f64,
}

impl NoiseTerm {
    fn validate(&self, channel: &str) -> Result<()> {
        check(
            &format!("noise.{channel}.intensity"),
            self.intensity,
            (0.0..=MAX_NOISE).contains(&self.intensity),
            "[0, 1e6]",
        )?;
        check(
            &format!("noise.{channel}.correlation_time"),
            self.correlation_time,
            (0.0..=MAX_NOISE).contains(&self.correlation_time),
            "[0, 1e6] (0: white)",
        )
    }
}

/// The excitations by noise: η_a (additive) and η_m (multiplicative, the term U·η_m), with
/// correlation coefficient c = ⟨η_aη_m⟩/√(⟨η_a²⟩⟨η_m²⟩) ∈ [−1, 1] (0: independent).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Noises {
    /// η_a; absent: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub additive: Option<NoiseTerm>,
    /// η_m; absent: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub multiplicative: Option<NoiseTerm>,
    /// c ∈ [−1, 1]; non-zero only with both noises, of the same correlation time.
    #[serde(default)]
    pub correlation: f64,
}

impl Noises {
    /// Each source's ranges; c ∈ [−1, 1], and c ≠ 0 only between two noises of one τ.
    pub fn validate(&self) -> Result<()> {
        if let Some(a) = &self.additive {
            a.validate("additive")?;
        }
        if let Some(m) = &self.multiplicative {
            m.validate("multiplicative")?;
        }
        check(
            "noise.correlation",
            self.correlation,
            (-1.0..=1.0).contains(&self.correlation),
            "[-1, 1]",
        )?;
        if self.correlation != 0.0 {
            match (&self.additive, &self.multiplicative) {
                (Some(a), Some(m)) if a.correlation_time == m.correlation_time => {}
                (Some(_), Some(_)) => return Err(Error::invalid(
                    "noise.correlation",
                    self.correlation,
                    "0 unless noise.additive and noise.multiplicative have one correlation_time",
                )),
                _ => {
                    return Err(Error::invalid(
                        "noise.correlation",
                        self.correlation,
                        "0 unless both noise.additive and noise.multiplicative are given",
                    ))
                }
            }
        }
        Ok(())
    }
}

/// The start (U(0), U̇(0)).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Start {
    /// U(0), |U(0)| ≤ 1e6; default 1.
    #[serde(default = "one")]
    pub u0: f64,
    /// U̇(0), |U̇(0)| ≤ 1e6; default 0.
    #[serde(default)]
    pub v0: f64,
}

fn one() -> f64 {
    1.0
}

impl Default for Start {
    /// (1, 0), the engine's default start.
    fn default() -> Self {
        Start { u0: 1.0, v0: 0.0 }
    }
}

impl Start {
    /// |U(0)|, |U̇(0)| ≤ 1e6.
    pub fn validate(&self) -> Result<()> {
        check(
            "start.u0",
            self.u0,
            self.u0.abs() <= MAX_POSITION,
            "[-1e6, 1e6]",
        )?;
        check(
            "start.v0",
            self.v0,
            self.v0.abs() <= MAX_POSITION,
            "[-1e6, 1e6]",
        )
    }
}

//! The model description: one value of the class of stochastic (fractional) vibro-impact
//! oscillators, of which the paper's Eq. (1) is one value.
//!
//! Equation:
//! D^{1+λ}U + Σ_{j≤2} K_j D^{α_j}U − h(U, U̇)·U̇ + k(U) = F cos(Ωt + φ) + η_a(t) + U·η_m(t),
//! h = μ0·P(U) + Σ_{k≥1} d_k U̇^{2k}, k(U) = ω0²U + k3U³ + k5U⁵, walls none, one at δ or two
//! at δ1 < δ2 (the terms: [`super::terms`]).
//!
//! Method: [`Model`] is plain data whose serde form is the model file (`docs/model-file.md`,
//! [`super::file`]); [`Model::validate`] runs every term's range checks and the cross-field
//! ones (two walls ordered and facing each other, the start on the allowed side of every wall,
//! a correlation only between noises of one correlation time). The paper family's
//! [`Params`] converts losslessly: `Model::from(&params).paper_params() == Some(params)`.
//! [`Model::paper_family`] is the paper's family (refusing every other term by name,
//! [`Error::NotApplicable`]); [`Model::engine_terms`] is what the engine steps: that family plus
//! the General kernel's terms ([`GeneralTerms`]: Duffing, Rayleigh, forcing, fractional terms
//! K·D^αU, multiplicative noise U·η_m, and every wall set other than the paper's — a wall at
//! any δ keeping U above or below, two walls, a speed-dependent restitution).
//!
//! Reference: the paper's Eq. (1) and issue 36's class; `docs/model-file.md`.
//!
//! Tests: `tests/model_file.rs` (presets → file → model bit for bit, the round trip, malformed
//! files refused with the field named, terms the engine does not step refused, and
//! `Problem::from_params(p)` against `Problem::from_model(file of p)`: identical paths).

use super::terms::{
    Dissipation, Fractional, Harmonic, Keep, Leading, NoiseTerm, Noises, Restitution, Restoring,
    Start, Wall, MAX_FRACTIONAL, MAX_WALLS,
};
use super::{Damping, Params};
use crate::error::{Error, Exact, Result};
use serde::{Deserialize, Serialize};

/// One oscillator of the class; its serde form is the model file (without `format`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Model {
    /// D^{1+λ}U.
    pub leading: Leading,
    /// h = μ0·P(U) + Σ d_k U̇^{2k}.
    pub damping: Dissipation,
    /// k(U) = ω0²U + k3U³ + k5U⁵.
    pub restoring: Restoring,
    /// K_j D^{α_j}U, at most two; default none.
    #[serde(default)]
    pub fractional: Vec<Fractional>,
    /// None, one wall, or two (lower keeping above, then upper keeping below); default none.
    #[serde(default, rename = "wall")]
    pub walls: Vec<Wall>,
    /// F cos(Ωt + φ); default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub forcing: Option<Harmonic>,
    /// η_a, η_m and their correlation; default none.
    #[serde(default)]
    pub noise: Noises,
    /// (U(0), U̇(0)); default (1, 0).
    #[serde(default)]
    pub start: Start,
}

/// The part of a model the engine steps today: the paper family's parameters and whether the
/// wall at U = 0 is present (see [`Model::paper_family`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PaperFamily {
    /// μ0, ω0, λ, P(U), D, τ, and r (1 when there is no wall).
    pub params: Params,
    /// Whether the wall at U = 0 (keeping U ≥ 0) is present.
    pub wall: bool,
    /// The start (U(0), U̇(0)).
    pub start: (f64, f64),
}

/// The terms of the class beyond the paper's family that the engine's General kernel steps
/// (`engine::stepper::general`): the odd restoring terms k3U³ + k5U⁵, the Rayleigh damping
/// Σ d_k U̇^{2k} in h, the harmonic forcing F cos(Ωt + φ), the fractional terms K_j·D^{α_j}U,
/// the multiplicative noise U·η_m (with its correlation to the additive noise), and walls other
/// than the paper's (`engine::stepper::walls`). The rest of the equation (μ0P(U), ω0, λ, the
/// additive noise, the paper's wall at 0 if it is the model's) is the [`PaperFamily`] beside it
/// ([`Model::engine_terms`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct GeneralTerms {
    /// k3, the coefficient of U³ in k(U).
    pub cubic: f64,
    /// k5, the coefficient of U⁵ in k(U).
    pub quintic: f64,
    /// d_k, the coefficient of U̇^{2k} in h (`rayleigh[0]` multiplies U̇²); trailing zeros
    /// dropped.
    pub rayleigh: Vec<f64>,
    /// F cos(Ωt + φ), with F ≠ 0.
    pub forcing: Option<Harmonic>,
    /// The walls when they are not the paper's (none, or one at U = 0 keeping U ≥ 0 with a
    /// constant r, which stay in [`PaperFamily::wall`]): one wall at any δ keeping U above or
    /// below it, or two at δ1 < δ2 (lower keeping above, upper keeping below), each with a
    /// constant or speed-dependent restitution (`engine::stepper::walls`). Empty otherwise.
    pub walls: Vec<Wall>,
    /// K_j·D^{α_j}U (Caputo), at most two, each with K ≠ 0 and α ∈ (0, 1].
    pub fractional: Vec<Fractional>,
    /// η_m of U·η_m (white for τ = 0, ⟨η_mη_m⟩ = 2Dδ; else OU), with D ≠ 0.
    pub multiplicative: Option<NoiseTerm>,
    /// The correlation coefficient c ∈ [−1, 1] of η_m with the additive noise (0 without
    /// multiplicative noise; the two of one correlation time).
    pub correlation: f64,
}

impl GeneralTerms {
    /// Whether every term is absent (the paper's family).
    pub fn is_empty(&self) -> bool {
        self.cubic == 0.0
            && self.quintic == 0.0
            && self.rayleigh.is_empty()
            && self.forcing.is_none()
            && self.walls.is_empty()
            && self.fractional.is_empty()
            && self.multiplicative.is_none()
    }

    /// `cubic=… quintic=… rayleigh=[…] forcing: amplitude=… frequency=… phase=…` (or
    /// `forcing: none`), then ` fractional=[K@α,…]` and ` multiplicative: intensity=…
    /// correlation_time=… correlation=…` when present, with the model file's names, for header
    /// lines.
    pub fn describe(&self) -> String {
        let rayleigh: Vec<String> = self
            .rayleigh
            .iter()
            .map(|d| Exact(*d).to_string())
            .collect();
        let forcing = match &self.forcing {
            Some(f) => format!(
                "amplitude={} frequency={} phase={}",
                Exact(f.amplitude),
                Exact(f.frequency),
                Exact(f.phase)
            ),
            None => "none".to_string(),
        };
        let mut line = format!(
            "cubic={} quintic={} rayleigh=[{}] forcing: {forcing}",
            Exact(self.cubic),
            Exact(self.quintic),
            rayleigh.join(",")
        );
        if !self.fractional.is_empty() {
            let terms: Vec<String> = self
                .fractional
                .iter()
                .map(|f| format!("{}@{}", Exact(f.coefficient), Exact(f.order)))
                .collect();
            line.push_str(&format!(" fractional=[{}]", terms.join(",")));
        }
        if let Some(m) = &self.multiplicative {
            line.push_str(&format!(
                " multiplicative: intensity={} correlation_time={} correlation={}",
                Exact(m.intensity),
                Exact(m.correlation_time),
                Exact(self.correlation)
            ));
        }
        // the paper's wall (or none) is said elsewhere; so are the lines without these walls
        if !self.walls.is_empty() {
            let walls: Vec<String> = self.walls.iter().map(describe_wall).collect();
            line.push_str(&format!(" walls: {}", walls.join("; ")));
        }
        line
    }
}

/// `position=… keep=… restitution=…` (or `restitution=r0:…,r_fast:…,speed:…`).
fn describe_wall(w: &Wall) -> String {
    let r = match w.restitution {
        Restitution::Constant(r) => Exact(r).to_string(),
        Restitution::Speed(s) => format!(
            "r0:{},r_fast:{},speed:{}",
            Exact(s.r0),
            Exact(s.r_fast),
            Exact(s.speed)
        ),
    };
    format!(
        "position={} keep={} restitution={r}",
        Exact(w.position),
        w.keep.name()
    )
}

/// Whether `walls` are the paper's: none, or one at U = 0 keeping U ≥ 0 with a constant r.
fn paper_walls(walls: &[Wall]) -> bool {
    match walls {
        [] => true,
        [w] => {
            w.position == 0.0
                && w.keep == Keep::Above
                && matches!(w.restitution, Restitution::Constant(_))
        }
        _ => false,
    }
}

impl From<&Params> for Model {
    /// The paper's Eq. (1) of `p`: the wall at 0 with constant r, additive noise (D, τ) (kept
    /// even at D = 0, so that τ survives), the default start (1, 0). Lossless:
    /// `Model::from(&p).paper_params() == Some(p)`.
    fn from(p: &Params) -> Self {
        Model {
            leading: Leading { lambda: p.lambda },
            damping: Dissipation {
                mu0: p.mu0,
                coefficients: p.damping.coefficients.clone(),
                rayleigh: Vec::new(),
            },
            restoring: Restoring {
                omega0: p.omega0,
                cubic: 0.0,
                quintic: 0.0,
            },
            fractional: Vec::new(),
            walls: vec![Wall {
                position: 0.0,
                keep: Keep::Above,
                restitution: Restitution::Constant(p.restitution),
            }],
            forcing: None,
            noise: Noises {
                additive: Some(super::terms::NoiseTerm {
                    intensity: p.noise_intensity,
                    correlation_time: p.correlation_time,
                }),
                multiplicative: None,
                correlation: 0.0,
            },
            start: Start::default(),
        }
    }
}

impl Model {
    /// Every term's ranges, then the cross-field checks; the error names the dotted field,
    /// its value and the allowed range.
    pub fn validate(&self) -> Result<()> {
        self.leading.validate()?;
        self.damping.validate()?;
        self.restoring.validate()?;
        if self.fractional.len() > MAX_FRACTIONAL {
            return Err(Error::invalid(
                "fractional",
                self.fractional.len() as f64,
                format!("at most {MAX_FRACTIONAL} terms"),
            ));
        }
        for (j, f) in self.fractional.iter().enumerate() {
            f.validate(j)?;
        }
        if self.walls.len() > MAX_WALLS {
            return Err(Error::invalid(
                "wall",
                self.walls.len() as f64,
                format!("at most {MAX_WALLS} walls"),
            ));
        }
        for (i, w) in self.walls.iter().enumerate() {
            w.validate(i)?;
        }
        if let [lower, upper] = self.walls.as_slice() {
            if lower.keep != Keep::Above {
                return Err(Error::Malformed {
                    field: "wall.0.keep".into(),
                    detail: "\"below\": with two walls the first is the lower one and keeps \
                             U above it (keep = \"above\")"
                        .into(),
                });
            }
            if upper.keep != Keep::Below {
                return Err(Error::Malformed {
                    field: "wall.1.keep".into(),
                    detail: "\"above\": with two walls the second is the upper one and keeps \
                             U below it (keep = \"below\")"
                        .into(),
                });
            }
            if upper.position <= lower.position {
                return Err(Error::invalid(
                    "wall.1.position",
                    upper.position,
                    format!("({}, 1e6] (above wall.0.position)", Exact(lower.position)),
                ));
            }
        }
        if let Some(f) = &self.forcing {
            f.validate()?;
        }
        self.noise.validate()?;
        self.start.validate()?;
        for (i, w) in self.walls.iter().enumerate() {
            if !w.allows(self.start.u0) {
                let side = match w.keep {
                    Keep::Above => format!("[{}, ∞)", Exact(w.position)),
                    Keep::Below => format!("(−∞, {}]", Exact(w.position)),
                };
                return Err(Error::invalid(
                    "start.u0",
                    self.start.u0,
                    format!(
                        "{side}: wall.{i} at {} keeps U {}",
                        Exact(w.position),
                        w.keep.name()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The paper family's parameters, when the model is one of Eq. (1) with the wall at 0 or
    /// none (no wall: r = 1 in the parameters, which then do not use it).
    pub fn paper_params(&self) -> Option<Params> {
        self.paper_family("the paper's parameters")
            .ok()
            .map(|f| f.params)
    }

    /// The model as one of the paper's family (what the paper's kernel steps and `--param`
    /// edits): h = μ0P(U), k = ω0²U, the wall at 0 keeping U ≥ 0 with a constant r or no
    /// wall, additive white or OU noise, no fractional term, no forcing. Any other term is
    /// refused by name with [`Error::NotApplicable`] for `method` (the General kernel's terms
    /// are [`Model::engine_terms`]'s): never dropped. Terms present with a zero coefficient are
    /// absent.
    pub fn paper_family(&self, method: &str) -> Result<PaperFamily> {
        self.validate()?;
        let refuse = |assumption: &str, reason: String| Error::NotApplicable {
            method: method.to_string(),
            assumption: assumption.to_string(),
            reason,
        };
        let not_yet = "outside the paper's family (its Eq. (1) with the wall at 0 or none)";
        if let Some(k) = self.damping.rayleigh.iter().position(|&d| d != 0.0) {
            return Err(refuse(
                "h = μ0·P(U) (no Rayleigh term)",
                format!(
                    "damping.rayleigh.{k} = {} is a Rayleigh term d·U̇^{}: {not_yet}",
                    Exact(self.damping.rayleigh[k]),
                    2 * (k + 1)
                ),
            ));
        }
        for (name, v, power) in [
            ("restoring.cubic", self.restoring.cubic, 3),
            ("restoring.quintic", self.restoring.quintic, 5),
        ] {
            if v != 0.0 {
                return Err(refuse(
                    "k(U) = ω0²U",
                    format!(
                        "{name} = {} is a restoring term in U^{power}: {not_yet}",
                        Exact(v)
                    ),
                ));
            }
        }
        if let Some(j) = self.fractional.iter().position(|f| f.coefficient != 0.0) {
            return Err(refuse(
                "no fractional term K·D^α U",
                format!(
                    "fractional.{j}.coefficient = {} is a term K·D^{}U: {not_yet}",
                    Exact(self.fractional[j].coefficient),
                    Exact(self.fractional[j].order)
                ),
            ));
        }
        let mut restitution = 1.0;
        let wall = match self.walls.as_slice() {
            [] => false,
            [w] => {
                if w.position != 0.0 {
                    return Err(refuse(
                        "a wall at U = 0 or none",
                        format!(
                            "wall.0.position = {} is a wall off 0: {not_yet}",
                            Exact(w.position)
                        ),
                    ));
                }
                if w.keep != Keep::Above {
                    return Err(refuse(
                        "a wall at U = 0 keeping U ≥ 0",
                        format!("wall.0.keep = \"below\": {not_yet}"),
                    ));
                }
                match w.restitution {
                    Restitution::Constant(r) => restitution = r,
                    Restitution::Speed(_) => {
                        return Err(refuse(
                            "a constant restitution coefficient",
                            format!("wall.0.restitution is speed-dependent: {not_yet}"),
                        ))
                    }
                }
                true
            }
            _ => {
                return Err(refuse(
                    "a wall at U = 0 or none",
                    format!("wall has two walls: {not_yet}"),
                ))
            }
        };
        if let Some(f) = self.forcing.filter(|f| f.amplitude != 0.0) {
            return Err(refuse(
                "no forcing",
                format!(
                    "forcing.amplitude = {} is a harmonic forcing F cos(Ωt + φ): {not_yet}",
                    Exact(f.amplitude)
                ),
            ));
        }
        if let Some(m) = self.noise.multiplicative.filter(|m| m.intensity != 0.0) {
            return Err(refuse(
                "additive noise only",
                format!(
                    "noise.multiplicative.intensity = {} is a multiplicative noise U·η_m: {not_yet}",
                    Exact(m.intensity)
                ),
            ));
        }
        let (noise_intensity, correlation_time) = self
            .noise
            .additive
            .map_or((0.0, 0.0), |a| (a.intensity, a.correlation_time));
        let params = Params {
            mu0: self.damping.mu0,
            omega0: self.restoring.omega0,
            lambda: self.leading.lambda,
            restitution,
            damping: Damping {
                coefficients: self.damping.coefficients.clone(),
            },
            noise_intensity,
            correlation_time,
        };
        params.validate()?;
        Ok(PaperFamily {
            params,
            wall,
            start: (self.start.u0, self.start.v0),
        })
    }

    /// The model as the engine steps it: the paper family's part ([`Model::paper_family`]) and
    /// the General kernel's terms (Duffing k3, k5; Rayleigh d_k; harmonic forcing; fractional
    /// terms K·D^αU; multiplicative noise U·η_m; walls other than the paper's: a wall off 0,
    /// keeping U below, two walls, a speed-dependent restitution), None when there are none
    /// (the paper's kernel, the paper's bits). Errors are the paper family's, for `method`.
    /// Terms present with a zero coefficient are absent.
    pub fn engine_terms(&self, method: &str) -> Result<(PaperFamily, Option<GeneralTerms>)> {
        self.validate()?;
        let mut rayleigh = self.damping.rayleigh.clone();
        while rayleigh.last() == Some(&0.0) {
            rayleigh.pop();
        }
        let multiplicative = self.noise.multiplicative.filter(|m| m.intensity != 0.0);
        let terms = GeneralTerms {
            cubic: self.restoring.cubic,
            quintic: self.restoring.quintic,
            rayleigh,
            forcing: self.forcing.filter(|f| f.amplitude != 0.0),
            walls: if paper_walls(&self.walls) {
                Vec::new()
            } else {
                self.walls.clone()
            },
            fractional: self
                .fractional
                .iter()
                .copied()
                .filter(|f| f.coefficient != 0.0)
                .collect(),
            multiplicative,
            correlation: if multiplicative.is_some() {
                self.noise.correlation
            } else {
                0.0
            },
        };
        let mut paper = self.clone();
        paper.restoring.cubic = 0.0;
        paper.restoring.quintic = 0.0;
        paper.damping.rayleigh.clear();
        paper.forcing = None;
        if !terms.walls.is_empty() {
            paper.walls.clear();
        }
        paper.fractional.clear();
        paper.noise.multiplicative = None;
        paper.noise.correlation = 0.0;
        let family = paper.paper_family(method)?;
        if terms.is_empty() {
            return Ok((family, None));
        }
        Ok((family, Some(terms)))
    }

    /// The damping polynomial P(U) of h = μ0·P(U) + ….
    pub fn polynomial(&self) -> Damping {
        Damping {
            coefficients: self.damping.coefficients.clone(),
        }
    }
}

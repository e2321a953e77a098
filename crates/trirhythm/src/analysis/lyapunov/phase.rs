//! The phase response Z(θ) of a stable deterministic cycle, measured by small impulses of the
//! forcing with the real stepper, and the phase-reduction prediction of the frozen-noise
//! exponent under weak Ornstein–Uhlenbeck noise (noise-induced synchronisation).
//!
//! # Equation
//! On a stable cycle of period T the phase θ ∈ [0, 2π) grows at Ω = 2π/T; to first order in the
//! forcing, dθ/dt = Ω + Z(θ)η, where Z(θ) is the **asymptotic phase shift in radians per unit
//! impulse of η** given at phase θ (at λ = 1 an impulse m of η is a velocity kick m). With
//! Z(θ) = Σ_k Z_k e^{ikθ} and η an OU process with ⟨η(t)η(s)⟩ = (D/τ)e^{−|t−s|/τ}, the
//! exponent of the phase equation with frozen noise is, to leading order in D,
//!
//!   λ_pred = −c·D,   c = 2 Σ_{k≥1} k²|Z_k|² / (1 + k²Ω²τ²).
//!
//! Derivation. The exponent of the one-dimensional phase equation is the time average of the
//! derivative of its right-hand side, λ = ⟨Z′(θ(t))η(t)⟩. With θ(t) = Ωt + φ₀ + ∫^t Z η ds,
//! expand Z′ to first order: Z′(θ(t)) = Z′(Ωt + φ₀) + Z″(Ωt + φ₀)∫_{−∞}^t Z(θ(s))η(s)ds. The
//! first term averages to 0 against η(t); the second gives
//! λ = ∫₀^∞ C(s)⟨Z″(θ)Z(θ − Ωs)⟩_θ ds, C(s) = (D/τ)e^{−s/τ}. The phase average is
//! −Σ_k k²|Z_k|²e^{ikΩs} (Z real: Z_{−k} = Z_k*), and ∫₀^∞ (D/τ)e^{−s/τ}e^{ikΩs}ds =
//! D/(1 − ikΩτ); the terms k and −k together give 2D/(1 + k²Ω²τ²), hence c above. For τ → 0
//! (white noise, ⟨η(t)η(s)⟩ = 2Dδ(t − s), the OU normalisation's limit) c = ⟨Z′²⟩_θ: Teramae and
//! Tanaka's λ = −D⟨Z′²⟩. The amplitude's relaxation is not in the phase equation: the formula is
//! the leading order in D at fixed relaxation rate.
//!
//! With the wall, Z **jumps** at the impact: an impulse just before it changes U̇₋ by m, and
//! the law U̇₊ = −rU̇₋ turns that into −rm just after, so Z(2π⁻) ≈ −rZ(0⁺) (θ = 0 at the
//! impact). A jump J = Z(0⁺) − Z(2π⁻) gives Z_k ≈ J/(2πik) for large k, so k²|Z_k|² tends to
//! J²/4π²: for white noise the series **diverges** (the result then has no coefficient, with the
//! reason), for τ > 0 its terms fall like J²/(4π²k²Ω²τ²).
//!
//! # Method
//! 1. The start's noise-free path is followed until it settles on a cycle
//!    ([`super::AttractorSpec`], module `attractor`); a start that ends at rest or unsettled is
//!    refused ([`Error::Undefined`]).
//! 2. The **section** that fixes θ = 0 is the impact with the wall (its time t* as the stepper
//!    locates it), or without impacts the upward crossing of U = 0 (on the step's cubic Hermite
//!    interpolant). The period T is the mean spacing of `periods` sections of the reference.
//! 3. Over one period, `phases` grid nodes t_n are picked nearest to θ = 2π(j + ½)/`phases`;
//!    a node whose next step holds an impact is replaced by the next node. At each, four copies
//!    of the path get an impulse of η of mass ±m and ±2m (`Stepper::pulse`: a hat of g on the
//!    next step, mass γm, centre t_n + Δt/3; the phase of the sample is that of the centre).
//!    m = `kick`·A·Ω/2 (A·Ω/2 = Aπ/T is about the velocity amplitude of the cycle).
//!    **How the impulse enters the Volterra form**: V = V₀ + Σ jumps + J^λ g, and the hat is
//!    part of g, so V gains γm·J^λ(hat) → γm(t − t_n)^{λ−1}/Γ(λ): the fractional response to a
//!    Dirac impulse of η, exactly what the phase equation's Z multiplies; at λ = 1 a velocity
//!    kick γm. The memory, the impacts (their saltation) and the impact memory act on the
//!    copies as on any path.
//! 4. Each copy is followed for `periods` sections after the impulse. With t±_i the i-th
//!    section time of the copies kicked ±m, the central difference Δ_i = (t⁺_i − t⁻_i)/2 tends
//!    to the asymptotic time shift as the amplitude's disturbance relaxes. It is extrapolated
//!    by Aitken's Δ² over the sections i = N/3, 2N/3, N (N = `periods`; applied when the
//!    ratio of the two differences lies in [0, 1), else Δ_N is taken), and
//!    Z = −ΩΔ_∞/m. The same with ±2m gives Z₂; the **linearity** is max|Z − Z₂|/max|Z|; the
//!    **extrapolation** max|Δ_∞ − Δ_N|·Ω/m/max|Z| says how far the copies were from settled.
//! 5. The **coefficient** c from the samples: the jump J from the three samples on each side of
//!    θ = 0 (quadratic extrapolation to 0⁺ and 2π⁻; J = 0 without impacts), the sawtooth
//!    s(θ) = J(½ − θ/2π) (whose coefficients are exactly J/(2πik)) subtracted, the continuous
//!    rest r fitted by least squares with the harmonics k ≤ K = min(`phases`/4,
//!    [`super::MAX_HARMONICS`]; module `spectrum`) (the samples' phases are the grid's, not
//!    uniform: a quadrature on them errs by O((kΔθ)²), which grows with k, the fit does not),
//!    and Z_k = r_k + J/(2πik);
//!    above K, r_k is dropped (r is continuous with a kink at the impact: r_k = O(k⁻²), so its
//!    share of c above K is O(K⁻³/a²)) and the sawtooth's tail is summed in closed form,
//!    Σ_{k>K} 1/(1 + k²a²) = (π/a·coth(π/a) − 1)/2 − Σ_{k≤K}, a = Ωτ. The **uncertainty** is
//!    |c − c_half|, c_half the same from every other sample with K for half the phases: it
//!    holds the sampling, the truncation and the jump's estimate together.
//!    `phases` must not exceed T/Δt (one grid node per phase).
//! 6. **No number where there is none**: the coefficient is None, with the reason, for white
//!    noise with impacts (the divergent series), where the linearity exceeds
//!    [`LINEARITY_LIMIT`] and where the extrapolation exceeds [`EXTRAPOLATION_LIMIT`]. Both
//!    catch a step map that is not smooth along the cycle: on Fig. 17(a)'s μ0 = 0.05 outer cycle
//!    at Δt = 0.01 the phase difference of the copies drifts toward a value locked to the grid
//!    (followed 12 sections: linearity 8·10⁻⁴ but extrapolation 1.5; 60 sections: linearity
//!    0.52), at Δt = 0.0025 linearity 5·10⁻⁶ and no extrapolation. Measured elsewhere with the
//!    restarting impact memory: extrapolation ≤ 5·10⁻⁶ (the copies settle within a few
//!    periods); with the continuous memory 4·10⁻³–10⁻², the memory's slow tail.
//!
//! # Reference
//! Teramae & Tanaka, PRL 93, 204103 (2004) (white noise, λ = −D⟨Z′²⟩); Goldobin & Pikovsky,
//! PRE 71, 045201 (2005); Goldobin, Teramae, Nakao & Ermentrout, PRL 105, 154101 (2010)
//! (general noise: the spectral form above); Winfree, *The Geometry of Biological Time* (2001)
//! (phase response by kicks).
//!
//! # Tests
//! Unit tests below: a van der Pol cycle at λ = 1 without the wall (ε = μ0 = 0.01, P = 1 − U²)
//! has Z(θ) = −sin θ/(Aω), A = 2, ω = 1, to 0.01 (measured: within 2.5·10⁻³, the same at
//! Δt = 0.0025 and 2.5·10⁻⁴ at ε = 0.001 — the van der Pol response's own O(ε) term, not the
//! method's; c = 0.10001 against 1/(2A²(1 + τ²)) = 0.1 at τ = 0.5); on Fig. 17(a)'s μ0 = 0.01 outer cycle Z(2π⁻) ≈ −rZ(0⁺)
//! (0.0570 against 0.0542) and τ = 0 gives no coefficient; a start that ends at rest is
//! refused. Module `spectrum`: c of a sine and of a sawtooth. `tests/phase.rs`: c converged in
//! Δt and in the phases; the drifting phase of the stiff step refused; (extended suite) λ̂/D of
//! the simulated exponent against c on Fig. 17(a)'s outer cycles.

use super::attractor::{hermite_crossing, noise_free, settle};
use super::spectrum::{coefficient, ends, harmonics};
use super::{Attractor, AttractorSpec};
use crate::engine::{PredictorCorrector, Problem, Stepper, System};
use crate::error::{Error, Result};
use crate::monitor::Monitor;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::sync::atomic::{AtomicU64, Ordering};

/// Most phases of a [`PhaseSpec`].
pub const MAX_PHASES: usize = 4096;
/// Largest [`PhaseResponse::linearity`] with which a coefficient is given: beyond it the
/// asymptotic phase shift is not linear in the kick (the step map locks the phase to the time
/// grid), and the sampled Z is not a phase response.
pub const LINEARITY_LIMIT: f64 = 1e-2;
/// Largest [`PhaseResponse::extrapolation`] with which a coefficient is given: beyond it the
/// copies were far from their asymptotic phase when last seen.
pub const EXTRAPOLATION_LIMIT: f64 = 0.05;
/// Most periods a kicked copy is followed.
pub const MAX_FOLLOW_PERIODS: usize = 100_000;

/// How the phase response is measured (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhaseSpec {
    /// Phases sampled over one period, 8 to [`MAX_PHASES`] (even).
    pub phases: usize,
    /// Impulse m relative to the cycle's velocity scale A·Ω/2, in [1e-8, 1e-2].
    pub kick: f64,
    /// Sections each kicked copy is followed, 6 to [`MAX_FOLLOW_PERIODS`].
    pub periods: usize,
    /// How the start's path reaches its cycle.
    pub attractor: AttractorSpec,
}

impl Default for PhaseSpec {
    fn default() -> Self {
        PhaseSpec {
            phases: 128,
            kick: 1e-4,
            periods: 60,
            attractor: AttractorSpec::default(),
        }
    }
}

impl PhaseSpec {
    /// Check the spec: `phases` even in 8 to [`MAX_PHASES`], `kick` in [1e-8, 1e-2], `periods` 6
    /// to [`MAX_FOLLOW_PERIODS`], the attractor spec ([`AttractorSpec::validate`]).
    pub fn validate(&self) -> Result<()> {
        if !(8..=MAX_PHASES).contains(&self.phases) || self.phases % 2 != 0 {
            return Err(Error::invalid(
                "phases",
                self.phases as f64,
                format!("an even number from 8 to {MAX_PHASES}"),
            ));
        }
        if !(1e-8..=1e-2).contains(&self.kick) {
            return Err(Error::invalid("kick", self.kick, "[1e-8, 1e-2]"));
        }
        if !(6..=MAX_FOLLOW_PERIODS).contains(&self.periods) {
            return Err(Error::invalid(
                "periods",
                self.periods as f64,
                format!("6 to {MAX_FOLLOW_PERIODS}"),
            ));
        }
        self.attractor.validate()
    }
}

/// Where θ = 0 is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Section {
    /// The impact with the wall.
    Impact,
    /// The upward crossing of U = 0 (no impacts).
    UpwardCrossing,
}

/// Z at one phase.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PhaseSample {
    /// Phase θ ∈ (0, 2π) of the impulse's centre.
    pub theta: f64,
    /// Z(θ), radians per unit impulse of η, from the impulses ±m.
    pub z: f64,
    /// The same from ±2m (linearity).
    pub z_double: f64,
    /// Aitken's correction of the ±m time shift, in the units of Z (how far from settled the
    /// copies were after `periods` sections).
    pub extrapolation: f64,
}

/// The phase response of a cycle and the phase-reduction prediction of its exponent.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PhaseResponse {
    /// U(0) of the start.
    pub u0: f64,
    /// The cycle the start reached.
    pub cycle: Attractor,
    /// Its turning amplitude.
    pub amplitude: f64,
    /// Its period T (mean spacing of `periods` sections).
    pub period: f64,
    /// Ω = 2π/T.
    pub omega: f64,
    /// Where θ = 0 is.
    pub section: Section,
    /// The impulse m of η.
    pub impulse: f64,
    /// Z at the sampled phases, ascending in θ.
    pub samples: Vec<PhaseSample>,
    /// Z(0⁺) extrapolated from the first three samples.
    pub z_after: f64,
    /// Z(2π⁻) extrapolated from the last three samples.
    pub z_before: f64,
    /// The jump J = Z(0⁺) − Z(2π⁻) at the impact (0 without impacts: Z is continuous).
    pub jump: f64,
    /// The correlation time τ of the noise (the problem's).
    pub correlation_time: f64,
    /// c of λ_pred = −c·D (None: undefined, see `undefined`).
    #[serde(default)]
    pub coefficient: Option<f64>,
    /// |c − c_half| (NaN when undefined).
    #[serde(with = "crate::non_finite")]
    pub uncertainty: f64,
    /// Harmonics K summed from the samples.
    pub harmonics: usize,
    /// The part of c from the jump's closed-form tail above K (NaN when undefined).
    #[serde(with = "crate::non_finite")]
    pub tail: f64,
    /// max|Z − Z₂|/max|Z|.
    pub linearity: f64,
    /// max|extrapolation|/max|Z|.
    pub extrapolation: f64,
    /// Why there is no coefficient.
    #[serde(default)]
    pub undefined: Option<String>,
}

impl PhaseResponse {
    /// λ_pred = −c·D at noise intensity `d` (None where c is undefined).
    pub fn predicted_exponent(&self, d: f64) -> Option<f64> {
        self.coefficient.map(|c| -c * d)
    }
}

/// The section event of the step just taken by `path` from `prev` = (t, U, U̇), if any.
fn section_event(prev: (f64, f64, f64), path: &Stepper, wall: bool) -> Option<f64> {
    if wall {
        return path.events().impact.map(|i| i.time);
    }
    let (t0, u0, v0) = prev;
    if u0 < 0.0 && path.u() >= 0.0 {
        let h = path.time() - t0;
        return Some(t0 + h * hermite_crossing(h, (u0, v0), (path.u(), path.v())));
    }
    None
}

/// Step `path` until it has met `n` section events (at most `max_steps` steps): their times.
fn sections(path: &mut Stepper, n: usize, wall: bool, max_steps: u64) -> Result<Vec<f64>> {
    let mut out = Vec::with_capacity(n);
    for _ in 0..max_steps {
        let prev = (path.time(), path.u(), path.v());
        path.step()?;
        if let Some(t) = section_event(prev, path, wall) {
            out.push(t);
            if out.len() == n {
                return Ok(out);
            }
        }
    }
    Err(Error::Undefined {
        what: "phase response",
        why: format!(
            "a path met {} of {n} sections within {max_steps} steps (the cycle was left)",
            out.len()
        ),
    })
}

/// The phase response of the cycle the noise-free path of `problem` from (u0, 0) reaches, and
/// c of the prediction λ = −c·D for the problem's τ (module docs). `monitor` hears the phases
/// done and may stop the run.
pub fn phase_response(
    problem: &Problem,
    method: &PredictorCorrector,
    u0: f64,
    spec: &PhaseSpec,
    monitor: &dyn Monitor,
) -> Result<PhaseResponse> {
    spec.validate()?;
    method.validate()?;
    if problem.system() == System::Zhuravlev {
        return Err(Error::Undefined {
            what: "phase response",
            why: "Eq. (9)'s Z crosses the wall; use Eq. (5) with the wall instead".into(),
        });
    }
    let free = noise_free(problem, u0)?;
    let omega1 = free.oscillator().equivalents().omega1;
    // the memory certified over the settling, the kick window and the copies' runs (periods
    // of up to four times 2π/ω1: the stiff cycles' are longer than π/ω1)
    let long_period = 4.0 * 2.0 * PI / omega1;
    let horizon = spec.attractor.t_max + (2 * spec.periods + 4) as f64 * long_period;
    let max_steps = ((spec.periods + 2) as f64 * long_period / method.dt).ceil() as u64;
    let mut path = Stepper::new(&free, method, (0, 0), horizon)?;
    let (cycle, _, _, _) = settle(&free, &mut path, &spec.attractor)?;
    let Attractor::Cycle { amplitude, .. } = cycle else {
        return Err(Error::Undefined {
            what: "phase response",
            why: format!(
                "the noise-free path from U(0) = {u0} reaches no cycle ({})",
                cycle.label()
            ),
        });
    };
    monitor.check()?;
    let wall = free.wall();
    // θ = 0 at the next section; the period from `periods` sections of a copy
    let first = sections(&mut path, 1, wall, max_steps)?[0];
    let later = sections(
        &mut path.clone(),
        spec.periods,
        wall,
        max_steps * spec.periods as u64,
    )?;
    let period = (later[spec.periods - 1] - first) / spec.periods as f64;
    let omega = 2.0 * PI / period;
    let section = if wall && path.impacts() > 0 {
        Section::Impact
    } else {
        Section::UpwardCrossing
    };
    // the kick nodes: nearest to θ_j = 2π(j + ½)/M, a node whose next step impacts replaced by
    // the next
    let h = method.dt;
    if spec.phases as f64 * h > period {
        return Err(Error::invalid(
            "phases",
            spec.phases as f64,
            format!(
                "at most T/Δt = {} (one kick node per phase; the period is {period:.6})",
                (period / h).floor()
            ),
        ));
    }
    let targets: Vec<f64> = (0..spec.phases)
        .map(|j| first + (j as f64 + 0.5) / spec.phases as f64 * period)
        .collect();
    let mut nodes: Vec<(f64, Stepper)> = Vec::with_capacity(spec.phases);
    let mut next = 0;
    while next < targets.len() {
        let centre = path.time() + h / 3.0;
        let due = centre + 0.5 * h >= targets[next];
        let before = path.clone();
        path.step()?;
        if due && path.events().impact.is_none() {
            nodes.push((2.0 * PI * (centre - first) / period, before));
            next += 1;
            // targets closer than a step take the same node
            while next < targets.len() && centre + 0.5 * h >= targets[next] {
                nodes.push((
                    2.0 * PI * (centre - first) / period,
                    nodes.last().unwrap().1.clone(),
                ));
                next += 1;
            }
        }
        if path.time() - first > 2.0 * period {
            return Err(Error::Undefined {
                what: "phase response",
                why: "the kick nodes were not found within two periods".into(),
            });
        }
    }
    let m = spec.kick * amplitude * omega / 2.0;
    let done = AtomicU64::new(0);
    let total = nodes.len() as u64;
    let n = spec.periods;
    let shifts: Vec<(f64, f64, f64)> = crate::profile::parallel(|stage| {
        nodes
            .par_iter()
            .map(|(_, node)| {
                stage.task(|| -> Result<(f64, f64, f64)> {
                    monitor.check()?;
                    let run = |mass: f64| -> Result<Vec<f64>> {
                        let mut copy = node.clone();
                        if !copy.pulse(mass) {
                            return Err(Error::Undefined {
                                what: "phase response",
                                why: "the cycle sticks at the wall at a kick node".into(),
                            });
                        }
                        sections(&mut copy, n, wall, max_steps * n as u64)
                    };
                    let (p1, m1, p2, m2) = (run(m)?, run(-m)?, run(2.0 * m)?, run(-2.0 * m)?);
                    let half = |a: &[f64], b: &[f64], i: usize| 0.5 * (a[i] - b[i]);
                    let (d1, last) =
                        aitken([n / 3 - 1, 2 * n / 3 - 1, n - 1].map(|i| half(&p1, &m1, i)));
                    let (d2, _) =
                        aitken([n / 3 - 1, 2 * n / 3 - 1, n - 1].map(|i| half(&p2, &m2, i)));
                    let k = done.fetch_add(1, Ordering::Relaxed) + 1;
                    monitor.progress(k, total);
                    let z = |d: f64, mass: f64| -omega * d / mass;
                    Ok((z(d1, m), z(d2, 2.0 * m), z(d1 - last, m)))
                })
            })
            .collect::<Result<_>>()
    })?;
    let samples: Vec<PhaseSample> = nodes
        .iter()
        .zip(shifts)
        .map(|((theta, _), (z, z_double, extrapolation))| PhaseSample {
            theta: *theta,
            z,
            z_double,
            extrapolation,
        })
        .collect();
    let zmax = samples.iter().map(|s| s.z.abs()).fold(0.0, f64::max);
    let rel = |f: &dyn Fn(&PhaseSample) -> f64| {
        samples.iter().map(|s| f(s).abs()).fold(0.0, f64::max) / zmax
    };
    let linearity = rel(&|s| s.z - s.z_double);
    let extrapolation = rel(&|s| s.extrapolation);
    let tau = free.params().correlation_time;
    let thetas: Vec<f64> = samples.iter().map(|s| s.theta).collect();
    let zs: Vec<f64> = samples.iter().map(|s| s.z).collect();
    let (z_after, z_before) = ends(&thetas, &zs);
    // without impacts Z is continuous
    let jump = if section == Section::Impact {
        z_after - z_before
    } else {
        0.0
    };
    let mut out = PhaseResponse {
        u0,
        cycle,
        amplitude,
        period,
        omega,
        section,
        impulse: m,
        samples,
        z_after,
        z_before,
        jump,
        correlation_time: tau,
        coefficient: None,
        uncertainty: f64::NAN,
        harmonics: harmonics(spec.phases),
        tail: f64::NAN,
        linearity,
        extrapolation,
        undefined: None,
    };
    // NaN (no finite Z) counts as not linear
    if linearity.partial_cmp(&LINEARITY_LIMIT) != Some(std::cmp::Ordering::Less) {
        out.undefined = Some(format!(
            "the phase shift is not linear in the kick (max|Z(m) − Z(2m)|/max|Z| = {linearity:.3}, \
             above {LINEARITY_LIMIT}): the step map is not smooth along this cycle at dt = {h} \
             (try a smaller dt)"
        ));
        return Ok(out);
    }
    if extrapolation.partial_cmp(&EXTRAPOLATION_LIMIT) != Some(std::cmp::Ordering::Less) {
        out.undefined = Some(format!(
            "the kicked copies had not settled after {} sections (Aitken's correction {extrapolation:.3} \
             of max|Z|, above {EXTRAPOLATION_LIMIT}): follow more periods, or the step map drifts \
             the phase at dt = {h}",
            spec.periods
        ));
        return Ok(out);
    }
    if tau == 0.0 && section == Section::Impact {
        out.undefined =
            Some("white noise (τ = 0): Z jumps at the impact, so Σ k²|Z_k|² diverges".to_string());
        return Ok(out);
    }
    let a = omega * tau;
    let (c, tail) = coefficient(&thetas, &zs, jump, harmonics(spec.phases), a);
    let every_other = |v: &[f64]| v.iter().step_by(2).copied().collect::<Vec<_>>();
    let (th2, z2) = (every_other(&thetas), every_other(&zs));
    let (a2, b2) = ends(&th2, &z2);
    let jump2 = if jump == 0.0 { 0.0 } else { a2 - b2 };
    let (c_half, _) = coefficient(&th2, &z2, jump2, harmonics(spec.phases / 2), a);
    out.coefficient = Some(c);
    out.uncertainty = (c - c_half).abs();
    out.tail = tail;
    Ok(out)
}

/// Aitken's Δ² over three values of a sequence (module docs): the extrapolated limit and the
/// last value.
fn aitken(x: [f64; 3]) -> (f64, f64) {
    let (d1, d2) = (x[1] - x[0], x[2] - x[1]);
    let q = d2 / d1;
    if d1 != 0.0 && (0.0..1.0).contains(&q) {
        (x[2] + d2 * q / (1.0 - q), x[2])
    } else {
        (x[2], x[2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::Barrier;
    use crate::model::preset;
    use crate::monitor::Silent;

    #[test]
    fn the_spec_is_checked() {
        for s in [
            PhaseSpec {
                phases: 7,
                ..Default::default()
            },
            PhaseSpec {
                phases: 9,
                ..Default::default()
            },
            PhaseSpec {
                kick: 0.0,
                ..Default::default()
            },
            PhaseSpec {
                periods: 3,
                ..Default::default()
            },
        ] {
            assert!(
                matches!(s.validate(), Err(Error::InvalidParameter { .. })),
                "{s:?}"
            );
        }
    }

    /// λ = 1 without the wall and P(U) = 1 − U²: Ü − μ0(1 − U²)U̇ + U = η, a van der Pol
    /// oscillator with ε = μ0 = 0.01 (Fig. 2(i)'s other parameters), cycle U ≈ A sin θ with
    /// A = 2, ω = 1; a velocity kick m moves θ by −m sin θ/(Aω) (to O(ε)).
    #[test]
    fn a_weakly_nonlinear_cycle_has_the_harmonic_phase_response() {
        let mut params = preset("fig2i").unwrap().params.with("tau", 0.5).unwrap();
        for key in ["alpha0", "beta0", "gamma0", "delta0"] {
            params = params.with(key, 0.0).unwrap();
        }
        let problem = Problem::from_params(&params)
            .unwrap()
            .with_barrier(Barrier::Off)
            .unwrap();
        let method = PredictorCorrector::default();
        let a = 2.0;
        let spec = PhaseSpec {
            phases: 16,
            periods: 9,
            ..Default::default()
        };
        let r = phase_response(&problem, &method, a, &spec, &Silent).unwrap();
        assert_eq!(r.section, Section::UpwardCrossing);
        assert!((r.amplitude - a).abs() < 0.01 * a, "{}", r.amplitude);
        assert!((r.omega - 1.0).abs() < 1e-3, "{}", r.omega);
        for s in &r.samples {
            let expected = -s.theta.sin() / (a * 1.0);
            assert!(
                (s.z - expected).abs() < 0.02 / a,
                "{s:?} against {expected}"
            );
        }
        assert!(r.linearity < 1e-3, "{}", r.linearity);
        let c = r.coefficient.unwrap();
        let expected = 1.0 / (2.0 * a * a * (1.0 + 0.25));
        assert!((c - expected).abs() < 0.03 * expected, "{c} {expected}");
    }

    /// Fig. 17(a)'s μ0 = 0.01 outer cycle: Z jumps at the impact by ≈ (1 + r)Z(0⁺); with white
    /// noise there is no coefficient, with τ = 0.06 there is one.
    #[test]
    fn the_jump_at_the_impact_and_white_noise() {
        let params = preset("fig17a").unwrap().params.with("mu0", 0.01).unwrap();
        let method = PredictorCorrector {
            impact_memory: crate::engine::ImpactMemory::Restart,
            ..Default::default()
        };
        let spec = PhaseSpec {
            phases: 32,
            periods: 9,
            ..Default::default()
        };
        let outer = 12.915346636317683;
        let problem = Problem::from_params(&params).unwrap();
        let r = phase_response(&problem, &method, outer, &spec, &Silent).unwrap();
        assert_eq!(r.section, Section::Impact);
        // Z(2π⁻) ≈ −r·Z(0⁺), r = 0.998 (measured 0.057 against 0.054)
        assert!(r.z_after < 0.0 && (r.z_before + 0.998 * r.z_after).abs() < 0.1 * r.z_before);
        let c = r.coefficient.unwrap();
        assert!(r.uncertainty < 0.05 * c && r.tail > 0.0, "{r:?}");
        let white = problem
            .with_params(&params.with("tau", 0.0).unwrap())
            .unwrap();
        let r = phase_response(&white, &method, outer, &spec, &Silent).unwrap();
        assert!(r.coefficient.is_none() && r.undefined.is_some());
        assert!(r.predicted_exponent(0.1).is_none());
    }

    #[test]
    fn a_start_at_rest_has_no_phase_response() {
        let params = preset("fig18b").unwrap().params.with("r", 0.9).unwrap();
        let problem = Problem::from_params(&params).unwrap();
        let method = PredictorCorrector::default();
        let r = phase_response(&problem, &method, 1.0, &PhaseSpec::default(), &Silent);
        assert!(matches!(r, Err(Error::Undefined { .. })), "{r:?}");
    }
}

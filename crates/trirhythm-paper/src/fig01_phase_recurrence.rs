//! Fig. 1: phase portraits (U, U̇) of the fractional system (Eq. 1, predictor–corrector) and of
//! its harmonic-balance equivalent (Eq. 5), side by side, with their recurrence plots
//! (Eq. 6–7, ε = 0.1, Euclidean norm) and the recurrence rate and determinism of each.
//!
//! Both start at the turning point U = A02 (A01 is unstable at the paper's parameters), U̇ = 0 of the smallest stable cycle of the averaged
//! theory (Eq. 18), as the paper's text says ("around the attractor's minimum amplitude").
//!
//! Method: [`simulate`] with the predictor–corrector for both systems, the last 15 time units
//! kept; the recurrence samples are strided so that consecutive samples stay within ε/2 in
//! the phase plane; [`RecurrenceMatrix`] gives RR and DET (l_min = 2). Two more runs (no
//! barrier; the restart impact-memory convention) are reported in the notes. Checked by
//! `tests/figures.rs`; the recurrence quantities by the library's recurrence tests.

use crate::notes::num;
use crate::notes::{caption, panel_line, table_notes, Caption};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
use trirhythm::analysis::{RecurrenceMatrix, RecurrenceThreshold};
use trirhythm::engine::{
    simulate, Barrier, ImpactMemory, Options, PredictorCorrector, Problem, System, Trajectory,
};
use trirhythm::model::preset;
use trirhythm::theory::averaging::Theory;
use trirhythm::{Error, Result};

/// Recurrence threshold ε (Eq. 7).
pub const EPSILON: f64 = 0.1;

/// One system's path: the phase portrait and the recurrence plot's samples.
#[derive(Serialize, Deserialize)]
pub struct Panel {
    /// Which system.
    pub title: String,
    /// The phase portrait at every step of the window.
    pub phase: Vec<(f64, f64)>,
    /// The recurrence plot's samples.
    /// Times of the samples.
    pub t: Vec<f64>,
    /// U at the samples.
    pub u: Vec<f64>,
    /// U̇ at the samples.
    pub v: Vec<f64>,
    /// Recurrence rate and determinism of the recurrence matrix of (u, v) at ε (ratios:
    /// carried through JSON whatever their value).
    #[serde(with = "trirhythm::non_finite")]
    /// Recurrence rate.
    pub rr: f64,
    #[serde(with = "trirhythm::non_finite")]
    /// Determinism.
    pub det: f64,
    /// Mean amplitude √(U² + U̇²/ω1²) over the last 5 periods.
    pub amplitude: f64,
}

/// Fig. 1's data: the two paths, sampled for the recurrence plots (the recurrence matrices
/// follow from the samples and ε; the renderer rebuilds them).
#[derive(Serialize, Deserialize)]
pub struct Fig01 {
    /// What the figure shows, shared parameters, variant, choices.
    pub caption: Caption,
    /// Notes of the data table: parameters per panel, methods, verdicts.
    pub notes: Vec<String>,
    /// Fractional (Eq. 1) and equivalent (Eq. 5).
    pub panels: Vec<Panel>,
    /// Start of the window shown.
    pub start: f64,
    /// Recurrence threshold ε.
    pub epsilon: f64,
}

impl Figure for Fig01 {
    const NUMBER: u32 = 1;
    const TITLE: &'static str = "phase portraits and recurrence plots, Eq. (1) vs Eq. (5)";

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig01> {
        compute(options, monitor)
    }

    fn validate(&self) -> crate::validate::Valid {
        use crate::validate::{finite, fraction, len, points};
        for (i, p) in self.panels.iter().enumerate() {
            let f = format!("panels[{i}]");
            finite(&format!("{f}.t"), &p.t)?;
            len(&format!("{f}.u"), p.u.len(), p.t.len(), "one per time")?;
            len(&format!("{f}.v"), p.v.len(), p.t.len(), "one per time")?;
            finite(&format!("{f}.u"), &p.u)?;
            finite(&format!("{f}.v"), &p.v)?;
            points(&format!("{f}.phase"), &p.phase)?;
            fraction(&format!("{f}.rr"), p.rr)?;
            fraction(&format!("{f}.det"), p.det)?;
            finite(&format!("{f}.amplitude"), &[p.amplitude])?;
        }
        Ok(())
    }

    fn tables(&self) -> Vec<Table> {
        let mut csv = Table::new(&self.notes, &["system", "t", "U", "V"]);
        for (panel, name) in self.panels.iter().zip(["fractional", "equivalent"]) {
            for i in 0..panel.t.len() {
                csv.row([
                    name.to_string(),
                    num(panel.t[i]),
                    num(panel.u[i]),
                    num(panel.v[i]),
                ]);
            }
        }
        vec![csv]
    }
}

/// One system's panel from its path: the phase portrait from `start` on, the recurrence
/// samples strided so that consecutive samples stay within ε/2 in the phase plane, RR and DET;
/// with the sampling interval and the largest phase-plane step between samples.
fn panel(title: &str, tr: &Trajectory, start: f64, dt: f64) -> Result<(Panel, (f64, f64))> {
    let first = tr.t.iter().position(|&t| t >= start).unwrap_or(0);
    let phase: Vec<(f64, f64)> = tr.u[first..]
        .iter()
        .copied()
        .zip(tr.v[first..].iter().copied())
        .collect();
    // impacts reverse U̇ in one step: the jump is not a sampling gap
    let flights: Vec<f64> = tr.u[first..]
        .windows(2)
        .zip(tr.v[first..].windows(2))
        .filter(|(_, v)| v[0] * v[1] > 0.0 || v[0].abs() < 1.0)
        .map(|(a, b)| (a[1] - a[0]).hypot(b[1] - b[0]))
        .collect();
    let step = flights.iter().copied().fold(0.0, f64::max);
    let stride = ((0.5 * EPSILON / step).floor() as usize).max(1);
    let pick = |x: &[f64]| -> Vec<f64> { x[first..].iter().step_by(stride).copied().collect() };
    let (t, u, v) = (pick(&tr.t), pick(&tr.u), pick(&tr.v));
    let recurrence = RecurrenceMatrix::new(&u, &v, RecurrenceThreshold(EPSILON))?;
    let (rr, det) = (recurrence.recurrence_rate(), recurrence.determinism(2));
    let panel = Panel {
        title: title.to_string(),
        phase,
        t,
        u,
        v,
        rr,
        det,
        amplitude: tr.final_amplitude,
    };
    // consecutive samples are at most `stride` flight steps apart
    Ok((panel, (stride as f64 * dt, step * stride as f64)))
}

fn compute(ctx: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig01> {
    let p = preset("fig1")?.params;
    let th = Theory::new(&p, ctx.variant)?;
    let Some(a02) = th
        .limit_cycles()
        .iter()
        .find(|c| c.stable)
        .map(|c| c.amplitude)
    else {
        return Err(Error::Undefined {
            what: "figure 1's start A02",
            why: "the averaged theory has no stable cycle for these parameters".into(),
        });
    };
    let dt = if ctx.quick { 0.01 } else { 0.005 };
    let t_end = if ctx.quick { 200.0 } else { 1000.0 };
    // The recurrence plot covers the last `window` time units (about four periods). Its
    // samples must be closer than ε in the phase plane, or a return to the same point is
    // missed whenever the period is not a multiple of the sampling interval: the stride is
    // the largest that keeps consecutive samples within ε/2.
    let window = 15.0;
    let osc = Problem::from_params(&p)?.with_start(a02, 0.0)?;
    let method = PredictorCorrector {
        dt,
        ..Default::default()
    };
    let mut panels = Vec::new();
    let mut sampling = Vec::new();
    for (title, system) in [
        (
            "fractional system, Eq. (1), continuous impact memory",
            System::Fractional,
        ),
        ("integer-order equivalent, Eq. (5)", System::Equivalent),
    ] {
        crate::step(monitor, panels.len(), 4)?;
        let o = Options {
            t_end,
            ..Default::default()
        };
        let path = simulate(&osc.clone().with_system(system)?, &method, &o)?;
        let (panel, sampled) = panel(title, &path, t_end - window, dt)?;
        panels.push(panel);
        sampling.push(sampled);
    }
    let amplitude_with = |barrier, impact_memory| -> Result<f64> {
        let method = PredictorCorrector {
            dt,
            impact_memory,
            ..Default::default()
        };
        let o = Options {
            t_end,
            record_every: usize::MAX,
            ..Default::default()
        };
        Ok(simulate(&osc.clone().with_barrier(barrier)?, &method, &o)?.final_amplitude)
    };
    crate::step(monitor, 2, 4)?;
    let free_amplitude = amplitude_with(Barrier::Off, ImpactMemory::Continuous)?;
    crate::step(monitor, 3, 4)?;
    let restart_amplitude = amplitude_with(Barrier::On, ImpactMemory::Restart)?;
    let (notes, heading_lines) = texts(
        ctx,
        (a02, dt, t_end, window),
        &panels,
        &sampling,
        (free_amplitude, restart_amplitude),
    );
    let mut header = table_notes(
        1,
        "phase portraits and recurrence plots, Eq. (1) vs Eq. (5)",
        ctx,
        &notes,
    );
    header.push(panel_line("all", &p));
    header.push(format!(
        "fractional without the barrier (same start, T = {t_end}): mean amplitude = {:.4}",
        free_amplitude
    ));
    Ok(Fig01 {
        caption: caption(
                1,
                "phase portraits and recurrence plots, fractional system (Eq. 1) vs its integer-order equivalent (Eq. 5)",
                ctx,
                &p,
                &[],
                heading_lines,
            ),
        notes: header,
        panels,
        start: t_end - window,
        epsilon: EPSILON,
    })
}

/// The table's notes and the caption's lines: the start, the method, the sampling, RR, DET
/// and the amplitudes of both systems, the impact-memory conventions compared.
fn texts(
    ctx: &FigureOptions,
    (a02, dt, t_end, window): (f64, f64, f64, f64),
    panels: &[Panel],
    sampling: &[(f64, f64)],
    (free_amplitude, restart_amplitude): (f64, f64),
) -> (Vec<String>, Vec<String>) {
    // the start's name: the roots of f at r = 1 by increasing amplitude (A_01 is the smallest
    // root, stable or not; at the paper's parameters an unstable A_01 lies below it)
    let name = preset("fig1")
        .ok()
        .and_then(|pre| Theory::new(&pre.params, ctx.variant).ok())
        .and_then(|th| th.limit_cycles().iter().position(|c| c.stable))
        .map_or("A_0?".to_string(), |k| format!("A_0{}", k + 1));
    let sampling_text = |k: usize| {
        format!(
            "sampled every {} time units, phase-plane step ≤ {:.3} (ε/2 = {})",
            sampling[k].0,
            sampling[k].1,
            EPSILON / 2.0
        )
    };
    let notes = vec![
        format!(
            "start: U(0) = {name} = {a02:.6} (smallest stable cycle of Eq. 18, {} variant), U'(0) = 0; barrier on, r = 1, D = 0",
            ctx.variant.name()
        ),
        format!(
            "predictor-corrector dt = {dt}, T = {t_end}, SOE memory (tolerance {:e}, the default 1e-5·dt²), impact memory continuous; Eq. (5) by the same driver at lambda = 1", trirhythm::engine::step_tolerance(dt)
        ),
        format!(
            "phase portraits and recurrence plots over the last {window} time units; epsilon = {EPSILON}, Euclidean norm; DET with l_min = 2, main diagonal excluded"
        ),
        format!("fractional: {}", sampling_text(0)),
        format!("Eq. (5): {}", sampling_text(1)),
        format!(
            "fractional: RR = {:.4}, DET = {:.4}, mean amplitude sqrt(U^2 + V^2/omega1^2) over the last 5 periods = {:.4}",
            panels[0].rr, panels[0].det, panels[0].amplitude
        ),
        format!(
            "Eq. (5): RR = {:.4}, DET = {:.4}, mean amplitude = {:.4}",
            panels[1].rr, panels[1].det, panels[1].amplitude
        ),
        format!(
            "impact-memory convention: continuous (drawn) gives amplitude {:.4}, restart gives {:.4}; without the barrier {:.4}",
            panels[0].amplitude, restart_amplitude, free_amplitude
        ),
        "without the barrier the fractional system stays on the Eq. (5) cycle (the smooth oscillator Eq. 5 is derived for); with impacts (continuous memory) it settles on a larger cycle: the memory of the velocity reversals is what Eq. (5) misses (the Zhuravlev transformation is not exact for the fractional system). The amplitude is converged in dt (7.8862, 7.8865, 7.8866 at dt = 0.02, 0.01, 0.005) and the Direct memory gives the same path (checked to T = 300)".to_string(),
    ];
    let heading_lines = vec![
        format!(
            "start U(0) = {name} = {a02:.4}, dU/dt(0) = 0 (smallest stable cycle of Eq. 18); predictor–corrector Δt = {dt}, T = {t_end}; last {window} time units shown"
        ),
        format!(
            "(a) impact memory: continuous (lower terminal kept at t = 0), amplitude {:.3}; the restart convention gives {:.3}, Eq. (5) {:.3}",
            panels[0].amplitude, restart_amplitude, panels[1].amplitude
        ),
        format!(
            "recurrence: ε = {EPSILON}, Euclidean norm; (c) {}; (d) {}",
            sampling_text(0),
            sampling_text(1)
        ),
        crate::fig04_drift::CYCLE_NAMING.to_string(),
    ];
    (notes, heading_lines)
}

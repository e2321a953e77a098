//! Fig. 14: the joint density P(U, U̇) for four restitution coefficients — the averaged
//! theory's Eq. (30–31) (left) against the Monte Carlo histogram of Eq. (1) (right), a row per r,
//! as heat maps with one colour scale per r, the Hellinger distance between them and the
//! stationarity verdict of each ensemble.
//!
//! Method: [`crate::montecarlo::ensemble`] with a joint histogram; the theory's density
//! averaged over each cell exactly (amplitude slices spread over their half-ellipses).
//! Checked by `tests/figures.rs`.

use crate::montecarlo::{stationary_ensemble, Sizes};
use crate::notes::num;
use crate::notes::{caption, table_notes, Caption};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
use trirhythm::engine::System;
use trirhythm::model::preset;
use trirhythm::theory::averaging::Theory;
use trirhythm::Result;

/// The paper's r of panels (a)–(d).
pub const RS: [f64; 4] = [0.999, 0.96, 0.92, 0.86];

/// How many times finer than the Monte Carlo grid the theory's drawn grid is, per axis.
pub const FINE: usize = 4;

/// One r: the grid, both densities (row-major, U index then U̇ index), the mass each leaves
/// outside the window, the verdict.
#[derive(Serialize, Deserialize)]
pub struct JointPanel {
    /// Restitution coefficient.
    pub r: f64,
    /// Cell edges in U.
    pub u_edges: Vec<f64>,
    /// Cell edges in U̇.
    pub v_edges: Vec<f64>,
    /// Eq. 31 averaged over each cell.
    pub theory: Vec<Vec<f64>>,
    /// Eq. 31 averaged over the cells of a grid [`FINE`] times finer on the same window (what
    /// the picture draws: the theory's thin rings stay smooth).
    pub theory_fine: Vec<Vec<f64>>,
    /// Fraction of the theory's mass outside the window.
    pub theory_outside: f64,
    /// Fraction of the Monte Carlo samples outside the window (the fast returns of the
    /// relaxation oscillation reach velocities beyond ±ω1·A_max).
    pub mc_outside: f64,
    /// The Monte Carlo histogram.
    pub mc: Vec<Vec<f64>>,
    /// Standard error of each cell of the Monte Carlo histogram (jackknife over the paths;
    /// empty in data written before it was stored, or where a standard error is undefined).
    #[serde(default)]
    pub mc_stderr: Vec<Vec<f64>>,
    /// The Monte Carlo variance of U̇ (the distribution's extent in Z = U̇) and its standard
    /// error, [value, se] (empty in data written before it was stored).
    #[serde(default, with = "trirhythm::non_finite::vec")]
    pub mc_velocity_variance: Vec<f64>,
    /// The theory's ⟨U̇²⟩ = ω1²⟨A²⟩/2 over its P(A) (Eq. 30–31: U̇ = ω1A sin φ, φ uniform).
    #[serde(default = "nan", with = "trirhythm::non_finite")]
    pub theory_velocity_variance: f64,
    /// Hellinger distance between them over the cells.
    pub hellinger: f64,
    /// Passed the stationarity check.
    pub stationary: bool,
    #[serde(with = "trirhythm::non_finite")]
    /// R̂ of the ensemble.
    pub r_hat: f64,
    /// `direct` or `wells` ([`crate::montecarlo::stationary_ensemble`]).
    #[serde(default = "crate::montecarlo::direct")]
    pub estimator: String,
    /// The well decomposition, where the direct ensemble was not stationary.
    #[serde(default)]
    pub wells: Option<crate::montecarlo::WellsSummary>,
}

fn nan() -> f64 {
    f64::NAN
}

/// Half-width of the U̇ axis as a multiple of ω1·A_max: the simulated outer cycle is a
/// relaxation oscillation whose fast returns reach |U̇| ≈ 24 (99th percentile of one path at
/// r = 0.999) against ω1·A_max ≈ 16, which left 8–24 % of the samples outside ±ω1·A_max; twice
/// that holds more than 99 %.
pub const VELOCITY_FACTOR: f64 = 2.0;

/// Fig. 14's data.
#[derive(Serialize, Deserialize)]
pub struct Fig14 {
    /// What the figure shows, shared parameters, variant, verdict.
    pub caption: Caption,
    /// Notes of the data table: distances, verdicts, the paper's claims checked.
    pub notes: Vec<String>,
    /// One panel per r.
    pub panels: Vec<JointPanel>,
}

impl Figure for Fig14 {
    const NUMBER: u32 = 14;
    const TITLE: &'static str = "joint density P(U, dU/dt) for four r: theory against Monte Carlo";

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig14> {
        let ctx = options;
        let pre = preset("fig14")?;
        let sz = Sizes {
            joint_velocity_factor: VELOCITY_FACTOR,
            ..Sizes::of(ctx.quick)
        };
        let bins = if ctx.quick { 32 } else { 64 };
        let mut notes: Vec<String> = pre.notes.iter().map(|s| s.to_string()).collect();
        notes.push(format!(
            "Monte Carlo of Eq. 1: {}; joint histogram {bins} × {bins} on U ∈ [0, A_max], dU/dt ∈ ±{VELOCITY_FACTOR}·ω1·A_max",
            sz.describe()
        ));
        notes.push("theory: Eq. 31, P(U, dU/dt) = P(A)/(πω1A) on U ≥ 0 with A² = U² + (dU/dt)²/ω1², averaged over each cell exactly: in polar form its mass is P(A)dA·dφ/π, so each of 4000 amplitude slices (mass from the quadrature of P(A)) is spread over 720 angles of its half-ellipse".into());
        // every r side by side, each with its own notes
        let progress = crate::Progress::new(0, RS.len());
        let computed = crate::each(&RS, |&r| {
            let mut notes = Vec::new();
            let p = pre.params.with("r", r)?;
            let (res, step_warnings, estimator, wells) =
                stationary_ensemble(monitor, &p, ctx.variant, System::Fractional, sz, bins)?;
            if let Some(w) = &wells {
                notes.push(format!("r = {r}: {}", w.line()));
                if let Some(b) = w.bounds_line() {
                    notes.push(format!("r = {r}: {b}"));
                }
                notes.extend(w.notes.iter().map(|n| format!("r = {r}: {n}")));
            }
            notes.extend(
                step_warnings
                    .iter()
                    .map(|w| format!("r = {r}: step warning: {w}")),
            );
            let pdf = Theory::new(&p, ctx.variant)?.amplitude_pdf()?;
            let j = &res.joint;
            let (du, dv) = (j.u_edges[1] - j.u_edges[0], j.v_edges[1] - j.v_edges[0]);
            let theory = cell_averages(&pdf, res.omega1, &j.u_edges, &j.v_edges);
            let theory_fine = cell_averages(
                &pdf,
                res.omega1,
                &refine(&j.u_edges, FINE),
                &refine(&j.v_edges, FINE),
            );
            // Hellinger over the cells (each side's mass outside the grid as one more cell)
            let cell = du * dv;
            let q_in: f64 = theory.iter().flatten().sum::<f64>() * cell;
            let p_in: f64 = j.density.iter().flatten().sum::<f64>() * cell;
            let bc = theory
                .iter()
                .flatten()
                .zip(j.density.iter().flatten())
                .map(|(q, m)| (q * cell * m * cell).sqrt())
                .sum::<f64>()
                + ((1.0 - q_in).max(0.0) * (1.0 - p_in).max(0.0)).sqrt();
            let hellinger = (1.0 - bc).max(0.0).sqrt();
            let st = &res.stationarity;
            // ⟨U̇²⟩ of Eq. 31: ω1²⟨A²⟩/2, ⟨A²⟩ by slices of P(A) up to the window's amplitude
            let a_top = *j.u_edges.last().unwrap_or(&1.0);
            let theory_velocity_variance = 0.5
                * res.omega1.powi(2)
                * (0..20_000)
                    .map(|k| {
                        let (a, b) = (a_top * k as f64 / 2e4, a_top * (k + 1) as f64 / 2e4);
                        pdf.probability(a, b) * (0.5 * (a + b)).powi(2)
                    })
                    .sum::<f64>();
            if let Some(&outer) = pdf.modes.last() {
                notes.push(format!(
                    "r = {r}: at the theory's outer mode A = {outer:.2} the damping is μ0|P(A)| = {:.0} against ω0 = {}: the simulated outer cycle is a relaxation oscillation (a slow creep near U ≈ A with dU/dt ≈ 0, the bright cells, and fast returns), which the averaging's uniform-phase ring of Eq. 31 cannot represent",
                    p.mu0 * p.damping.eval(outer).abs(),
                    p.omega0
                ));
            }
            notes.push(format!(
                "r = {r}: Hellinger distance theory–MC over the cells {hellinger:.3}; MC ({estimator}) {} (R̂ = {:.3}, ESS = {:.0}); mass outside the window: theory {:.2} %, MC {:.2} %",
                if st.stationary && estimator == "wells" {
                    "well decomposition accepted (stationary mixture)"
                } else if st.stationary {
                    "stationarity check passed"
                } else {
                    "NOT STATIONARY"
                },
                st.r_hat,
                st.ess,
                100.0 * (1.0 - q_in).max(0.0),
                100.0 * j.outside
            ));
            let panel = JointPanel {
                r,
                u_edges: j.u_edges.clone(),
                v_edges: j.v_edges.clone(),
                theory,
                theory_fine,
                theory_outside: (1.0 - q_in).max(0.0),
                mc_outside: j.outside,
                mc: j.density.clone(),
                // undefined standard errors (a single unit) are not stored: without them the
                // verdicts count no Monte Carlo maxima
                mc_stderr: if j.stderr.iter().flatten().all(|x| x.is_finite()) {
                    j.stderr.clone()
                } else {
                    Vec::new()
                },
                mc_velocity_variance: vec![res.var_v.value, res.var_v.stderr],
                theory_velocity_variance,
                hellinger,
                stationary: st.stationary,
                r_hat: st.r_hat,
                estimator: estimator.into(),
                wells,
            };
            progress.advance(monitor, 1)?;
            Ok((panel, notes))
        })?;
        let mut panels = Vec::new();
        for (panel, n) in computed {
            notes.extend(n);
            panels.push(panel);
        }
        notes.push("the paper's claims (a crater at r = 0.92 turning into four separate peaks at r = 0.999; the trimodal P(A) matching a three- or four-peak joint PDF) are checked against these maps: the joint density of Eq. 31 is a function of A alone, so its peaks are rings, never separate peaks".into());
        let passed = panels.iter().filter(|p| p.stationary).count();
        let outside = |f: fn(&JointPanel) -> f64| {
            panels
                .iter()
                .map(|p| format!("{:.1} %", 100.0 * f(p)))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let window = format!(
            "mass outside the window U ∈ [0, A_max], dU/dt ∈ ±{VELOCITY_FACTOR}·ω1·A_max, per r: Monte Carlo {}; theory {} (not drawn, counted as one more cell in H)",
            outside(|p| p.mc_outside),
            outside(|p| p.theory_outside)
        );
        let caption = caption(
            14,
            "joint density P(U, dU/dt) for four r: theory (left) against Monte Carlo of Eq. 1 (right)",
            ctx,
            &pre.params,
            &["r"],
            vec![
                format!("Monte Carlo: {}; one logarithmic colour scale per r (three decades; white below)", sz.describe()),
                format!("stationarity check passed by {passed} of {} ensembles", panels.len()),
                decides_line(&panels),
                window,
                format!("theory drawn on a grid {FINE} times finer per axis than the Monte Carlo cells (its rings are thin); H compares both on the Monte Carlo cells"),
            ],
        );
        Ok(Fig14 {
            caption,
            notes: table_notes(14, Self::TITLE, ctx, &notes),
            panels,
        })
    }

    fn tables(&self) -> Vec<Table> {
        let mut csv = Table::new(&self.notes, &["r", "U", "V", "theory", "mc"]);
        for p in &self.panels {
            for (i, u) in p.u_edges.windows(2).enumerate() {
                for (k, v) in p.v_edges.windows(2).enumerate() {
                    csv.row([
                        num(p.r),
                        num(0.5 * (u[0] + u[1])),
                        num(0.5 * (v[0] + v[1])),
                        num(p.theory[i][k]),
                        num(p.mc[i][k]),
                    ]);
                }
            }
        }
        let mut fine = Table::new(&self.notes, &["r", "U", "V", "theory"]).named("_theory");
        for p in &self.panels {
            let (u, v) = (refine(&p.u_edges, FINE), refine(&p.v_edges, FINE));
            for (i, u) in u.windows(2).enumerate() {
                for (k, v) in v.windows(2).enumerate() {
                    fine.row([
                        num(p.r),
                        num(0.5 * (u[0] + u[1])),
                        num(0.5 * (v[0] + v[1])),
                        num(p.theory_fine[i][k]),
                    ]);
                }
            }
        }
        vec![csv, fine]
    }

    fn validate(&self) -> crate::validate::Valid {
        use crate::validate::{density_matrix, edges, len, scalar};
        for (i, p) in self.panels.iter().enumerate() {
            let f = format!("panels[{i}]");
            scalar(&format!("{f}.r"), p.r)?;
            edges(&format!("{f}.u_edges"), &p.u_edges)?;
            edges(&format!("{f}.v_edges"), &p.v_edges)?;
            let (nu, nv) = (p.u_edges.len() - 1, p.v_edges.len() - 1);
            let of = format!("{nu} × {nv} cells of u_edges, v_edges");
            density_matrix(&format!("{f}.theory"), &p.theory, nu, nv, &of)?;
            density_matrix(&format!("{f}.mc"), &p.mc, nu, nv, &of)?;
            // the cells' standard errors: none (earlier data) or one per cell
            if !p.mc_stderr.is_empty() {
                let se = format!("{f}.mc_stderr");
                len(&se, p.mc_stderr.len(), nu, &of)?;
                for (k, row) in p.mc_stderr.iter().enumerate() {
                    len(&format!("{se}[{k}]"), row.len(), nv, &of)?;
                }
            }
            if !p.mc_velocity_variance.is_empty() {
                len(
                    &format!("{f}.mc_velocity_variance"),
                    p.mc_velocity_variance.len(),
                    2,
                    "[value, standard error]",
                )?;
            }
            let fine = format!("{} × {} cells, {FINE} times finer", nu * FINE, nv * FINE);
            density_matrix(
                &format!("{f}.theory_fine"),
                &p.theory_fine,
                nu * FINE,
                nv * FINE,
                &fine,
            )?;
            for (name, v) in [
                ("theory_outside", p.theory_outside),
                ("mc_outside", p.mc_outside),
                ("hellinger", p.hellinger),
            ] {
                scalar(&format!("{f}.{name}"), v)?;
            }
        }
        Ok(())
    }
}

/// What the Monte Carlo maps can decide: every ensemble stationary, or, plainly, that they
/// decide nothing and why (the wells' exchange rates that no window in the budget resolves).
fn decides_line(panels: &[JointPanel]) -> String {
    let open: Vec<String> = panels
        .iter()
        .filter(|p| !p.stationary)
        .map(|p| {
            let why = p
                .wells
                .as_ref()
                .and_then(|w| w.refusals.first().cloned())
                .unwrap_or_else(|| format!("R̂ = {}", crate::notes::sig(p.r_hat, 3)));
            format!("r = {}: {why}", p.r)
        })
        .collect();
    if open.is_empty() {
        "every Monte Carlo map is stationary: its peaks and shift in dU/dt decide".into()
    } else {
        format!(
            "the Monte Carlo maps of {} of {} r DECIDE NOTHING (not stationary, and the well decomposition refused: its weights, and so the density, are undetermined): {}",
            open.len(),
            panels.len(),
            open.join("; ")
        )
    }
}

/// Edges `k` times finer: each interval of `edges` split evenly into `k`.
pub fn refine(edges: &[f64], k: usize) -> Vec<f64> {
    let mut out: Vec<f64> = edges
        .windows(2)
        .flat_map(|w| (0..k).map(move |j| w[0] + (w[1] - w[0]) * j as f64 / k as f64))
        .collect();
    out.extend(edges.last());
    out
}

/// The theory's density averaged over each cell of the grid: P(U, U̇)dU dU̇ = P(A)dA dφ/π on
/// U = A cos φ, U̇ = ω1 A sin φ, φ ∈ [−π/2, π/2], so amplitude slices (their mass from the
/// quadrature of P(A)) are spread evenly in φ over their half-ellipses.
fn cell_averages(
    pdf: &trirhythm::theory::averaging::AmplitudePdf,
    omega1: f64,
    u_edges: &[f64],
    v_edges: &[f64],
) -> Vec<Vec<f64>> {
    const SLICES: usize = 4000;
    const ANGLES: usize = 720;
    let (nu, nv) = (u_edges.len() - 1, v_edges.len() - 1);
    let (u0, du) = (u_edges[0], u_edges[1] - u_edges[0]);
    let (v0, dv) = (v_edges[0], v_edges[1] - v_edges[0]);
    let a_max = (u_edges[nu].abs()).max(v_edges[nv].abs() / omega1);
    let mut mass = vec![vec![0.0; nv]; nu];
    for k in 0..SLICES {
        let (a, b) = (
            a_max * k as f64 / SLICES as f64,
            a_max * (k + 1) as f64 / SLICES as f64,
        );
        let w = pdf.probability(a, b) / ANGLES as f64;
        if w <= 0.0 {
            continue;
        }
        let amp = 0.5 * (a + b);
        for m in 0..ANGLES {
            let phi = std::f64::consts::PI * ((m as f64 + 0.5) / ANGLES as f64 - 0.5);
            let (s, c) = phi.sin_cos();
            let i = ((amp * c - u0) / du).floor();
            let l = ((omega1 * amp * s - v0) / dv).floor();
            if i >= 0.0 && l >= 0.0 && (i as usize) < nu && (l as usize) < nv {
                mass[i as usize][l as usize] += w;
            }
        }
    }
    for row in &mut mass {
        for x in row.iter_mut() {
            *x /= du * dv;
        }
    }
    mass
}

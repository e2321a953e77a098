//! Commands of the averaged theory: equivalents, cycles, drift, potential, barriers, pdf.

use crate::args::{Format, Grid, OutputArgs, ParamArgs, TheoryModelArg};
use crate::error::bad;
use crate::io::{emit, jlimit, jnum, jvec, params_json, pretty, reading, Csv};
use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use serde_json::{json, Value};
use trirhythm::model::Model;
use trirhythm::theory::averaging::{AmplitudePdf, Balance, Theory, Variant};
use trirhythm_paper::table::Table;
use trirhythm_paper::views;

/// Arguments of every theory command.
#[derive(Debug, Args)]
pub struct TheoryArgs {
    #[command(flatten)]
    pub params: ParamArgs,
    #[command(flatten)]
    pub file: TheoryModelArg,
    /// Where the fractional terms are balanced: at ω0 (the paper's Eq. 4) or at the linearised
    /// oscillator's own frequency ω_b = ω1(ω_b) (consistent variant; by quadrature).
    #[arg(long, value_enum, default_value_t = BalanceArg::Natural)]
    pub balance: BalanceArg,
    #[command(flatten)]
    pub output: OutputArgs,
}

/// `natural` or `self-consistent`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum BalanceArg {
    /// ω_b = ω0 (Eq. 4).
    #[default]
    Natural,
    /// ω_b = ω1(ω_b).
    SelfConsistent,
}

impl TheoryArgs {
    /// The theory of `--model FILE` (by quadrature, or its refusal), else of the parameters.
    fn theory(&self) -> Result<Theory> {
        let balance = match self.balance {
            BalanceArg::Natural => Balance::Natural,
            BalanceArg::SelfConsistent => Balance::SelfConsistent,
        };
        let (model, variant) = match self.file.load(&self.params)? {
            Some(model) => {
                let variant = self.params.variant_for(&model);
                if self.params.variant.is_none() && variant != Variant::Paper {
                    crate::io::progress::note(
                        "note: --variant consistent (the paper's formulas are printed for its \
                         Eq. (1) with the wall at 0 only, not for this model)",
                    );
                }
                (model, variant)
            }
            None if balance == Balance::Natural => {
                return Ok(Theory::new(&self.params.resolve()?, self.params.variant())?)
            }
            None => (Model::from(&self.params.resolve()?), self.params.variant()),
        };
        let th = Theory::from_model_with(&model, variant, balance);
        match &self.file.model {
            Some(path) => th.with_context(|| format!("--model {}", path.display())),
            None => Ok(th?),
        }
    }
}

/// A theory document: the parameters (or the model and the assumptions measured on it), the
/// variant, the equivalents (Eq. 5), then `rest`.
fn doc<'a>(th: &Theory, rest: impl IntoIterator<Item = (&'a str, Value)>) -> Result<String> {
    let mut m = serde_json::Map::new();
    match th.model() {
        None => m.insert("params".into(), params_json(th.params())),
        Some(model) => m.insert("model".into(), json!(model)),
    };
    m.insert("variant".into(), json!(th.variant().name()));
    if !th.assumptions().is_empty() {
        m.insert("assumptions".into(), json!(th.assumptions()));
    }
    m.insert("equivalents".into(), json!(th.equivalents()));
    m.extend(rest.into_iter().map(|(k, v)| (k.to_string(), v)));
    pretty(&m)
}

/// `equivalents`: μ1, β1, ω1, β2 of Eq. 5, with σ1 and the impact loss rate.
pub fn equivalents(args: &TheoryArgs) -> Result<()> {
    let th = args.theory()?;
    let text = match args.output.format {
        Format::Json => doc(
            &th,
            [
                ("sigma1", jnum(th.diffusion())),
                ("loss_rate", jnum(th.loss_rate())),
            ]
            .into_iter()
            .chain(th.model().map(|_| {
                (
                    "multiplicative",
                    json!({
                        "diffusion_b1": jnum(th.multiplicative_diffusion()),
                        "drift_correction_q": jnum(th.multiplicative_correction()),
                    }),
                )
            })),
        )?,
        Format::Csv => Csv::of(&views::equivalents_table(&th))?,
        Format::Table => reading(&Table {
            notes: vec![],
            ..views::equivalents_table(&th)
        })?,
    };
    emit(args.output.out.as_deref(), &text)
}

/// `cycles`: every positive root of f (D = 0) or m1 (D > 0) with its stability.
pub fn cycles(args: &TheoryArgs) -> Result<()> {
    let th = args.theory()?;
    let cycles = th.cycles();
    let rhythm = th.rhythmicity();
    let kind = views::cycles_kind(&th);
    let text = match args.output.format {
        Format::Json => doc(
            &th,
            [
                ("kind", json!(kind)),
                ("cycles", json!(cycles)),
                ("stable_count", json!(rhythm.count())),
                ("rhythmicity", json!(rhythm.name())),
                ("rest_state_stable", json!(th.rest_state_slope() < 0.0)),
            ],
        )?,
        Format::Csv => Csv::of(&views::cycles_table(&th))?,
        Format::Table => reading(&views::cycles_reading(&th))?,
    };
    emit(args.output.out.as_deref(), &text)
}

/// Arguments of `drift` and `potential`.
#[derive(Debug, Args)]
pub struct CurveArgs {
    #[command(flatten)]
    pub theory: TheoryArgs,
    /// Amplitude grid START:STOP:COUNT (START ≥ 0).
    #[arg(long, default_value = "0:15:301", allow_hyphen_values = true)]
    pub grid: String,
}

fn amplitude_grid(s: &str) -> Result<Vec<f64>> {
    let g = Grid::parse(s, "--grid")?;
    if g.start < 0.0 {
        return bad(format!("--grid: amplitude START = {} must be ≥ 0", g.start));
    }
    Ok(g.points())
}

/// Write named columns; ±∞ is allowed (as a limit) in the columns named in `infinite`.
fn emit_columns(
    args: &TheoryArgs,
    th: &Theory,
    names: &[&str],
    cols: Vec<Vec<f64>>,
    infinite: &[&str],
) -> Result<()> {
    let text = match args.output.format {
        Format::Json => doc(
            th,
            names.iter().zip(&cols).map(|(&name, col)| {
                let limit = infinite.contains(&name);
                let v = col.iter().map(|&v| if limit { jlimit(v) } else { jnum(v) });
                (name, Value::Array(v.collect()))
            }),
        )?,
        Format::Csv => {
            let cols: Vec<&[f64]> = cols.iter().map(Vec::as_slice).collect();
            let notes = views::theory_notes(th);
            Csv::of(&views::columns_table(&notes, names, &cols, infinite))?
        }
        Format::Table => {
            let cols: Vec<&[f64]> = cols.iter().map(Vec::as_slice).collect();
            reading(&views::columns_reading(names, &cols, infinite))?
        }
    };
    emit(args.output.out.as_deref(), &text)
}

/// `drift`: f(A) (Eq. 18), df/dA and the energy change per period (Eq. 20).
pub fn drift(args: &CurveArgs) -> Result<()> {
    let th = args.theory.theory()?;
    let a = amplitude_grid(&args.grid)?;
    let f = a.iter().map(|&x| th.drift(x)).collect();
    let df = a.iter().map(|&x| th.drift_slope(x)).collect();
    let de = a.iter().map(|&x| th.energy_change(x)).collect();
    emit_columns(
        &args.theory,
        &th,
        &["A", "f", "df_dA", "delta_E"],
        vec![a, f, df, de],
        &[],
    )
}

/// `potential`: U_eff(A) (Eq. 23) and the FPK drift m1.
pub fn potential(args: &CurveArgs) -> Result<()> {
    let th = args.theory.theory()?;
    let a = amplitude_grid(&args.grid)?;
    let u = a.iter().map(|&x| th.potential(x)).collect();
    let m1 = a.iter().map(|&x| th.fpk_drift(x)).collect();
    // at A = 0 with D > 0: U_eff = +∞ and m1 = +∞ (the σ1 ln A and σ1/(2A) terms), the limits
    emit_columns(
        &args.theory,
        &th,
        &["A", "U_eff", "m1"],
        vec![a, u, m1],
        &["U_eff", "m1"],
    )
}

/// `barriers`: the extrema of U_eff and the barriers ΔU_i between them.
pub fn barriers(args: &TheoryArgs) -> Result<()> {
    let th = args.theory()?;
    let ex = th.extrema();
    let bs = th.barriers();
    let text = match args.output.format {
        Format::Json => {
            let named = bs.iter().enumerate().map(|(i, b)| {
                let mut v = json!(b);
                v["name"] = json!(format!("dU{}", i + 1));
                v
            });
            let named = Value::Array(named.collect());
            doc(&th, [("extrema", json!(ex)), ("barriers", named)])?
        }
        Format::Csv => Csv::of(&views::barriers_table(&th))?,
        Format::Table => reading(&views::barriers_reading(&th))?,
    };
    emit(args.output.out.as_deref(), &text)
}

/// Which stationary PDF.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PdfKind {
    /// P(A), Eq. 27.
    Amplitude,
    /// P(H), Eq. 29.
    Energy,
    /// P(U, U̇) on U ≥ 0, Eq. 30–31.
    Joint,
}

/// Arguments of `pdf`.
#[derive(Debug, Args)]
pub struct PdfArgs {
    #[command(flatten)]
    pub theory: TheoryArgs,
    /// Which density.
    #[arg(long, value_enum, default_value_t = PdfKind::Amplitude)]
    pub kind: PdfKind,
    /// Grid START:STOP:COUNT of A, H, or U (joint); default: 401 points over the density's
    /// support plus 101 over ±6 widths around each mode (A and H).
    #[arg(long, allow_hyphen_values = true)]
    pub grid: Option<String>,
    /// Velocity grid START:STOP:COUNT for the joint density; default: symmetric, 101 points.
    #[arg(long, allow_hyphen_values = true)]
    pub vgrid: Option<String>,
}

/// The default amplitude grid of `pdf`: 401 points over [0, support end] and 101 more over
/// ±6 widths around each mode, so that a peak narrower than the uniform spacing (small D, large
/// τ) is still drawn.
fn support_grid(pdf: &AmplitudePdf) -> Vec<f64> {
    let end = pdf.support_end;
    let mut a: Vec<f64> = (0..401).map(|i| end * i as f64 / 400.0).collect();
    for (&m, &w) in pdf.modes.iter().zip(&pdf.mode_widths) {
        a.extend((0..=100).map(|i| m + w * (i as f64 / 50.0 - 1.0) * 6.0));
    }
    a.retain(|&x| (0.0..=end).contains(&x));
    a.sort_by(f64::total_cmp);
    a.dedup();
    a
}

/// `pdf`: the stationary densities, normalised in log space.
pub fn pdf(args: &PdfArgs) -> Result<()> {
    let th = args.theory.theory()?;
    let pdf = th.amplitude_pdf()?;
    let text = match args.kind {
        PdfKind::Amplitude | PdfKind::Energy => pdf_1d(args, &th, &pdf)?,
        PdfKind::Joint => pdf_joint(args, &th, &pdf)?,
    };
    emit(args.theory.output.out.as_deref(), &text)
}

/// P(A) (Eq. 27) or P(H) (Eq. 29) on a grid.
fn pdf_1d(args: &PdfArgs, th: &Theory, pdf: &AmplitudePdf) -> Result<String> {
    let energy = args.kind == PdfKind::Energy;
    let w1 = th.equivalents().omega1;
    let xs = match args.grid.as_deref() {
        Some(g) => amplitude_grid(g)?,
        None if energy => support_grid(pdf)
            .iter()
            .map(|&a| 0.5 * w1 * w1 * a * a)
            .collect(),
        None => support_grid(pdf),
    };
    let logp: Vec<f64> = xs
        .iter()
        .map(|&x| {
            if energy {
                pdf.log_energy_density(x)
            } else {
                pdf.log_density(x)
            }
        })
        .collect();
    let p: Vec<f64> = logp.iter().map(|l| l.exp()).collect();
    let xname = if energy { "H" } else { "A" };
    Ok(match args.theory.output.format {
        Format::Json => doc(
            th,
            [
                ("kind", json!(if energy { "energy" } else { "amplitude" })),
                ("sigma1", jnum(th.diffusion())),
                ("modes", jvec(&pdf.modes)),
                ("antimodes", jvec(&pdf.antimodes)),
                ("mean_amplitude", jnum(pdf.mean_amplitude)),
                (xname, jvec(&xs)),
                ("p", jvec(&p)),
                ("log_p", logp.iter().map(|&v| jlimit(v)).collect()),
            ],
        )?,
        Format::Csv => {
            let mut h = views::theory_notes(th);
            h.push(format!("modes: {:?}", pdf.modes));
            h.push(format!("antimodes: {:?}", pdf.antimodes));
            h.push(format!("mean_amplitude: {}", pdf.mean_amplitude));
            let columns = [xname, "p", "log_p"];
            Csv::of(&views::columns_table(
                &h,
                &columns,
                &[&xs, &p, &logp],
                &["log_p"],
            ))?
        }
        Format::Table => reading(&views::pdf_reading(xname, &xs, &p, &logp, pdf))?,
    })
}

/// The most cells (U points × U̇ points) of the joint density: the document is held in memory
/// before it is written, at most [`JOINT_CELL_BYTES`] bytes a cell at its peak, so this bounds
/// it near 1 GiB.
pub const MAX_JOINT_CELLS: usize = 2_500_000;

/// The peak memory of one joint-density cell, in bytes, rounded up from the measured peak
/// resident size of a 2000 × 2000 grid: 361 bytes a cell as CSV (the log-densities, the table
/// and its text), 112 as JSON.
pub const JOINT_CELL_BYTES: usize = 400;

/// Refuse a joint grid whose document would not fit in [`MAX_JOINT_CELLS`], before any work,
/// naming the largest `--grid` count that fits with the given `--vgrid` (and the square grid).
fn check_joint_cells(nu: usize, nv: usize) -> Result<()> {
    let cells = nu as u128 * nv as u128;
    if cells <= MAX_JOINT_CELLS as u128 {
        return Ok(());
    }
    let side = (MAX_JOINT_CELLS as f64).sqrt().floor() as usize;
    bad(format!(
        "--grid/--vgrid: {nu} × {nv} = {cells} cells; the joint density is held in memory \
         (up to {JOINT_CELL_BYTES} bytes a cell), at most {MAX_JOINT_CELLS} cells: with \
         --vgrid of {nv} points --grid may have at most {} points (or {side} × {side})",
        MAX_JOINT_CELLS / nv.max(1)
    ))
}

/// P(U, U̇) on U ≥ 0 (Eq. 30–31) on a grid.
fn pdf_joint(args: &PdfArgs, th: &Theory, pdf: &AmplitudePdf) -> Result<String> {
    let a_end = pdf.support_end;
    let vmax = th.equivalents().omega1 * a_end;
    let u_default = format!("0:{a_end}:101");
    let ug = Grid::parse(args.grid.as_deref().unwrap_or(&u_default), "--grid")?;
    let v_default = format!("{}:{vmax}:101", -vmax);
    let vg = Grid::parse(args.vgrid.as_deref().unwrap_or(&v_default), "--vgrid")?;
    check_joint_cells(ug.count, vg.count)?;
    let (us, vs) = (ug.points(), vg.points());
    let spacing = (ug.stop - ug.start) / (ug.count - 1) as f64;
    if let Some((m, w)) = pdf
        .modes
        .iter()
        .zip(&pdf.mode_widths)
        .find(|(_, &w)| w < spacing)
    {
        eprintln!(
            "note: the peak at A = {m:.6} is {w:.3e} wide, narrower than the grid spacing \
             {spacing:.3e}: p may read 0 between grid points; refine --grid and --vgrid \
             around U² + V²/ω1² = A²"
        );
    }
    let logp: Vec<Vec<f64>> = us
        .iter()
        .map(|&u| vs.iter().map(|&v| pdf.log_joint_density(u, v)).collect())
        .collect();
    Ok(match args.theory.output.format {
        Format::Json => {
            let p = logp.iter().map(|row| row.iter().map(|l| l.exp()).collect());
            let p = p.map(|row: Vec<f64>| jvec(&row)).collect();
            let (u, v) = (jvec(&us), jvec(&vs));
            doc(th, [("kind", json!("joint")), ("U", u), ("V", v), ("p", p)])?
        }
        Format::Csv | Format::Table => Csv::of(&views::joint_pdf_table(
            &views::theory_notes(th),
            &us,
            &vs,
            &logp,
        ))?,
    })
}

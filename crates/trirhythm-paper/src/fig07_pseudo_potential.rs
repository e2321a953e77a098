//! Fig. 7: the pseudo-potential U_eff(A0) of the averaged amplitude
//! equation (Eq. 23), for several restitution coefficients r (panel a) and several fractional
//! orders λ (panel b).
//!
//! Method: [`Theory::potential`] on a grid of A0 ∈ [0, 14] and [`Theory::extrema`] (wells are
//! the stable cycles A01, A03, A05 of Eq. 18, crests the unstable ones). The text's claims on
//! the figure (the A01 well shrinks as r decreases, the outer well deepens, the well
//! amplitudes barely move) are checked on the computed curves and stated in the notes.
//! Checked by the crate's doctest (three wells at r = 1) and `tests/figures.rs`.

use crate::notes::num;
use crate::notes::{caption, panel_line, table_notes, Caption};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
use trirhythm::model::preset;
use trirhythm::theory::averaging::{Extremum, Theory};
use trirhythm::Result;

/// One U_eff curve with its extrema.
#[derive(Serialize, Deserialize)]
pub struct Curve {
    /// Which curve (`r = …` or `λ = …`).
    pub label: String,
    /// (A0, U_eff) on the grid.
    pub points: Vec<(f64, f64)>,
    /// Wells (minima: stable cycles) and crests (maxima: unstable cycles).
    pub extrema: Vec<Extremum>,
}

impl Curve {
    /// U_eff of `th` on `grid` (A = 0 skipped when the potential has a log term).
    pub(crate) fn new(label: String, th: &Theory, grid: &[f64]) -> Curve {
        let points = grid
            .iter()
            .filter(|&&a| a > 0.0 || th.diffusion() == 0.0)
            .map(|&a| (a, th.potential(a)))
            .collect();
        Curve {
            label,
            points,
            extrema: th.extrema(),
        }
    }
}

/// The depth of the inner well A01 (to the crest after it) and of the outer well (to the
/// crest before it), and the well amplitudes, of one curve; `None` where a well is missing.
fn wells(cv: &Curve) -> (Option<f64>, Option<f64>, Vec<f64>) {
    let ex: Vec<&Extremum> = cv.extrema.iter().filter(|e| e.amplitude > 0.0).collect();
    let minima: Vec<f64> = ex
        .iter()
        .filter(|e| e.minimum)
        .map(|e| e.amplitude)
        .collect();
    let depth = |i: usize, crest: Option<&&Extremum>| {
        crest
            .filter(|c| !c.minimum)
            .map(|c| c.potential - ex[i].potential)
    };
    let first = ex.iter().position(|e| e.minimum);
    let last = ex.iter().rposition(|e| e.minimum);
    let inner = first
        .filter(|_| minima.len() >= 3)
        .and_then(|i| depth(i, ex.get(i + 1)));
    let outer = last.and_then(|i| depth(i, i.checked_sub(1).and_then(|j| ex.get(j))));
    (inner, outer, minima)
}

/// The text's claims on Fig. 7 ("when r decreases, the potential well in A01 tends to
/// disappear and … that one in A05 increases in depth"; "the amplitudes A01, A03 and A05
/// change very slightly"; "quasi-same phenomena" with λ), checked on the computed curves.
fn text_claims(panel: &str, symbol: &str, values: &[f64], curves: &[Curve]) -> Vec<String> {
    let mut out = Vec::new();
    let rows: Vec<_> = curves.iter().map(wells).collect();
    for (v, (inner, outer, minima)) in values.iter().zip(&rows) {
        out.push(format!(
            "panel {panel}, {symbol} = {v}: wells at A = {}; depth of the A01 well {}, of the outer well {}",
            minima.iter().map(|a| format!("{a:.4}")).collect::<Vec<_>>().join(", "),
            inner.map_or("(no A01 well)".into(), |d| format!("{d:.3e}")),
            outer.map_or("-".into(), |d| format!("{d:.4}"))
        ));
    }
    // values are listed from the largest down
    let inner: Vec<Option<f64>> = rows.iter().map(|r| r.0).collect();
    let outer: Vec<Option<f64>> = rows.iter().map(|r| r.1).collect();
    let shrinking = inner
        .windows(2)
        .all(|w| matches!((w[0], w[1]), (Some(a), Some(b)) if b < a) || w[1].is_none());
    let deepening = outer
        .windows(2)
        .all(|w| matches!((w[0], w[1]), (Some(a), Some(b)) if b > a));
    let spread = rows
        .iter()
        .filter(|r| r.2.len() == rows[0].2.len())
        .flat_map(|r| r.2.iter().zip(&rows[0].2).map(|(a, b)| (a - b).abs() / b))
        .fold(0.0f64, f64::max);
    out.push(format!(
        "panel {panel}, the text's claims as {symbol} decreases: the A01 well becomes shallower or disappears: {}; the outer well (A05) deepens: {}; the well amplitudes change by at most {:.1}% (the text: 'very slightly')",
        if shrinking { "yes" } else { "no" },
        if deepening { "yes" } else { "no" },
        100.0 * spread
    ));
    out
}

/// One panel: U_eff curves for several (r, λ).
#[derive(Serialize, Deserialize)]
pub struct Panel {
    /// `a` or `b`.
    pub id: String,
    /// What the panel varies.
    pub caption: String,
    /// (r, λ) of each curve.
    pub params: Vec<(f64, f64)>,
    /// The curves.
    pub curves: Vec<Curve>,
}

/// Fig. 7's data: U_eff on a grid, with its extrema, per curve.
#[derive(Serialize, Deserialize)]
pub struct Fig07 {
    /// What the figure shows, shared parameters, variant, choices.
    pub caption: Caption,
    /// Notes of the data table: parameters per panel, choices, the text's claims checked.
    pub notes: Vec<String>,
    /// Panels a (several r) and b (several λ).
    pub panels: Vec<Panel>,
}

impl Figure for Fig07 {
    const NUMBER: u32 = 7;
    const TITLE: &'static str = "pseudo-potential U_eff for several r and λ (Eq. 23)";

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig07> {
        monitor.check()?;
        compute(options)
    }

    fn validate(&self) -> crate::validate::Valid {
        use crate::validate::{limits, points};
        for (i, p) in self.panels.iter().enumerate() {
            let f = format!("panels[{i}]");
            points(&format!("{f}.params"), &p.params)?;
            for (j, c) in p.curves.iter().enumerate() {
                limits(&format!("{f}.curves[{j}].points"), &c.points)?;
            }
        }
        Ok(())
    }

    fn tables(&self) -> Vec<Table> {
        let mut csv = Table::new(&self.notes, &["panel", "r", "lambda", "A", "U_eff"]);
        for panel in &self.panels {
            for (cv, &(r, l)) in panel.curves.iter().zip(&panel.params) {
                for &(a, u) in &cv.points {
                    csv.row([panel.id.clone(), num(r), num(l), num(a), num(u)]);
                }
            }
        }
        vec![csv]
    }
}

fn compute(ctx: &FigureOptions) -> Result<Fig07> {
    let n = if ctx.quick { 281 } else { 1401 };
    let grid: Vec<f64> = (0..n).map(|i| 14.0 * i as f64 / (n - 1) as f64).collect();
    let rs = [1.0, 0.999, 0.998, 0.996];
    let lambdas = [1.0, 0.999, 0.998, 0.997];
    let pa = preset("fig7a")?.params;
    let pb = preset("fig7b")?.params;
    let mut a_curves = Vec::new();
    for r in rs {
        let th = Theory::new(&pa.with("r", r)?, ctx.variant)?;
        a_curves.push(Curve::new(format!("r = {r}"), &th, &grid));
    }
    let mut b_curves = Vec::new();
    for l in lambdas {
        let th = Theory::new(&pb.with("lambda", l)?, ctx.variant)?;
        b_curves.push(Curve::new(format!("λ = {l}"), &th, &grid));
    }
    let notes = vec![
        format!(
            "panel a: λ = {}, r ∈ {rs:?} (r values not printed in the paper; chosen)",
            pa.lambda
        ),
        format!(
            "panel b: r = {}, λ ∈ {lambdas:?} (λ values not printed in the paper; chosen)",
            pb.restitution
        ),
        "ω0 is not printed; ω0 = 1 chosen. D = 0, so U_eff = −∫f dA (no log term)".into(),
        "wells: filled markers; crests: open markers".into(),
    ];
    let mut notes = notes;
    notes.extend(text_claims("a", "r", &rs, &a_curves));
    notes.extend(text_claims("b", "λ", &lambdas, &b_curves));
    let mut header = table_notes(7, "pseudo-potential U_eff(A0) (Eq. 23)", ctx, &notes);
    header.push(panel_line("a (base)", &pa));
    header.push(panel_line("b (base)", &pb));
    Ok(Fig07 {
        caption: caption(
            7,
            "the pseudo-potential U_eff(A0) (Eq. 23): wells are stable cycles, crests unstable ones",
            ctx,
            &pa,
            &["r", "lambda"],
            vec![
                format!("r values (a) and λ values (b) are not printed in the paper: chosen; ω0 = 1 chosen (not printed); D = 0, so U_eff = −∫f dA"),
            ],
        ),
        notes: header,
        panels: vec![
            Panel {
                id: "a".into(),
                caption: format!("(a) λ = {}, several r", pa.lambda),
                params: rs.iter().map(|&r| (r, pa.lambda)).collect(),
                curves: a_curves,
            },
            Panel {
                id: "b".into(),
                caption: format!("(b) r = {}, several λ", pb.restitution),
                params: lambdas.iter().map(|&l| (pb.restitution, l)).collect(),
                curves: b_curves,
            },
        ],
    })
}

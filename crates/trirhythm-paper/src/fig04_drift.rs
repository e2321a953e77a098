//! Fig. 4: the averaged drift f(A0) of the amplitude equation (Eq. 18) for four parameter
//! sets (presets `fig4a` … `fig4d`), its zones and its roots, the limit cycles.
//!
//! f > 0 means the amplitude grows (energy uptake); f < 0 that it decays. The paper labels
//! f > 0 "dissipation"; the notes label by the physics and say so. Method: [`Theory::drift`]
//! on a grid of A0 ∈ [0, 14] and [`Theory::limit_cycles`] (stable ⇔ df/dA0 < 0); each panel's
//! root count is set against the count the paper's text gives. Checked by `tests/figures.rs`
//! (every figure computes and reads back) and the CLI's quick figure run.

use crate::notes::num;
use crate::notes::{caption, panel_line, table_notes, Caption};
use crate::table::Table;
use crate::{Figure, FigureOptions, Monitor};

use serde::{Deserialize, Serialize};
use trirhythm::model::preset;
use trirhythm::theory::averaging::{Cycle, Theory};
use trirhythm::Result;

/// What the paper's text says each panel shows (number of roots of f).
const TEXT_ROOTS: [(&str, &str); 4] = [("a", "five"), ("b", "five"), ("c", "three"), ("d", "none")];

/// One panel: f(A0) for one parameter set.
#[derive(Serialize, Deserialize)]
pub struct Panel {
    /// `a` … `d`.
    pub label: String,
    /// Restitution coefficient r.
    pub r: f64,
    /// (A0, f(A0)) on the grid.
    pub curve: Vec<(f64, f64)>,
    /// f(A0) with the same control parameters at r = 1 (where r < 1).
    pub reference: Option<Vec<(f64, f64)>>,
    /// The roots of f: limit cycles, with their stability.
    pub cycles: Vec<Cycle>,
    /// The damping's control parameters (α0, β0, γ0, δ0).
    pub cp: [f64; 4],
    /// The outermost limit cycle of the r = 1 curve (the grid's end, 14, where it has none).
    pub outermost_at_r1: f64,
}

impl Panel {
    /// The roots of this panel's own f at r = 1 (ascending), the reference of its cycles'
    /// names ([`cycle_names`]): its cycles where r = 1; else the sign changes of its r = 1
    /// curve (`reference`), located by linear interpolation, stable where f falls through 0;
    /// None where the panel has no r = 1 curve.
    pub fn reference_cycles(&self) -> Option<Vec<Cycle>> {
        if self.r == 1.0 {
            return Some(self.cycles.clone());
        }
        let curve = self.reference.as_ref()?;
        // the points off zero (A > 0), in order; a root between two of opposite signs: an
        // exact zero between them, else the linear interpolation
        let signed: Vec<usize> = (0..curve.len())
            .filter(|&i| curve[i].0 > 0.0 && curve[i].1 != 0.0 && curve[i].1.is_finite())
            .collect();
        let roots = signed
            .windows(2)
            .filter(|w| (curve[w[0]].1 > 0.0) != (curve[w[1]].1 > 0.0))
            .map(|w| {
                let ((a0, f0), (a1, f1)) = (curve[w[0]], curve[w[1]]);
                let amplitude = if w[1] > w[0] + 1 {
                    curve[(w[0] + w[1]) / 2].0
                } else {
                    a0 + (a1 - a0) * f0 / (f0 - f1)
                };
                Cycle {
                    amplitude,
                    stable: f0 > 0.0,
                    fold: false,
                }
            })
            .collect();
        Some(roots)
    }
}

/// Fig. 4's data: f(A0) on a grid, its roots, per panel.
#[derive(Serialize, Deserialize)]
pub struct Fig04 {
    /// What the figure shows, shared parameters, variant, choices.
    pub caption: Caption,
    /// Notes of the data table: parameters per panel, methods, verdicts.
    pub notes: Vec<String>,
    /// Panels a … d.
    pub panels: Vec<Panel>,
}

impl Figure for Fig04 {
    const NUMBER: u32 = 4;
    const TITLE: &'static str = "f(A0) with its zones and limit cycles (Eq. 18)";

    fn compute(options: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig04> {
        compute(options, monitor)
    }

    fn validate(&self) -> crate::validate::Valid {
        use crate::validate::{finite, points};
        for (i, p) in self.panels.iter().enumerate() {
            let f = format!("panels[{i}]");
            points(&format!("{f}.curve"), &p.curve)?;
            if let Some(r) = &p.reference {
                points(&format!("{f}.reference"), r)?;
            }
            let a: Vec<f64> = p.cycles.iter().map(|c| c.amplitude).collect();
            finite(&format!("{f}.cycles"), &a)?;
            finite(&format!("{f}.cp"), &p.cp)?;
        }
        Ok(())
    }

    fn tables(&self) -> Vec<Table> {
        let mut csv = Table::new(&self.notes, &["panel", "r", "A", "f"]);
        for p in &self.panels {
            for &(a, f) in &p.curve {
                csv.row([p.label.clone(), num(p.r), num(a), num(f)]);
            }
            // the dashed curve: the same control parameters at r = 1
            for &(a, f) in p.reference.iter().flatten() {
                csv.row([p.label.clone(), num(1.0), num(a), num(f)]);
            }
        }
        vec![csv]
    }
}

fn compute(ctx: &FigureOptions, monitor: &dyn Monitor) -> Result<Fig04> {
    monitor.check()?;
    let n = if ctx.quick { 281 } else { 1401 };
    let a_max = 14.0;
    let grid: Vec<f64> = (0..n).map(|i| a_max * i as f64 / (n - 1) as f64).collect();
    let mut panels = Vec::new();
    let mut notes = vec![
        "f > 0: the amplitude grows (energy uptake); the paper calls this zone 'dissipation'"
            .to_string(),
        "stable cycle ⇔ df/dA0 < 0".to_string(),
    ];
    let mut params_lines = Vec::new();
    for (label, said) in TEXT_ROOTS {
        let p = preset(&format!("fig4{label}"))?.params;
        let th = Theory::new(&p, ctx.variant)?;
        let curve: Vec<(f64, f64)> = grid.iter().map(|&a| (a, th.drift(a))).collect();
        let t1 = Theory::new(&p.with("r", 1.0)?, ctx.variant)?;
        let outermost = t1
            .limit_cycles()
            .last()
            .map(|c| c.amplitude)
            .unwrap_or(a_max);
        let reference =
            (p.restitution < 1.0).then(|| grid.iter().map(|&a| (a, t1.drift(a))).collect());
        let cycles = th.limit_cycles();
        let stable = cycles.iter().filter(|c| c.stable).count();
        notes.push(format!(
            "panel {label} (r = {}): Eq. 18 gives {} positive roots ({} stable) at A0 = [{}]; the paper's text says {said}",
            p.restitution,
            cycles.len(),
            stable,
            cycles.iter().map(|c| format!("{:.4}{}", c.amplitude, if c.stable { " s" } else { " u" })).collect::<Vec<_>>().join(", ")
        ));
        params_lines.push(panel_line(label, &p));
        panels.push(Panel {
            label: label.to_string(),
            r: p.restitution,
            curve,
            reference,
            cycles,
            cp: p.damping.control_parameters(),
            outermost_at_r1: outermost,
        });
    }
    let mut header = table_notes(4, "f(A0) (Eq. 18) with its zones and roots", ctx, &notes);
    header.extend(params_lines);
    let base = preset("fig4c")?.params;
    let caption = caption(
        4,
        "the averaged drift f(A0) (Eq. 18): zones and limit cycles",
        ctx,
        &base,
        &["r", "gamma0", "delta0"],
        vec![
            "red: f > 0, the amplitude grows (energy uptake; the paper calls this zone 'dissipation'); blue: f < 0, it decays; dashed: the same control parameters at r = 1".into(),
            CYCLE_NAMING.into(),
        ],
    );
    Ok(Fig04 {
        caption,
        notes: header,
        panels,
    })
}

/// The naming rule of [`cycle_names`] in one line, for the captions of Figs 1 and 4.
pub const CYCLE_NAMING: &str = "cycle names: A_{01}, A_{02}, … are the roots of f at r = 1 (the panel's own control parameters) by increasing amplitude; at another r a root takes the name of the r = 1 root of its stability at the same rank from the largest amplitude";

/// The names of a panel's roots `cycles` (ascending amplitude), in the paper's convention:
/// the roots at r = 1 (`reference`, ascending) are A_01, A_02, … by amplitude (stable odd,
/// unstable even where the smallest root is stable), and a root of another panel continues
/// the same-named root of the r = 1 panel: its k-th stable root counted from the largest
/// amplitude takes the name of the k-th stable root of the reference counted from the
/// largest, and likewise for the unstable ones. A root beyond the reference's takes the
/// next number above all used, odd if stable, even if not. Names are written `A_{0k}`
/// (drawn with a subscript).
pub fn cycle_names(reference: &[Cycle], cycles: &[Cycle]) -> Vec<String> {
    let mut names = vec![String::new(); cycles.len()];
    let mut top = reference.len();
    for stable in [true, false] {
        // the reference's numbers of this kind, from the largest amplitude
        let numbers: Vec<usize> = reference
            .iter()
            .enumerate()
            .filter(|(_, c)| c.stable == stable)
            .map(|(i, _)| i + 1)
            .rev()
            .collect();
        let own = cycles
            .iter()
            .enumerate()
            .filter(|(_, c)| c.stable == stable)
            .map(|(i, _)| i)
            .rev();
        for (k, i) in own.enumerate() {
            let n = match numbers.get(k) {
                Some(&n) => n,
                None => {
                    top += 1;
                    if (top % 2 == 1) != stable {
                        top += 1;
                    }
                    top
                }
            };
            names[i] = format!("A_{{0{n}}}");
        }
    }
    names
}

#[cfg(test)]
mod tests {
    use super::*;

    fn roots(kinds: &str, amplitudes: &[f64]) -> Vec<Cycle> {
        kinds
            .chars()
            .zip(amplitudes)
            .map(|(k, &a)| Cycle {
                amplitude: a,
                stable: k == 's',
                fold: false,
            })
            .collect()
    }

    #[test]
    fn roots_are_named_by_amplitude_at_r1_and_continued_elsewhere() {
        let r1 = roots("sus", &[1.9, 4.2, 7.7]);
        assert_eq!(cycle_names(&r1, &r1), ["A_{01}", "A_{02}", "A_{03}"]);
        // the inner stable root gone: the outer pair keeps its names
        let b = roots("us", &[5.6, 7.0]);
        assert_eq!(cycle_names(&r1, &b), ["A_{02}", "A_{03}"]);
        // the paper's five roots, the inner two gone
        let five = roots("susus", &[1.0, 2.0, 3.0, 4.0, 5.0]);
        assert_eq!(
            cycle_names(&five, &roots("sus", &[3.1, 4.1, 5.2])),
            ["A_{03}", "A_{04}", "A_{05}"]
        );
        // more roots than at r = 1: new numbers above, odd for stable, even for unstable
        assert_eq!(
            cycle_names(&r1, &roots("susus", &[1.0, 2.0, 3.0, 4.0, 5.0])),
            ["A_{05}", "A_{06}", "A_{01}", "A_{02}", "A_{03}"]
        );
        assert!(cycle_names(&[], &b).iter().all(|n| !n.is_empty()));
    }

    /// A panel at r < 1 takes its names from its own r = 1 curve's roots (Fig. 4 (c): five
    /// roots at r = 1, so its outer pair is A_04, A_05).
    #[test]
    fn a_panel_is_named_after_its_own_r1_curve() {
        // f = −(A − 1)(A − 2)(A − 3)(A − 4)(A − 5)·A on a grid: stable 1, 3, 5
        let f = |a: f64| -(1..=5).map(|k| a - k as f64).product::<f64>() * a;
        let grid: Vec<(f64, f64)> = (0..=600).map(|i| (i as f64 * 0.01, 0.0)).collect();
        let reference: Vec<(f64, f64)> = grid.iter().map(|&(a, _)| (a, f(a))).collect();
        let panel = Panel {
            label: "c".into(),
            r: 0.95,
            curve: grid,
            reference: Some(reference),
            cycles: roots("us", &[3.9, 4.8]),
            cp: [0.0; 4],
            outermost_at_r1: 5.0,
        };
        let r1 = panel.reference_cycles().unwrap();
        let found: Vec<(f64, bool)> = r1.iter().map(|c| (c.amplitude, c.stable)).collect();
        assert_eq!(found.len(), 5, "{found:?}");
        for (k, (a, stable)) in found.iter().enumerate() {
            assert!((a - (k + 1) as f64).abs() < 1e-9, "{found:?}");
            assert_eq!(*stable, k % 2 == 0);
        }
        assert_eq!(cycle_names(&r1, &panel.cycles), ["A_{04}", "A_{05}"]);
    }
}

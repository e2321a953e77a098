//! Fig. 1: phase portraits (U, U̇) of the fractional system (Eq. 1, predictor–corrector) and of
//! its harmonic-balance equivalent (Eq. 5), side by side on the same axes (each with the other's
//! orbit dashed beneath it), with their recurrence plots
//! (Eq. 6–7, ε = 0.1, Euclidean norm) and the recurrence rate and determinism of each.
//!
//! Both start at the turning point U = A01, U̇ = 0 of the smallest stable cycle of the averaged
//! theory (Eq. 18), as the paper's text says ("around the attractor's minimum amplitude").
//!
//! Rendering only: the data and its computation are [`trirhythm_paper::fig01_phase_recurrence`].

use crate::render::plot::{chart, padded_range, pe, stroke, LegendStrip, Symbol};
use plotters::prelude::*;
use trirhythm::analysis::{RecurrenceMatrix, RecurrenceThreshold};
use trirhythm_paper::fig01_phase_recurrence::Fig01;

/// Most display cells per axis of a recurrence plot: a cell is drawn when any pair of
/// samples in it recurs (the plot stays legible and the SVG small; RR and DET use every pair).
const DISPLAY_CELLS: usize = 520;

/// The other panel's orbit, drawn under each phase portrait for comparison.
const OTHER: RGBColor = RGBColor(150, 150, 150);

/// The flights between impacts of a phase portrait (the jumps at the wall are not drawn).
fn flights(phase: &[(f64, f64)]) -> Vec<&[(f64, f64)]> {
    let vmax = phase.iter().fold(0.0f64, |m, q| m.max(q.1.abs()));
    let mut out = Vec::new();
    let mut start = 0;
    for i in 1..=phase.len() {
        if i == phase.len() || (phase[i].1 - phase[i - 1].1).abs() > 0.5 * vmax {
            out.push(&phase[start..i]);
            start = i;
        }
    }
    out
}

fn key() -> LegendStrip {
    LegendStrip {
        entries: vec![
            (Symbol::Line(BLACK), "the panel's equation".into()),
            (
                Symbol::Dashed(OTHER),
                "the other panel's equation (same start)".into(),
            ),
        ],
    }
}

/// The caption's key: the recurrence plots' titles give RR and DET (the caption's
/// abbreviations define them).
fn caption_key() -> Vec<String> {
    vec!["the recurrence plots' titles (c), (d) give their RR and DET".to_string()]
}

// The phase portraits, their legend under them, the recurrence plots.
picture!(Fig01, |self, root| key caption_key(), size (1300, 1300 + key().height(1300)), draw {
    let (top, rest) = root.split_vertically(650);
    let (strip, bottom) = rest.split_vertically(key().height(1300));
    let areas: Vec<_> = top
        .split_evenly((1, 2))
        .into_iter()
        .chain(bottom.split_evenly((1, 2)))
        .collect();
    let ur = padded_range(self.panels.iter().flat_map(|p| p.u.iter().copied()));
    let vr = padded_range(self.panels.iter().flat_map(|p| p.v.iter().copied()));
    for (k, p) in self.panels.iter().enumerate() {
        let caption = format!("({}) {}", ["a", "b"][k], p.title);
        let mut c = chart(&areas[k], &caption, ur.clone(), vr.clone(), "U", "dU/dt")?;
        // the other equation's orbit under this one's, on the same axes
        for other in self.panels.iter().enumerate().filter(|(j, _)| *j != k) {
            for flight in flights(&other.1.phase) {
                c.draw_series(DashedLineSeries::new(
                    flight.iter().copied(),
                    9,
                    6,
                    OTHER.stroke_width(stroke(2)),
                ))
                .map_err(pe)?;
            }
        }
        for flight in flights(&p.phase) {
            c.draw_series(LineSeries::new(
                flight.iter().copied(),
                BLACK.stroke_width(2),
            ))
            .map_err(pe)?;
        }
        let recurrence = RecurrenceMatrix::new(&p.u, &p.v, RecurrenceThreshold(self.epsilon))?;
        let n = recurrence.len();
        let tmax = p.t.last().copied().unwrap_or(1.0) - self.start;
        let caption = format!(
            "({}) recurrence plot: RR = {:.3}, DET = {:.3}",
            ["c", "d"][k],
            p.rr,
            p.det
        );
        let mut c = chart(
            &areas[k + 2],
            &caption,
            0.0..tmax,
            0.0..tmax,
            "t_i − t_0",
            "t_j − t_0",
        )?;
        let block = n.div_ceil(DISPLAY_CELLS).max(1);
        let cells_n = n.div_ceil(block);
        let side = tmax * (block * cells_n) as f64 / n.max(1) as f64 / cells_n as f64;
        let mut cells = Vec::new();
        for bi in 0..cells_n {
            // runs of recurrent cells along the row, one rectangle each
            let mut run_start: Option<usize> = None;
            for bj in 0..=cells_n {
                let on = bj < cells_n
                    && (bi * block..((bi + 1) * block).min(n)).any(|i| {
                        (bj * block..((bj + 1) * block).min(n)).any(|j| recurrence.get(i, j))
                    });
                match (on, run_start) {
                    (true, None) => run_start = Some(bj),
                    (false, Some(s0)) => {
                        let (x0, x1) = (bi as f64 * side, (bi + 1) as f64 * side);
                        let (y0, y1) = (s0 as f64 * side, bj as f64 * side);
                        cells.push(Rectangle::new([(x0, y0), (x1, y1)], BLACK.filled()));
                        run_start = None;
                    }
                    _ => {}
                }
            }
        }
        c.draw_series(cells).map_err(pe)?;
    }
    key().draw(&strip)
});

//! The drawing of each paper figure: `impl Picture for FigNN` from the data the paper crate
//! computed (the `figure` command computes the data, writes its tables and
//! calls [`crate::render::plot::save`]).
//!
//! Each figure writes `figNN.csv` (its data, parameters and notes in `#` header lines) and
//! `figNN.png` + `figNN.svg` into the output directory; with `--data` also `figNN.json`, the
//! value everything else is rendered from. `--quick` trades resolution for speed (used by CI);
//! the default is paper quality. `--from-data DIR` renders from `DIR/figNN.json` without
//! computing anything.
//!
//! # Data first, pictures second
//!
//! A figure's data and its computation live in the library crate `trirhythm-paper`
//! ([`trirhythm_paper::Figure`]: number, title, `compute(options, monitor)`, and its data as
//! tables); this module only writes it: each table as a CSV file, and the picture (PNG + SVG)
//! drawn from the data value alone, deterministically, so that rendering the data read back
//! from `figNN.json` gives the same bytes. To add figure NN: its data type, computation and
//! tables in `trirhythm-paper` (`figNN_what.rs` there), then here `figNN_what.rs` with
//! `impl Picture for FigNN` (the drawing, [`crate::render::plot::save`] writes it), and
//! `entry::<FigNN>()` in [`registry`]. Progress of a computation goes to a bar on the terminal
//! through [`Bar`], the library's [`Monitor`].

mod boundary;
/// `impl Picture for $figure`, headed by its caption (`$self.caption` unless given): `$size`
/// pixels, drawn by the block `$draw`, which sees the figure as `self` and the area as `$root`.
macro_rules! picture {
    ($figure:ty, |$self:tt, $root:ident| size $size:expr, draw $draw:block) => {
        picture!($figure, |$self, $root| caption $self.caption, size $size, draw $draw);
    };
    ($figure:ty, |$self:tt, $root:ident| caption $caption:expr, size $size:expr, draw $draw:block) => {
        picture!($figure, |$self, $root| caption $caption, key Vec::new(), size $size, draw $draw);
    };
    ($figure:ty, |$self:tt, $root:ident| key $key:expr, size $size:expr, draw $draw:block) => {
        picture!($figure, |$self, $root| caption $self.caption, key $key, size $size, draw $draw);
    };
    ($figure:ty, |$self:tt, $root:ident| caption $caption:expr, key $key:expr, size $size:expr, draw $draw:block) => {
        impl crate::render::plot::Picture for $figure {
            fn size(&$self) -> (u32, u32) {
                $size
            }

            fn heading(&$self) -> crate::render::plot::Heading {
                super::heading_of(&$caption, $key)
            }

            fn draw<DB: crate::render::plot::Backend>(
                &$self,
                $root: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
            ) -> anyhow::Result<()>
            $draw
        }
    };
}

/// `impl Picture for $figure`, a newtype of shared data that is itself a [`Picture`]: the map
/// figures and the LLE-against-noise figures.
macro_rules! picture_through {
    ($figure:ty) => {
        // (the shared picture's heading, with the key its drawing adds)
        impl crate::render::plot::Picture for $figure {
            fn size(&self) -> (u32, u32) {
                self.0.size()
            }

            fn heading(&self) -> crate::render::plot::Heading {
                self.0.heading()
            }

            fn draw<DB: crate::render::plot::Backend>(
                &self,
                root: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
            ) -> anyhow::Result<()> {
                self.0.draw(root)
            }
        }
    };
}

mod fig01_phase_recurrence;
mod fig02_rhythmicity_planes;
mod fig03_restitution_planes;
mod fig04_drift;
mod fig05_branches;
mod fig06_fractional_planes;
mod fig07_pseudo_potential;
mod fig08_barriers;
mod fig09_barrier_surfaces;
mod fig10_pbif_lambda_tau;
mod fig11_amplitude_lambda;
mod fig12_pbif_maps;
mod fig13_pdf_restitution;
mod fig14_joint_pdf;
mod fig15_oscillation_boundaries;
mod fig16_oscillation_regions;
mod fig17_lle_noise;
mod fig18_lle_noise_fractional;
mod fig19_critical_noise;
mod lle;
mod mapfig;
mod montecarlo;
pub mod simmap;

use crate::render::plot::Heading;
use trirhythm_paper::notes::Caption;

/// A caption drawn as a picture's heading, with the lines the drawing adds after the data's
/// (`key`: what its marks mean where the data's notes cannot say it) and a glossary of the
/// abbreviations the caption uses without defining them.
pub fn heading_of(caption: &Caption, key: Vec<String>) -> Heading {
    let mut lines = caption.lines.clone();
    lines.extend(key);
    let glossary = glossary(&caption.title, &lines);
    lines.extend(glossary);
    Heading {
        title: untex(&caption.title),
        lines: lines.iter().map(|l| untex(l)).collect(),
        verdicts: Vec::new(),
    }
}

/// A caption line without TeX's subscript braces: `A_{01}` as A₀₁ (digits as subscripts),
/// `ω_{d}` as ω_d (other subscripts after a bare underscore).
fn untex(line: &str) -> String {
    const DIGITS: [char; 10] = ['₀', '₁', '₂', '₃', '₄', '₅', '₆', '₇', '₈', '₉'];
    let mut out = String::with_capacity(line.len());
    let mut rest = line;
    while let Some(i) = rest.find("_{") {
        let Some(j) = rest[i + 2..].find('}') else {
            break;
        };
        let inner = &rest[i + 2..i + 2 + j];
        out.push_str(&rest[..i]);
        if !inner.is_empty() && inner.chars().all(|c| c.is_ascii_digit()) {
            out.extend(inner.chars().map(|c| DIGITS[c as usize - '0' as usize]));
        } else {
            out.push('_');
            out.push_str(inner);
        }
        rest = &rest[i + 3 + j..];
    }
    out.push_str(rest);
    out
}

/// The abbreviations a caption uses (in its title or lines), each with what it stands for,
/// as one line "abbreviations: …"; none where it uses none.
fn glossary(title: &str, lines: &[String]) -> Option<String> {
    const TERMS: [(&str, &str); 3] = [
        (
            "cp = ",
            "cp = (α0, β0, γ0, δ0), the control parameters of the damping polynomial \
             P(U) = 1 − U² + α0U⁴ − β0U⁶ + γ0U⁸ − δ0U¹⁰",
        ),
        (
            "RR",
            "RR: the recurrence rate, the share of recurrent pairs of points",
        ),
        (
            "DET",
            "DET: the determinism, the share of recurrent points on diagonal lines of two \
             points or more (l_min = 2; the line of identity excluded)",
        ),
    ];
    let uses = |word: &str| {
        std::iter::once(title)
            .chain(lines.iter().map(String::as_str))
            .any(|l| l.contains(word))
    };
    let found: Vec<&str> = TERMS
        .iter()
        .filter(|(word, _)| uses(word))
        .map(|(_, what)| *what)
        .collect();
    (!found.is_empty()).then(|| format!("abbreviations: {}", found.join("; ")))
}

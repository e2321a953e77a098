//! The averaged theory's results as tables: for CSV files (`*_table`) and for reading
//! (`*_reading`, aligned by the CLI, notes closing the table).

use super::fixed;
use crate::notes::num;
use crate::table::Table;
use trirhythm::theory::averaging::{AmplitudePdf, Theory};

/// The notes every table of the averaged theory starts with: the parameters (or the model of
/// the class) and the variant, then the assumptions measured on a model.
pub fn theory_notes(th: &Theory) -> Vec<String> {
    let what = match th.model() {
        None => format!("params: {}", th.describe()),
        Some(_) => th.describe(),
    };
    let mut notes = vec![what, format!("variant: {}", th.variant().name())];
    for a in th.assumptions() {
        notes.push(format!(
            "assumption: {} = {} (limit {}: {})",
            a.name,
            num(a.value),
            num(a.limit),
            if a.holds { "holds" } else { "strained" }
        ));
    }
    notes
}

/// What the roots of the theory are: `pdf_extrema` (roots of m1, noise) or `limit_cycles`.
pub fn cycles_kind(th: &Theory) -> &'static str {
    if th.noisy() {
        "pdf_extrema"
    } else {
        "limit_cycles"
    }
}

/// The theory's cycles `amplitude,stable,fold`, their count and rhythmicity in the notes.
pub fn cycles_table(th: &Theory) -> Table {
    let rhythm = th.rhythmicity();
    let mut notes = theory_notes(th);
    notes.push(format!(
        "{}: {} stable ({})",
        cycles_kind(th),
        rhythm.count(),
        rhythm.name()
    ));
    let mut t = Table::new(&notes, &["amplitude", "stable", "fold"]);
    for c in th.cycles() {
        t.row([num(c.amplitude), c.stable.to_string(), c.fold.to_string()]);
    }
    t
}

/// The barriers of U_eff `name,well,crest,side,height` (`dU1`, `dU2`, …).
pub fn barriers_table(th: &Theory) -> Table {
    let columns = ["name", "well", "crest", "side", "height"];
    let mut t = Table::new(&theory_notes(th), &columns);
    for (i, b) in th.barriers().iter().enumerate() {
        t.row([
            format!("dU{}", i + 1),
            num(b.well),
            num(b.crest),
            b.side.name().into(),
            num(b.height),
        ]);
    }
    t
}

/// Named columns of equal length as a table; ±∞ allowed in the columns named in `infinite`.
pub fn columns_table(
    notes: &[String],
    names: &[&str],
    cols: &[&[f64]],
    infinite: &[&str],
) -> Table {
    let mut t = Table::new(notes, names);
    for column in infinite {
        t = t.allow_infinity(column);
    }
    for i in 0..cols.first().map_or(0, |c| c.len()) {
        t.row(cols.iter().map(|col| num(col[i])));
    }
    t
}

/// The joint density P(U, U̇) on a grid `U,V,p,log_p` (`log_p[i][j]` at `us[i]`, `vs[j]`).
pub fn joint_pdf_table(notes: &[String], us: &[f64], vs: &[f64], log_p: &[Vec<f64>]) -> Table {
    let mut t = Table::new(notes, &["U", "V", "p", "log_p"]).allow_infinity("log_p");
    for (&u, row) in us.iter().zip(log_p) {
        for (&v, &l) in vs.iter().zip(row) {
            t.row([num(u), num(v), num(l.exp()), num(l)]);
        }
    }
    t
}

/// The theory's cycles for reading: `cycle,amplitude,stability` (`A01`, …; stable, unstable
/// or fold), the count and rhythmicity as the closing note.
pub fn cycles_reading(th: &Theory) -> Table {
    let rhythm = th.rhythmicity();
    let note = format!(
        "{}: {} stable ({})",
        cycles_kind(th),
        rhythm.count(),
        rhythm.name()
    );
    let mut t = Table::new(&[note], &["cycle", "amplitude", "stability"]);
    for (i, c) in th.cycles().iter().enumerate() {
        let stability = if c.fold {
            "fold"
        } else if c.stable {
            "stable"
        } else {
            "unstable"
        };
        t.row([
            format!("A0{}", i + 1),
            fixed(c.amplitude, 10),
            stability.into(),
        ]);
    }
    t
}

/// The barriers of U_eff for reading: `barrier,well A,crest A,side,height` (`ΔU1`, …).
pub fn barriers_reading(th: &Theory) -> Table {
    let columns = ["barrier", "well A", "crest A", "side", "height"];
    let mut t = Table::new(&[], &columns);
    for (i, b) in th.barriers().iter().enumerate() {
        t.row([
            format!("ΔU{}", i + 1),
            fixed(b.well, 6),
            fixed(b.crest, 6),
            b.side.name().into(),
            format!("{:.6e}", b.height),
        ]);
    }
    t
}

/// Named columns for reading (8 significant decimals in exponent notation).
pub fn columns_reading(names: &[&str], cols: &[&[f64]], infinite: &[&str]) -> Table {
    let mut t = columns_table(&[], names, cols, infinite);
    for (i, row) in t.rows.iter_mut().enumerate() {
        *row = cols
            .iter()
            .map(|col| format!("{:.8e}", col[i] + 0.0))
            .collect();
    }
    t
}

/// A one-dimensional density for reading: `x,p,log_p`, the modes, antimodes and mean
/// amplitude of `pdf` as the closing note.
pub fn pdf_reading(
    x_name: &str,
    xs: &[f64],
    p: &[f64],
    log_p: &[f64],
    pdf: &AmplitudePdf,
) -> Table {
    let note = format!(
        "modes {:?}, antimodes {:?}, mean amplitude {}",
        pdf.modes, pdf.antimodes, pdf.mean_amplitude
    );
    let mut t = Table::new(&[note], &[x_name, "p", "log_p"]).allow_infinity("log_p");
    for ((&x, &p), &l) in xs.iter().zip(p).zip(log_p) {
        t.row([fixed(x, 6), format!("{p:.6e}"), fixed(l, 6)]);
    }
    t
}

/// The harmonic-balance equivalents (Eq. 5), σ1 and the impact loss rate: `name,value`.
pub fn equivalents_table(th: &Theory) -> Table {
    let e = th.equivalents();
    let mut t = Table::new(&theory_notes(th), &["name", "value"]);
    for (name, v) in [
        ("mu1", e.mu1),
        ("beta1", e.beta1),
        ("omega1", e.omega1),
        ("beta2", e.beta2),
        ("sigma1", th.diffusion()),
        ("loss_rate", th.loss_rate()),
    ] {
        t.row([name.to_string(), num(v)]);
    }
    // a model of the class: the multiplicative noise's b_1 (b = σ1 + b_1A²) and q (m_c ∋ qA)
    if th.model().is_some() {
        t.row([
            "diffusion_b1".to_string(),
            num(th.multiplicative_diffusion()),
        ]);
        t.row([
            "drift_correction_q".to_string(),
            num(th.multiplicative_correction()),
        ]);
    }
    t
}

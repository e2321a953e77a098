//! Figure data read back from a file is checked as a whole before anything is drawn from it:
//! [`crate::Figure::validate`] names the first field that is inconsistent — an array whose
//! length differs from its grid's point count or its edges' bin count, a grid whose range is
//! not finite and increasing, edges that do not increase, a value out of its range. A
//! computed figure passes by construction; a damaged or hand-edited file is refused with the
//! field's path instead of failing (or panicking) somewhere in the drawing.
//!
//! Method: plain shape and range checks; no tolerance, since the data is compared with itself.
//! Test: `trirhythm-cli/tests/malformed.rs` (mutated files are refused or rendered, never a
//! panic) and the unit tests below.

use std::fmt;
use trirhythm::theory::bifurcation::Axis;

/// The first inconsistent field of a figure's data: its path in the JSON (`panels[2].counts`)
/// and what is wrong with it.
#[derive(Debug, Clone, PartialEq)]
pub struct Invalid {
    /// The field's path inside the figure's data.
    pub field: String,
    /// What is wrong, with the values found and expected.
    pub why: String,
}

impl fmt::Display for Invalid {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.field, self.why)
    }
}

impl std::error::Error for Invalid {}

/// The result of a check.
pub type Valid = std::result::Result<(), Invalid>;

/// Refuse `field` with `why`.
pub fn invalid(field: impl Into<String>, why: impl Into<String>) -> Valid {
    Err(Invalid {
        field: field.into(),
        why: why.into(),
    })
}

/// A grid axis: finite start < stop (their difference finite too), at least two points (and no more than a plane holds).
pub fn axis(field: &str, a: &Axis) -> Valid {
    if !(a.start.is_finite() && a.stop.is_finite() && (a.stop - a.start).is_finite()) {
        return invalid(
            field,
            format!("range {} to {} is not finite", a.start, a.stop),
        );
    }
    if a.start >= a.stop {
        return invalid(
            field,
            format!("start {} is not below stop {}", a.start, a.stop),
        );
    }
    let max = trirhythm::theory::bifurcation::MAX_PLANE_POINTS / 2;
    if !(2..=max).contains(&a.count) {
        return invalid(
            format!("{field}.count"),
            format!("{} points, not in [2, {max}]", a.count),
        );
    }
    Ok(())
}

/// An array of `len` elements where `expected` are needed.
pub fn len(field: &str, len: usize, expected: usize, of: &str) -> Valid {
    if len != expected {
        return invalid(field, format!("{len} values, not {expected} ({of})"));
    }
    Ok(())
}

/// Every value finite.
pub fn finite(field: &str, values: &[f64]) -> Valid {
    match values.iter().position(|v| !v.is_finite()) {
        Some(i) => invalid(
            format!("{field}[{i}]"),
            format!("{} is not finite", values[i]),
        ),
        None => Ok(()),
    }
}

/// Every value finite and ≥ 0 (a density, a count, a probability mass).
pub fn non_negative(field: &str, values: &[f64]) -> Valid {
    finite(field, values)?;
    match values.iter().position(|v| *v < 0.0) {
        Some(i) => invalid(
            format!("{field}[{i}]"),
            format!("{} is negative", values[i]),
        ),
        None => Ok(()),
    }
}

/// Bin edges: at least two, finite, strictly increasing.
pub fn edges(field: &str, values: &[f64]) -> Valid {
    if values.len() < 2 {
        return invalid(field, format!("{} edges, at least 2 needed", values.len()));
    }
    finite(field, values)?;
    match values.windows(2).position(|w| w[1] <= w[0]) {
        Some(i) => invalid(
            format!("{field}[{}]", i + 1),
            format!("{} does not exceed {}", values[i + 1], values[i]),
        ),
        None => Ok(()),
    }
}

/// Points (x, y) of a curve: both coordinates finite.
pub fn points(field: &str, pts: &[(f64, f64)]) -> Valid {
    match pts
        .iter()
        .position(|(x, y)| !(x.is_finite() && y.is_finite()))
    {
        Some(i) => invalid(
            format!("{field}[{i}]"),
            format!("({}, {}) is not finite", pts[i].0, pts[i].1),
        ),
        None => Ok(()),
    }
}

/// Points (x, y) of a curve whose values may be a limit (±∞) but never NaN, at finite x.
pub fn limits(field: &str, pts: &[(f64, f64)]) -> Valid {
    match pts.iter().position(|(x, y)| !x.is_finite() || y.is_nan()) {
        Some(i) => invalid(
            format!("{field}[{i}]"),
            format!(
                "({}, {}): x must be finite and y a number",
                pts[i].0, pts[i].1
            ),
        ),
        None => Ok(()),
    }
}

/// A range (lo, hi) of an axis: finite, lo < hi.
pub fn range(field: &str, (lo, hi): (f64, f64)) -> Valid {
    if !(lo.is_finite() && hi.is_finite() && lo < hi) {
        return invalid(
            field,
            format!("({lo}, {hi}) is not a finite increasing range"),
        );
    }
    Ok(())
}

/// A fraction in [0, 1].
pub fn fraction(field: &str, value: f64) -> Valid {
    if !(0.0..=1.0).contains(&value) {
        return invalid(field, format!("{value} is not in [0, 1]"));
    }
    Ok(())
}

/// A `rows` × `cols` matrix of finite values ≥ 0 (a density on cells).
pub fn density_matrix(field: &str, m: &[Vec<f64>], rows: usize, cols: usize, of: &str) -> Valid {
    len(field, m.len(), rows, of)?;
    for (i, row) in m.iter().enumerate() {
        let f = format!("{field}[{i}]");
        len(&f, row.len(), cols, of)?;
        non_negative(&f, row)?;
    }
    Ok(())
}

/// A finite scalar.
pub fn scalar(field: &str, v: f64) -> Valid {
    if !v.is_finite() {
        return invalid(field, format!("{v} is not finite"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_axis_must_increase_and_hold_two_points() {
        let good = Axis::new("lambda", 0.0, 1.0, 3).unwrap();
        assert!(axis("x", &good).is_ok());
        let mut down = good.clone();
        (down.start, down.stop) = (1.0, 0.0);
        assert_eq!(axis("x", &down).unwrap_err().field, "x");
        let mut one = good.clone();
        one.count = 1;
        assert_eq!(axis("x", &one).unwrap_err().field, "x.count");
        let mut inf = good;
        inf.stop = f64::INFINITY;
        assert!(axis("x", &inf).is_err());
    }

    #[test]
    fn edges_must_increase_and_lengths_match() {
        assert!(edges("e", &[0.0, 1.0, 2.0]).is_ok());
        assert_eq!(edges("e", &[0.0, 2.0, 1.0]).unwrap_err().field, "e[2]");
        assert!(edges("e", &[0.0]).is_err());
        assert!(len("c", 3, 4, "x by y").is_err());
        assert_eq!(non_negative("d", &[0.0, -1.0]).unwrap_err().field, "d[1]");
        assert_eq!(finite("d", &[0.0, f64::NAN]).unwrap_err().field, "d[1]");
    }
}

//! The polynomial μP of the damping, evaluated on the step's critical path.

/// A polynomial Σ a_k x^k: up to degree 7 evaluated by Estrin's scheme (three levels of
/// independent multiply–adds instead of Horner's chain of seven: it is on the step's critical
/// path twice), beyond that by Horner.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Polynomial {
    Short([f64; 8]),
    Long(Vec<f64>),
}

impl Polynomial {
    /// μ·(c_0, c_1, …).
    pub(super) fn scaled(mu: f64, c: &[f64]) -> Self {
        Self::from_coefficients(c.iter().map(|&c| mu * c).collect())
    }

    pub(super) fn from_coefficients(a: Vec<f64>) -> Self {
        if a.len() <= 8 {
            let mut s = [0.0; 8];
            s[..a.len()].copy_from_slice(&a);
            Polynomial::Short(s)
        } else {
            Polynomial::Long(a)
        }
    }

    #[inline]
    pub(super) fn eval(&self, x: f64) -> f64 {
        match self {
            Polynomial::Short(c) => {
                let x2 = x * x;
                let x4 = x2 * x2;
                let p01 = c[0] + c[1] * x;
                let p23 = c[2] + c[3] * x;
                let p45 = c[4] + c[5] * x;
                let p67 = c[6] + c[7] * x;
                (p01 + p23 * x2) + (p45 + p67 * x2) * x4
            }
            Polynomial::Long(c) => c.iter().rev().fold(0.0, |acc, &c| acc * x + c),
        }
    }

    /// [`Polynomial::eval`] at L points: the same operations in the same order for each, so
    /// the same bits, in loops the compiler vectorises across the points.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)]
    pub(super) fn eval_lanes<const L: usize>(&self, x: &[f64; L]) -> [f64; L] {
        let mut out = [0.0; L];
        match self {
            Polynomial::Short(c) => {
                for i in 0..L {
                    let x = x[i];
                    let x2 = x * x;
                    let x4 = x2 * x2;
                    let p01 = c[0] + c[1] * x;
                    let p23 = c[2] + c[3] * x;
                    let p45 = c[4] + c[5] * x;
                    let p67 = c[6] + c[7] * x;
                    out[i] = (p01 + p23 * x2) + (p45 + p67 * x2) * x4;
                }
            }
            Polynomial::Long(c) => {
                for &c in c.iter().rev() {
                    for i in 0..L {
                        out[i] = out[i] * x[i] + c;
                    }
                }
            }
        }
        out
    }

    /// The derivative Σ k a_k x^{k−1}.
    pub(super) fn derivative(&self) -> Self {
        let a: &[f64] = match self {
            Polynomial::Short(c) => c,
            Polynomial::Long(c) => c,
        };
        Self::from_coefficients(
            a.iter()
                .enumerate()
                .skip(1)
                .map(|(k, &c)| k as f64 * c)
                .collect(),
        )
    }
}

/// The polynomials of L lanes side by side, coefficient k of lane i at `[k][i]`: lanes of
/// different problems stepped together (module docs of `lanes`). Each lane's evaluation is
/// [`Polynomial::eval`]'s, the same operations in the same order, so the same bits.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum LanePolynomial<const L: usize> {
    Short([[f64; L]; 8]),
    Long(Vec<[f64; L]>),
}

impl<const L: usize> LanePolynomial<L> {
    /// The polynomials `p` (at most L; the lanes beyond take the first's) side by side, or
    /// None when they are not all of one form (all short, or all long of one length): their
    /// evaluations would not be the same operations.
    #[allow(clippy::needless_range_loop)]
    pub(super) fn new(p: &[&Polynomial]) -> Option<Self> {
        let first = *p.first()?;
        let lane = |i: usize| *p.get(i).unwrap_or(&first);
        match first {
            Polynomial::Short(_) => {
                let mut c = [[0.0; L]; 8];
                for i in 0..L {
                    let Polynomial::Short(a) = lane(i) else {
                        return None;
                    };
                    for k in 0..8 {
                        c[k][i] = a[k];
                    }
                }
                Some(LanePolynomial::Short(c))
            }
            Polynomial::Long(a0) => {
                let mut c = vec![[0.0; L]; a0.len()];
                for i in 0..L {
                    match lane(i) {
                        Polynomial::Long(a) if a.len() == a0.len() => {
                            for (k, &a) in a.iter().enumerate() {
                                c[k][i] = a;
                            }
                        }
                        _ => return None,
                    }
                }
                Some(LanePolynomial::Long(c))
            }
        }
    }

    /// Lane i's polynomial at x[i], for every lane.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)]
    pub(super) fn eval_lanes(&self, x: &[f64; L]) -> [f64; L] {
        let mut out = [0.0; L];
        match self {
            LanePolynomial::Short(c) => {
                for i in 0..L {
                    let x = x[i];
                    let x2 = x * x;
                    let x4 = x2 * x2;
                    let p01 = c[0][i] + c[1][i] * x;
                    let p23 = c[2][i] + c[3][i] * x;
                    let p45 = c[4][i] + c[5][i] * x;
                    let p67 = c[6][i] + c[7][i] * x;
                    out[i] = (p01 + p23 * x2) + (p45 + p67 * x2) * x4;
                }
            }
            LanePolynomial::Long(c) => {
                for c in c.iter().rev() {
                    for i in 0..L {
                        out[i] = out[i] * x[i] + c[i];
                    }
                }
            }
        }
        out
    }
}

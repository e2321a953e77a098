//! An impulse of the forcing η put into a path between two steps: the hook of the phase
//! response ([`crate::analysis::lyapunov::phase`]).
//!
//! # Equation
//! A Dirac impulse m·δ(t − t_n) of η adds γm·δ(t − t_n) to g, so V = V₀ + J^λ g gains
//! γm·(t − t_n)^{λ−1}/Γ(λ): the fractional response to a kick, a velocity jump γm at λ = 1.
//!
//! # Method
//! The memory holds g as linear pieces, so the impulse is put into the next step's piece as a
//! hat: g at the step's left node gains 2γm/Δt, falling linearly to nothing at its right node
//! (mass γm, centre t_n + Δt/3). The step, its predictor, its impact handling and the memory
//! then treat it exactly like forcing of that shape; it tends to the Dirac impulse as Δt → 0.
//! Only g at the node (`drift`) changes; it is recomputed at the end of the step.
//!
//! # Reference
//! The phase response by small kicks: Winfree, *The Geometry of Biological Time* (2001), ch. 2.
//!
//! # Tests
//! The unit test below: at λ = 1 with μ0 = 1e-9 (no damping to speak of) and without the wall the pulse of mass m
//! changes V by m (to O(Δt)) and the energy as the kick predicts.

use super::Stepper;

impl Stepper {
    /// Put an impulse of mass `mass` of η into the next step (module docs); refused (false,
    /// nothing changed) while the path is stuck at the wall or for a mass that is not finite.
    pub(crate) fn pulse(&mut self, mass: f64) -> bool {
        if self.stuck || !mass.is_finite() {
            return false;
        }
        self.drift += self.rhs.forcing(2.0 * mass / self.h, self.side);
        true
    }
}

#[cfg(test)]
mod tests {
    use crate::engine::{Barrier, PredictorCorrector, Problem, Stepper};
    use crate::model::preset;

    #[test]
    fn a_pulse_at_lambda_one_is_a_velocity_kick() {
        let params = preset("fig1").unwrap().params;
        let params = params
            .with("lambda", 1.0)
            .unwrap()
            .with("mu0", 1e-9)
            .unwrap();
        let params = params.with("D", 0.0).unwrap().with("omega0", 1.0).unwrap();
        let problem = Problem::from_params(&params)
            .unwrap()
            .with_barrier(Barrier::Off)
            .unwrap()
            .with_start(1.0, 0.0)
            .unwrap();
        let method = PredictorCorrector {
            dt: 1e-3,
            ..Default::default()
        };
        let mut a = Stepper::new(&problem, &method, (1, 0), 10.0).unwrap();
        for _ in 0..500 {
            a.step().unwrap();
        }
        let mut b = a.clone();
        let m = 1e-3;
        assert!(b.pulse(m));
        // harmonic oscillator U'' = −U: the energy (U² + V²)/2 changes by V·m + m²/2
        let energy = |s: &Stepper| 0.5 * (s.u() * s.u() + s.v() * s.v());
        let expected = energy(&a) + a.v() * m + 0.5 * m * m;
        for _ in 0..1000 {
            a.step().unwrap();
            b.step().unwrap();
        }
        assert!(
            (energy(&b) - expected).abs() < 1e-3 * m,
            "{}",
            energy(&b) - expected
        );
        assert!(!b.pulse(f64::NAN));
    }
}

//! The integer-order companions: Eq. (5) at λ = 1 is Eq. (1); Zhuravlev's Eq. (9) maps onto the
//! impacting Eq. (5) through U = |Z| (exact for integer order), for r = 1 and r < 1, with noise.

use trirhythm::engine::*;
use trirhythm::model::preset;

#[test]
fn equivalent_at_lambda_one_is_the_system_itself() {
    let mut p = preset("fig1").unwrap().params;
    p.lambda = 1.0;
    p.mu0 = 0.05;
    p.restitution = 0.9;
    let run = |system| {
        let problem = Problem::from_params(&p)
            .and_then(|q| q.with_system(system))
            .and_then(|q| q.with_start(3.0, 0.0))
            .unwrap();
        let o = Options {
            t_end: 50.0,
            ..Default::default()
        };
        simulate(&problem, &PredictorCorrector::default(), &o).unwrap()
    };
    let a = run(System::Fractional);
    let b = run(System::Equivalent);
    assert_eq!(a.impacts, b.impacts);
    let du =
        a.u.iter()
            .zip(&b.u)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
    assert!(du < 1e-12, "{du}");
}

#[test]
fn zhuravlev_form_maps_onto_the_impacting_equivalent() {
    for (r, d) in [(1.0, 0.0), (0.9, 0.0), (0.95, 0.05)] {
        let mut p = preset("fig11").unwrap().params;
        p.restitution = r;
        p.noise_intensity = d;
        let dt = 0.001;
        let run = |system| {
            let problem = Problem::from_params(&p)
                .and_then(|q| q.with_system(system))
                .and_then(|q| q.with_start(2.0, 0.5))
                .unwrap();
            let o = Options {
                t_end: 30.0,
                seed: 5,
                record_every: 100,
                ..Default::default()
            };
            let m = PredictorCorrector {
                dt,
                ..Default::default()
            };
            simulate(&problem, &m, &o).unwrap()
        };
        let u = run(System::Equivalent);
        let z = run(System::Zhuravlev);
        assert_eq!(u.impacts, z.impacts, "r = {r}");
        assert!(u.impacts > 5);
        for i in 0..u.u.len() {
            let (a, b) = (u.u[i], z.u[i].abs());
            // both second order; the noise is the same path (same seed, same steps)
            assert!(
                (a - b).abs() < 1e-4,
                "r = {r}, t = {}: U = {a}, |Z| = {b}",
                u.t[i]
            );
            let (va, vb) = (u.v[i], z.v[i] * z.u[i].signum());
            assert!(
                (va - vb).abs() < 1e-3,
                "r = {r}, t = {}: V = {va}, Ż sgn Z = {vb}",
                u.t[i]
            );
        }
    }
}

//! Invariants checked on a sweep of pseudo-random linear systems (sizes 1–6, SPD M and K).

use faer::Mat;
use integrate::structural::{LinearStructure, StructuralMethod, StructuralStepper};

/// Small deterministic generator (64-bit LCG, Knuth's MMIX constants), uniform in [−1, 1).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    /// `BᵀB + shift·I` with random `B`: symmetric positive definite.
    fn spd(&mut self, n: usize, shift: f64) -> Mat<f64> {
        let b = Mat::from_fn(n, n, |_, _| self.next());
        Mat::from_fn(n, n, |i, j| {
            (0..n).map(|k| b[(k, i)] * b[(k, j)]).sum::<f64>() + if i == j { shift } else { 0.0 }
        })
    }
    fn vector(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.next()).collect()
    }
}

fn quadratic(a: &Mat<f64>, x: &[f64]) -> f64 {
    let n = x.len();
    (0..n)
        .map(|i| (0..n).map(|j| x[i] * a[(i, j)] * x[j]).sum::<f64>())
        .sum()
}

type Free = LinearStructure<fn(f64, &mut [f64])>;

fn random_system(rng: &mut Lcg, n: usize) -> (Free, Mat<f64>, Mat<f64>) {
    fn no_load(_: f64, f: &mut [f64]) {
        f.fill(0.0);
    }
    let (m, k) = (rng.spd(n, 0.5), rng.spd(n, 0.1));
    let system = LinearStructure::new(m.clone(), None, k.clone(), no_load as fn(f64, &mut [f64]));
    (system.unwrap(), m, k)
}

#[test]
fn trapezoidal_rule_conserves_energy_of_random_systems() {
    // Newmark (β = ¼, γ = ½) conserves ½vᵀMv + ½qᵀKq exactly for any SPD M, K and any Δt;
    // 500 steps accumulate round-off only (bound 1e-11 relative, as in structural_energy).
    let mut rng = Lcg(7);
    for n in 1..=6 {
        for _ in 0..3 {
            let (mut p, m, k) = random_system(&mut rng, n);
            let (q0, v0) = (rng.vector(n), rng.vector(n));
            let e0 = 0.5 * (quadratic(&m, &v0) + quadratic(&k, &q0));
            let method = StructuralMethod::average_acceleration();
            let mut s = StructuralStepper::new(method, &mut p, 0.0, &q0, &v0).unwrap();
            for _ in 0..500 {
                s.step(&mut p, 0.7).unwrap();
            }
            let e = 0.5 * (quadratic(&m, s.v()) + quadratic(&k, s.q()));
            assert!(
                (e / e0 - 1.0).abs() < 1e-11,
                "n = {n}: E/E0 − 1 = {:e}",
                e / e0 - 1.0
            );
        }
    }
}

#[test]
fn backward_euler_energy_loss_is_the_closed_form() {
    // From q_{n+1} − q_n = Δt v_{n+1} and M(v_{n+1} − v_n) = −Δt K q_{n+1}:
    // E_{n+1} − E_n = −½ΔvᵀMΔv − ½ΔqᵀKΔq exactly (so backward Euler always dissipates).
    // Checked per step to round-off: 1e-12 of E_n.
    let mut rng = Lcg(11);
    for n in 1..=6 {
        let (mut p, m, k) = random_system(&mut rng, n);
        let (q0, v0) = (rng.vector(n), rng.vector(n));
        let mut s =
            StructuralStepper::new(StructuralMethod::BackwardEuler, &mut p, 0.0, &q0, &v0).unwrap();
        for _ in 0..100 {
            let (q_old, v_old) = (s.q().to_vec(), s.v().to_vec());
            let e_old = 0.5 * (quadratic(&m, &v_old) + quadratic(&k, &q_old));
            s.step(&mut p, 0.3).unwrap();
            let e_new = 0.5 * (quadratic(&m, s.v()) + quadratic(&k, s.q()));
            let dq: Vec<f64> = s.q().iter().zip(&q_old).map(|(a, b)| a - b).collect();
            let dv: Vec<f64> = s.v().iter().zip(&v_old).map(|(a, b)| a - b).collect();
            let loss = -0.5 * (quadratic(&m, &dv) + quadratic(&k, &dq));
            assert!(
                (e_new - e_old - loss).abs() <= 1e-12 * e_old,
                "n = {n}: ΔE = {:e}, closed form {loss:e}",
                e_new - e_old
            );
        }
    }
}

#[test]
fn restart_equals_a_fresh_stepper() {
    // Restarting at (t, q, v) recomputes the consistent acceleration, exactly as a new stepper
    // does; the following steps must then be bitwise identical.
    let mut rng = Lcg(3);
    let (mut p, _, _) = random_system(&mut rng, 4);
    let (q0, v0) = (rng.vector(4), rng.vector(4));
    let method = StructuralMethod::hht(-0.2).unwrap();
    let mut a = StructuralStepper::new(method, &mut p, 0.0, &q0, &v0).unwrap();
    for _ in 0..20 {
        a.step(&mut p, 0.1).unwrap();
    }
    let (t, q, v) = (a.t(), a.q().to_vec(), a.v().to_vec());
    a.restart(&mut p, t, &q, &v).unwrap();
    let mut b = StructuralStepper::new(method, &mut p, t, &q, &v).unwrap();
    assert_eq!(a.a(), b.a());
    for _ in 0..20 {
        a.step(&mut p, 0.1).unwrap();
        b.step(&mut p, 0.1).unwrap();
        assert_eq!((a.q(), a.v()), (b.q(), b.v()));
    }
    assert!(a.restart(&mut p, f64::NAN, &q, &v).is_err());
}

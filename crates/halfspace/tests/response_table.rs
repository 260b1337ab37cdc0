//! The shared response table F(δ) of the boundary-element law (issue #14,
//! `halfspace::law::ResponseTable`) against exact solves at the query approach.

use std::sync::Arc;

use halfspace::law::{BemLaw, BemOptions, ContactLaw, ResponseTable, SharedTable, TABLE_STREAK};
use halfspace::{Material, NormalLoad, NormalSolver, SolverOptions};

/// The Manchester wheelset's static wheel load \[N\] and the grid's design force (2.5 ×).
const LOAD: f64 = 109_092.105;
const TOL: f64 = 3e-6;

fn law(reuse_tol: f64) -> BemLaw {
    let material = Material::identical(210e9, 0.3).unwrap();
    let options = BemOptions {
        reuse_tol,
        memoize: false,
        ..BemOptions::default()
    };
    BemLaw::wheel_on_rail(0.46, 0.3, material, 32, 2.5 * LOAD, options).unwrap()
}

fn exact_solver(law: &BemLaw) -> NormalSolver {
    NormalSolver::new(*law.grid(), Material::identical(210e9, 0.3).unwrap()).unwrap()
}

fn exact_options() -> SolverOptions {
    SolverOptions {
        tol: 1e-13,
        max_iter: 5000,
        sensitivity: false,
        ..SolverOptions::default()
    }
}

/// Every answer's force error against a solve at the query δ (NormCG to 1e-13, an
/// independent solve at a δ that is no node) is within the answer's estimate, every estimate
/// is within the tolerance, and the table answers most of its force range.
#[test]
fn table_forces_are_within_their_estimates() {
    let law = law(TOL);
    let start = std::time::Instant::now();
    let table = ResponseTable::build(
        *law.grid(),
        Material::identical(210e9, 0.3).unwrap(),
        law.base_gap(),
        2.5 * LOAD,
        TOL,
    )
    .unwrap();
    let built = start.elapsed();
    let mut solver = exact_solver(&law);
    let (d_lo, d_hi) = table.range();
    let n = 400;
    let (mut answered, mut worst_ratio, mut worst_error) = (0, 0.0f64, 0.0f64);
    let mut column_force = vec![0.0; law.grid().nx];
    let mut pressure = vec![0.0; law.grid().len()];
    for q in 0..n {
        // Irrational offsets: no query falls on a node.
        let theta = ((q as f64 + 0.5) / n as f64 + 0.618_033_988_7 * 1e-3).min(0.999_999);
        let delta = d_lo + theta * (d_hi - d_lo);
        let Some(a) = table.answer(delta, &mut column_force, &mut pressure) else {
            continue;
        };
        answered += 1;
        let exact = solver
            .solve(
                law.base_gap(),
                NormalLoad::Approach(delta),
                &exact_options(),
            )
            .unwrap();
        let error = (a.force - exact.normal_force).abs() / exact.normal_force;
        assert!(
            a.estimate <= TOL,
            "estimate {} > tol at δ = {delta}",
            a.estimate
        );
        assert!(
            error <= a.estimate,
            "error {error:e} > estimate {:e} at δ = {delta}",
            a.estimate
        );
        let column_sum: f64 = column_force.iter().sum();
        assert!((column_sum - a.force).abs() <= 1e-9 * a.force);
        worst_ratio = worst_ratio.max(error / a.estimate);
        worst_error = worst_error.max(error);
    }
    // The force at the first queries is below the table's 5 % of the design force.
    let covered = answered as f64 / n as f64;
    println!(
        "{} nodes, {} solves, built in {:.3} s; {answered}/{n} answered; worst error {worst_error:e}, \
         worst error/estimate {worst_ratio:.3}",
        table.len(),
        table.solves(),
        built.as_secs_f64()
    );
    assert!(covered >= 0.8, "only {covered} of the queries answered");
}

/// A law with the shared table answers evaluations without column corrections from it once
/// it has seen [`TABLE_STREAK`] of them in a row, and one with corrections by its own solve;
/// with `reuse_tol = 0` the table is not used and the law's answers equal those of a law
/// without it bit for bit.
#[test]
fn law_uses_the_table_only_for_the_base_gap() {
    let shared = Arc::new(SharedTable::new(2.5 * LOAD, TOL));
    let mut with = law(TOL);
    with.share_table(shared.clone());
    let delta = with.clone_static_approach(LOAD);
    let nx = with.grid().nx;
    let mut cf = vec![0.0; nx];
    for _ in 1..TABLE_STREAK {
        with.evaluate(delta, &[], &mut cf, true).unwrap();
    }
    assert_eq!(with.reuse_stats().unwrap().table_answers, 0);
    assert!(shared.built().is_none());
    let out = with.evaluate(delta, &[], &mut cf, true).unwrap();
    let stats = with.reuse_stats().unwrap();
    assert_eq!(stats.table_answers, 1);
    assert!(shared.built().is_some());
    assert!((out.force / LOAD - 1.0).abs() < 1e-5, "{}", out.force);
    // A tilt of the gap: solved.
    let tilt: Vec<f64> = with.columns().iter().map(|x| 1e-4 * x).collect();
    with.evaluate(delta, &tilt, &mut cf, true).unwrap();
    assert_eq!(with.reuse_stats().unwrap().table_answers, 1);

    let mut exact_a = law(0.0);
    let mut exact_b = law(0.0);
    exact_b.share_table(Arc::new(SharedTable::new(2.5 * LOAD, TOL)));
    for k in 0..20 {
        let d = delta * (0.8 + 0.02 * k as f64);
        let a = exact_a.evaluate(d, &[], &mut cf, k % 3 == 0).unwrap();
        let b = exact_b.evaluate(d, &[], &mut cf, k % 3 == 0).unwrap();
        assert_eq!(a, b);
    }
    assert!(exact_b.table().is_none());
}

trait StaticApproach {
    fn clone_static_approach(&mut self, force: f64) -> f64;
}

impl StaticApproach for BemLaw {
    fn clone_static_approach(&mut self, force: f64) -> f64 {
        self.static_approach(force).unwrap()
    }
}

//! The bounded force floor of the sweep's passages (`Simulation::bound_force_floor`, issue
//! #12 performance): the coupled iteration compares its force changes with max(tol, floor)
//! and 16 × floor only, so a floor bounded below tol/32 must take every decision the exact
//! floor takes. Checked on whole HSLM-A10 passages (an articulated rake, the power cars
//! detached off the span, and at 110 m/s wheels losing contact and landing again) against the
//! exact floor: every step's state, velocity, acceleration and wheel forces identical bit for
//! bit, the same iteration counts, and the bound actually used in most steps.

mod support;

use support::sweep_config;

/// Every step's (state, velocity, acceleration, wheel forces and approaches) as bits.
type Trace = Vec<Vec<u64>>;

fn passage(speed: f64, bound: bool) -> (Trace, usize, u64, u64) {
    let c = sweep_config(&format!(
        "kind = \"sweep\"\n[bridge]\nlength = 20.0\nEI = 1.9452e10\nmass_per_length = 12000.0\nsupports = \"simply_supported\"\nmodes = 3\ndamping_ratio = 0.01\n[trains]\nnames = [\"HSLM-A10\"]\nmodel = \"interaction\"\n[contact]\nmodel = \"hertz\"\n[speeds]\nlist = [{speed}]\n"
    ));
    let sim::sweep::SweepModel::Interaction(model) = &c.spec.model else {
        panic!("interaction");
    };
    let mut sim = sim::sweep::interaction::passage_simulation(model, 0, speed).unwrap();
    sim.bound_force_floor(bound);
    let mut trace = Vec::new();
    let summary = sim
        .run(|s| {
            let mut bits: Vec<u64> = s
                .state()
                .iter()
                .chain(s.velocity())
                .chain(s.acceleration())
                .map(|v| v.to_bits())
                .collect();
            for w in s.wheels() {
                bits.push(w.contact.force.to_bits());
                bits.push(w.approach.to_bits());
            }
            trace.push(bits);
        })
        .unwrap();
    (
        trace,
        summary.solver.iterations,
        sim.bounded_force_floors(),
        summary.solver.steps as u64,
    )
}

#[test]
fn the_bounded_floor_decides_as_the_exact_floor() {
    for speed in [100.0, 110.0] {
        let (exact, iterations, none, _) = passage(speed, false);
        let (bounded, bounded_iterations, used, steps) = passage(speed, true);
        assert_eq!(none, 0);
        assert_eq!(exact.len(), bounded.len(), "{speed} m/s: steps");
        let first = exact.iter().zip(&bounded).position(|(a, b)| a != b);
        assert!(
            first.is_none(),
            "{speed} m/s: the runs differ from step {first:?}"
        );
        assert_eq!(iterations, bounded_iterations, "{speed} m/s: iterations");
        println!(
            "HSLM-A10 at {speed} m/s: {steps} steps identical, {iterations} iterations, floor bounded in {used} steps"
        );
        // The bound serves most steps (else it is only overhead).
        assert!(
            used as f64 > 0.9 * steps as f64,
            "{speed} m/s: {used} of {steps}"
        );
    }
}

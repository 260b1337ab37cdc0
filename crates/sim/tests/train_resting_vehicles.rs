//! Vehicles held out of the coupled step: at rest ahead of the span (module
//! `vehicle_bridge::resting`) and solved on their own off the span (module
//! `vehicle_bridge::detached`). The whole crossing with each equals the full coupled step, in
//! which every vehicle takes part in every step (the reference).

mod support;

use sim::vehicle_bridge::Simulation;
use support::{relative_difference, simulation};

const BRIDGE: &str = "[bridge]\nlength = 25.0\nEI = 8.323e9\nmass_per_length = 2303.0\nsupports = \"simply_supported\"\nmodes = 20\ndamping_ratio = 0.02\n";
const CAR: &str = "type = \"bogie_vehicle\"\nlength = 25.0\nbody_mass = 32000.0\nbody_pitch_inertia = 1.97e6\nbogie_spacing = 19.0\nbogie_mass = 2615.0\nbogie_pitch_inertia = 1476.0\nwheelbase = 2.56\nwheelset_mass = 1813.0\nprimary_stiffness = 2.4e6\nprimary_damping = 8.0e3\nsecondary_stiffness = 8.6e5\nsecondary_damping = 4.0e4\n";

/// The crossing of `cars` Manchester cars (references.md §T4) at 300 km/h, leading axle at
/// the span's entry, with `extra` appended (an irregularity table).
fn crossing(cars: usize, extra: &str) -> String {
    format!(
        "kind = \"vehicle_bridge\"\n{BRIDGE}[train]\nspeed = 83.333\nposition = 0.0\n[[train.vehicles]]\ncount = {cars}\n{CAR}[contact]\nmodel = \"hertz\"\n[integrator]\nmethod = \"generalized_alpha\"\ndt = 1e-4\n{extra}"
    )
}

/// Per step: the whole state (bridge modes and every vehicle DOF), the accelerations, and
/// every wheel's contact force and approach.
struct History {
    state: Vec<Vec<f64>>,
    acceleration: Vec<Vec<f64>>,
    force: Vec<Vec<f64>>,
    approach: Vec<Vec<f64>>,
}

fn history(mut sim: Simulation) -> (History, u64, u64) {
    let mut h = History {
        state: Vec::new(),
        acceleration: Vec::new(),
        force: Vec::new(),
        approach: Vec::new(),
    };
    sim.run(|s| {
        h.state.push(s.state().to_vec());
        h.acceleration.push(s.acceleration().to_vec());
        h.force
            .push(s.wheels().iter().map(|w| w.contact.force).collect());
        h.approach
            .push(s.wheels().iter().map(|w| w.approach).collect());
    })
    .unwrap();
    (h, sim.held_vehicle_steps(), sim.detached_vehicle_steps())
}

/// Runs `text` with and without the hold and checks the held run against the full step: the
/// largest difference of each history relative to its largest magnitude, and the number of
/// vehicle-steps held against `expected_held` (±1 step per vehicle).
///
/// Tolerances: the static start balances each vehicle to round-off of its matrices, and the
/// full step lets that imbalance move a vehicle at rest (a body acceleration of about 1e-9
/// m/s², 4e-11 m of body displacement in 0.3 s), while a held vehicle stays exactly static;
/// that difference, carried through the stiff Hertz contact (1.5e9 N/m) once the vehicle
/// runs, is 1e-9 of the largest force. A vehicle held while the span or a dip reaches it would
/// miss that whole response.
fn compare(text: &str, expected_held: &[usize]) {
    let mut held_sim = simulation(text);
    held_sim.solve_detached_vehicles(false);
    // Every wheel's v fixed within a step attempt, as the coupled step declares.
    held_sim.verify_declared_geometry(true);
    let (held, held_steps, _) = history(held_sim);
    let mut full_sim = simulation(text);
    full_sim.hold_resting_vehicles(false);
    full_sim.solve_detached_vehicles(false);
    let (full, none, detached) = history(full_sim);
    assert_eq!((none, detached), (0, 0));
    let expected: usize = expected_held.iter().sum();
    assert!(
        (held_steps as f64 - expected as f64).abs() <= expected_held.len() as f64,
        "held {held_steps} vehicle-steps, expected {expected}"
    );
    for (name, a, b, tol) in [
        ("state", &held.state, &full.state, 1e-9),
        ("acceleration", &held.acceleration, &full.acceleration, 1e-8),
        ("force", &held.force, &full.force, 1e-8),
        ("approach", &held.approach, &full.approach, 1e-8),
    ] {
        let d = relative_difference(a, b);
        println!("{name}: relative difference {d:e} (held vehicle-steps {held_steps})");
        assert!(d <= tol, "{name}: {d:e} > {tol:e}");
    }
}

/// Steps of Δt = 1e-4 s until the leading axle of car `i` (25 m apart, the train's leading
/// axle at `start` at t = 0, 83.333 m/s) passes `x`; the first step attempt evaluates every
/// vehicle, so one less is held.
fn steps_until(i: usize, start: f64, x: f64) -> usize {
    let t = (x - (start - 25.0 * i as f64)) / 83.333;
    (t / 1e-4).ceil() as usize - 1
}

#[test]
fn held_vehicles_equal_the_full_step() {
    // Cars 1–3 wait on the approach until their leading axle reaches the span.
    let expected: Vec<usize> = (1..4).map(|i| steps_until(i, 0.0, 0.0)).collect();
    compare(&crossing(4, ""), &expected);
}

#[test]
fn an_irregularity_on_the_approach_releases_the_vehicles_that_reach_it() {
    // A rail dip 10–14 m ahead of the span: each car runs from the step its leading axle
    // meets it (the dip, 0.5 mm deep, is stepped in full).
    let dip = "[irregularity]\nkind = \"dip\"\nposition = -14.0\nlength = 4.0\ndepth = 5e-4\n";
    let expected: Vec<usize> = (1..4).map(|i| steps_until(i, 0.0, -14.0)).collect();
    compare(&crossing(4, dip), &expected);
}

#[test]
fn detached_vehicles_equal_the_coupled_step() {
    // The crossing of four cars with the hold at rest on in both runs; the detached solve on
    // in one. A detached car iterates until its own forces have converged (coupling.tol =
    // 1e-10 of the static wheel load, or the forces' floating-point floor) instead of until all
    // wheels have, so the runs differ at that level: forces and approaches to 1e-8 of their
    // largest value, the state to 1e-9. A car detached while on the span, or a wrong block,
    // would distort the whole response.
    compare_detached(&crossing(4, ""));
}

#[test]
fn detached_vehicles_equal_the_coupled_step_over_a_dip_after_the_span() {
    // A rail dip 40–44 m from the span's entry (15 m after its end): the cars meet it off the
    // span, in the detached solve (the irregularity under the wheels, the extrapolated start
    // and the iteration with changing forces).
    compare_detached(&crossing(
        4,
        "[irregularity]\nkind = \"dip\"\nposition = 40.0\nlength = 4.0\ndepth = 5e-4\n",
    ));
}

/// Runs `text` with and without the detached solve (the hold at rest on in both) and checks
/// the histories (tolerances: `detached_vehicles_equal_the_coupled_step`).
fn compare_detached(text: &str) {
    let (detached, _, detached_steps) = history({
        let mut s = simulation(text);
        s.verify_declared_geometry(true);
        s
    });
    let (coupled, _, none) = history({
        let mut s = simulation(text);
        s.solve_detached_vehicles(false);
        s
    });
    assert_eq!(none, 0);
    // Each car is off the span after its last axle has left it (at 21.56 m behind its leading
    // axle) until the end of the run.
    assert!(detached_steps > 10_000, "{detached_steps}");
    for (name, a, b, tol) in [
        ("state", &detached.state, &coupled.state, 1e-9),
        (
            "acceleration",
            &detached.acceleration,
            &coupled.acceleration,
            1e-8,
        ),
        ("force", &detached.force, &coupled.force, 1e-8),
        ("approach", &detached.approach, &coupled.approach, 1e-8),
    ] {
        let d = relative_difference(a, b);
        println!("{name}: relative difference {d:e} (detached vehicle-steps {detached_steps})");
        assert!(d <= tol, "{name}: {d:e} > {tol:e}");
    }
}

#[test]
fn detached_vehicles_lose_and_regain_contact_as_the_coupled_step() {
    // A 2 mm × 1 m dip 15 m after the span: the wheels of the cars off the span lose contact
    // and land again (Hertz impacts). Such impacts amplify any difference (two runs that differ
    // at round-off can part by 1e-2 of the forces after a few impacts), so the runs are compared
    // by what the impacts produce: the number of loss-of-contact events (equal), the largest
    // contact force and the largest car-body acceleration (to 1e-6; measured 2026-11-27: the
    // force to 1.4e-7 with the detached kernel on the wheels, 1.0e-9 before; the body
    // acceleration equal).
    let text = crossing(
        2,
        "[irregularity]\nkind = \"dip\"\nposition = 40.0\nlength = 1.0\ndepth = 2e-3\n",
    );
    let run = |detach: bool| {
        let mut sim = simulation(&text);
        sim.solve_detached_vehicles(detach);
        let summary = sim.run(|_| {}).unwrap();
        (
            sim.loss_of_contact_events(),
            summary.max_force(),
            summary.max_body_acceleration(),
            sim.detached_vehicle_steps(),
        )
    };
    let (events, force, body, detached_steps) = run(true);
    let (events_ref, force_ref, body_ref, none) = run(false);
    println!(
        "events {events} vs {events_ref}, max force {force:e} vs {force_ref:e}, body {body:e} vs {body_ref:e}, detached {detached_steps}"
    );
    assert_eq!(none, 0);
    assert!(detached_steps > 1000 && events_ref > 0);
    assert_eq!(events, events_ref);
    assert!((force / force_ref - 1.0).abs() < 1e-6);
    assert!((body / body_ref - 1.0).abs() < 1e-6);
}

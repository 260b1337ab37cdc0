//! Moving forces in the coupled model (`vehicle_bridge::moving_forces`): the axles of a
//! `moving_forces` vehicle load the bridge modes without DOFs or contact. Checked against the
//! exact modal solution of the same forces (`beam::simulate_moving_loads`, the exact
//! piecewise-linear-load recurrence; references.md §D1.1) with the convergence order of the
//! structural method, and in a mixed train against the static influence line.

use std::path::Path;

use sim::config::{self, LoadOptions};

const BRIDGE: &str = "[bridge]\nlength = 25.0\nEI = 8.323e9\nmass_per_length = 2303.0\nsupports = \"simply_supported\"\nmodes = 6\ndamping_ratio = 0.02\n";

/// Two axles of 170 kN, 3 m apart, at 60 m/s, and a quarter car 300 m behind them (it never
/// reaches the span during the run, so the bridge feels the forces only).
fn forces_ahead_of_a_car(dt: f64) -> String {
    format!(
        "kind = \"vehicle_bridge\"\n{BRIDGE}[train]\nspeed = 60.0\nposition = 0.0\n[[train.vehicles]]\ntype = \"moving_forces\"\nlength = 300.0\naxle_positions = [0.0, 3.0]\naxle_loads = [1.7e5, 1.7e5]\n[[train.vehicles]]\ntype = \"quarter_car\"\nlength = 10.0\nwheel_mass = 1800.0\nbody_mass = 9000.0\nsuspension_stiffness = 1.0e6\nsuspension_damping = 2.0e4\n[contact]\nmodel = \"hertz\"\n[integrator]\nmethod = \"generalized_alpha\"\ndt = {dt:e}\nduration = 0.6\n"
    )
}

mod support;
use support::simulation;

/// The midspan deflection history (t, w).
fn history(text: &str) -> Vec<(f64, f64)> {
    let mut sim = simulation(text);
    let mut out = vec![(0.0, sim.output_point_response().0)];
    sim.run(|s| out.push((s.t(), s.output_point_response().0)))
        .unwrap();
    out
}

/// The same forces by the exact modal recurrence at the same sample times.
fn exact(dt: f64) -> beam::MovingLoadResponse {
    let text = format!(
        "kind = \"moving_load\"\n{BRIDGE}[load]\nspeed = 60.0\naxles = [[0.0, 1.7e5], [3.0, 1.7e5]]\n"
    );
    support::moving_load_response(&text, dt, 0.6 - 28.0 / 60.0, &[12.5])
}

/// max_t |w(t) − w_exact(t)| / max_t |w_exact| over the common samples.
fn history_error(dt: f64) -> f64 {
    history_error_of(&forces_ahead_of_a_car(dt), dt)
}

fn history_error_of(text: &str, dt: f64) -> f64 {
    let coupled = history(text);
    let reference = exact(dt);
    let peak = reference
        .deflection
        .iter()
        .fold(0.0f64, |m, w| m.max(w.abs()));
    let mut err = 0.0f64;
    let mut compared = 0;
    for (i, &t) in reference.times.iter().enumerate() {
        if let Some(&(_, w)) = coupled.iter().find(|(tc, _)| (tc - t).abs() < 1e-9) {
            err = err.max((w - reference.deflection[i]).abs());
            compared += 1;
        }
    }
    assert!(compared > 1000, "only {compared} common samples");
    err / peak
}

/// Generalized-α is second-order accurate: the error against the exact modal solution must
/// be small at Δt = 1e-4 s (measured 3.3e-6 of the peak; bound 2e-5) and fall by about 4
/// when Δt is halved (measured 3.99; bound 3: second order with a margin).
#[test]
fn moving_forces_match_the_exact_modal_solution_at_second_order() {
    let coarse = history_error(2e-4);
    let fine = history_error(1e-4);
    println!(
        "moving forces vs exact modal solution: {coarse:.3e} (dt 2e-4), {fine:.3e} (dt 1e-4), ratio {:.2}",
        coarse / fine
    );
    assert!(fine < 2e-5, "{fine}");
    assert!(coarse / fine > 3.0, "{coarse} / {fine}");
}

/// Radau5 takes the moving forces in its right-hand side: with its default tolerances its
/// reported history matches the exact modal solution to 1e-3 of the peak (its error control
/// works on the whole state, rtol 1e-6 by default).
#[test]
fn radau5_takes_the_moving_forces_in_its_right_hand_side() {
    let text = forces_ahead_of_a_car(1e-4).replace("generalized_alpha", "radau5");
    let e = history_error_of(&text, 1e-4);
    println!("radau5: {e:.3e}");
    assert!(e < 1e-3, "{e}");
}

/// The quasi-static deflection behind the dynamic amplification includes the moving forces:
/// at every step it equals the closed-form influence line of a simply supported beam,
/// w(L/2) = Σ P a (3L² − 4a²)/(48 EI) (a = distance to the nearer support), to the
/// truncation of six modes (measured 2.1e-3, bound 4e-3: the tail beyond mode 6 is largest
/// for a force near a support, where w_j(a)/w_1(a) ≈ j and the terms fall like 1/j³ only).
#[test]
fn the_quasi_static_deflection_includes_the_moving_forces() {
    let (length, ei, p) = (25.0, 8.323e9, 1.7e5);
    let mut sim = simulation(&forces_ahead_of_a_car(1e-4));
    let mut worst = 0.0f64;
    let mut checked = 0;
    sim.run(|s| {
        let t = s.t();
        let closed: f64 = [0.0, 3.0]
            .iter()
            .map(|offset| 60.0 * t - offset)
            .filter(|x| (0.0..=length).contains(x))
            .map(|x: f64| {
                let a = x.min(length - x);
                p * a * (3.0 * length * length - 4.0 * a * a) / (48.0 * ei)
            })
            .sum();
        if closed > 1e-4 {
            let modal = s.quasi_static_output_deflection().unwrap().unwrap();
            worst = worst.max((modal / closed - 1.0).abs());
            checked += 1;
        }
    })
    .unwrap();
    println!("quasi-static vs influence line: {worst:.3e} over {checked} steps");
    assert!(checked > 1000 && worst < 4e-3, "{worst} over {checked}");
}

/// A train of moving forces only has nothing to couple: refused with the remedy.
#[test]
fn a_train_of_moving_forces_only_is_refused_with_the_remedy() {
    let text = format!(
        "kind = \"vehicle_bridge\"\n{BRIDGE}[train]\nspeed = 60.0\n[[train.vehicles]]\ntype = \"moving_forces\"\nlength = 20.0\naxle_positions = [0.0]\naxle_loads = [1.0e5]\n"
    );
    let e = config::load(&text, Path::new("."), &LoadOptions::default())
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("moving forces only") && e.contains("moving_load"),
        "{e}"
    );
}

/// Moving forces trailing the wheels set the run's length (until the rearmost of them has
/// left the span), and a random irregularity is tabulated over the whole of it: the leading
/// wheel still sees the profile at the end of the run (the table once ended where the last
/// wheel, not the last force, left the span, and beyond it the profile read zero).
#[test]
fn trailing_moving_forces_set_the_run_length_and_the_profile_covers_it() {
    let text = format!(
        "kind = \"vehicle_bridge\"\n{BRIDGE}[train]\nspeed = 60.0\nposition = 0.0\n[[train.vehicles]]\ntype = \"quarter_car\"\nlength = 100.0\nwheel_mass = 1800.0\nbody_mass = 9000.0\nsuspension_stiffness = 1.0e6\nsuspension_damping = 2.0e4\n[[train.vehicles]]\ntype = \"moving_forces\"\nlength = 10.0\naxle_positions = [0.0]\naxle_loads = [1.7e5]\n[irregularity]\nkind = \"random\"\nspectrum = \"german_low\"\nlambda_min = 1.0\nlambda_max = 30.0\ncomponents = 50\nseed = 3\n[contact]\nmodel = \"hertz\"\n"
    );
    let sim = simulation(&text);
    // The force starts 100 m behind the wheel: the run ends when it leaves the 25 m span.
    let end = sim.end_time();
    assert!((end - 125.0 / 60.0).abs() < 1e-12, "{end}");
    // Where the wheel is at the end: the profile is still there (a random profile is zero
    // only at isolated points; check a short stretch).
    let x_end = 60.0 * end;
    let largest = (0..20)
        .map(|i| {
            sim.scenario()
                .irregularity
                .height(x_end - 0.05 * i as f64)
                .abs()
        })
        .fold(0.0f64, f64::max);
    assert!(largest > 1e-6, "profile {largest} m near x = {x_end} m");
}

//! Reuse of the boundary-element solves across time steps (`[contact] reuse_tol`,
//! references.md §C8.4): runs with reuse against the same runs solving at every evaluation
//! (`reuse_tol = 0`).
//!
//! Each case compares the contact-force histories of every wheel (largest difference relative
//! to the peak force), the peak midspan deflection and the peak midspan acceleration, and checks
//! that the run's largest estimated error (relative to the force of the full solve a reused
//! evaluation came from) bounds the measured force-history difference. The
//! estimate is local (one evaluation); the measured difference also carries the propagation
//! through the dynamics and the NormCG tolerance of the run without reuse, so the bound is not
//! a theorem: these cases test it.

use sim::config::vehicle_bridge::parse;
use sim::vehicle_bridge::{ContactSolves, Simulation};

/// One Manchester bogie car (references.md §T4, 4 wheels) at 50 m/s on a random irregularity,
/// BEM 16 × 16 at every wheel, 0.1 s.
const FOUR_WHEELS: &str = r#"kind = "vehicle_bridge"
[bridge]
length = 25.0
EI = 8.323e9
mass_per_length = 2303.0
supports = "simply_supported"
modes = 8
damping_ratio = 0.02
[train]
speed = 50.0
position = 8.0
[[train.vehicles]]
type = "bogie_vehicle"
length = 25.0
body_mass = 32000.0
body_pitch_inertia = 1.97e6
bogie_spacing = 19.0
bogie_mass = 2615.0
bogie_pitch_inertia = 1476.0
wheelbase = 2.56
wheelset_mass = 1813.0
primary_stiffness = 2.4e6
primary_damping = 8.0e3
secondary_stiffness = 8.6e5
secondary_damping = 4.0e4
[contact]
model = "bem"
grid = 16
bem_tol = 1e-6
[irregularity]
kind = "random"
spectrum = "german_low"
lambda_min = 1.0
lambda_max = 30.0
components = 100
seed = 3
[integrator]
method = "generalized_alpha"
dt = 1e-4
duration = 0.1
"#;

/// One Manchester bogie car (references.md §T4) at 300 km/h over the default bridge on a smooth
/// rail, its leading axle 1 m before the span, BEM 16 × 16 at every wheel, until 0.12 s after
/// its last axle has left the span: the wheels on the approach and on the exit track (after the
/// abutment's slope kink, bouncing) are answered by the shared response table F(δ), the car off
/// the span is solved on its own (module `detached`).
const ONE_CAR_CROSSING: &str = r#"kind = "vehicle_bridge"
[bridge]
length = 25.0
EI = 8.323e9
mass_per_length = 2303.0
supports = "simply_supported"
modes = 20
damping_ratio = 0.02
[train]
speed = 83.333333
position = -1.0
[[train.vehicles]]
preset = "Manchester"
[contact]
model = "bem"
grid = 16
bem_tol = 1e-6
[integrator]
method = "generalized_alpha"
dt = 2.5e-4
duration = 0.7
"#;

struct Run {
    forces: Vec<Vec<f64>>,
    max_deflection: f64,
    max_acceleration: f64,
    solves: ContactSolves,
    detached_steps: u64,
}

fn run(text: &str, reuse_tol: f64) -> Run {
    run_with(text, reuse_tol, true)
}

fn run_with(text: &str, reuse_tol: f64, detach: bool) -> Run {
    let text = text.replace("[contact]", &format!("[contact]\nreuse_tol = {reuse_tol}"));
    let config = parse(&text).unwrap();
    let mut sim = Simulation::with_vehicles(config.scenario, config.vehicles).unwrap();
    sim.solve_detached_vehicles(detach);
    let (mut forces, mut max_deflection, mut max_acceleration) = (Vec::new(), 0.0_f64, 0.0_f64);
    sim.run(|s| {
        forces.push(s.wheels().iter().map(|w| w.contact.force).collect());
        let (d, _, a) = s.output_point_response();
        max_deflection = max_deflection.max(d.abs());
        max_acceleration = max_acceleration.max(a.abs());
    })
    .unwrap();
    let solves = sim.contact_solves().unwrap();
    Run {
        forces,
        max_deflection,
        max_acceleration,
        solves,
        detached_steps: sim.detached_vehicle_steps(),
    }
}

/// The largest difference of every wheel's force at every step between `run` and its
/// `reference`, relative to the reference's peak force.
fn force_history_difference(reference: &Run, run: &Run) -> f64 {
    let peak = reference
        .forces
        .iter()
        .flatten()
        .fold(0.0_f64, |m, f| m.max(f.abs()));
    reference
        .forces
        .iter()
        .zip(&run.forces)
        .flat_map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y).abs()))
        .fold(0.0_f64, f64::max)
        / peak
}

/// Runs `text` with and without reuse and checks the differences against `tol` (relative to
/// the peaks) and the estimate; returns (measured force difference, estimate, full solves,
/// reused evaluations) for the message.
fn compare(name: &str, text: &str, reuse_tol: f64, tol: f64) -> (Run, Run) {
    let exact = run(text, 0.0);
    let reused = run(text, reuse_tol);
    assert_eq!(exact.solves.reused, 0, "{name}: reuse_tol = 0 reuses");
    assert_eq!(exact.forces.len(), reused.forces.len());
    let force_diff = force_history_difference(&exact, &reused);
    let deflection = (reused.max_deflection / exact.max_deflection - 1.0).abs();
    let acceleration = (reused.max_acceleration / exact.max_acceleration - 1.0).abs();
    let s = reused.solves;
    let message = format!(
        "{name}: force history {force_diff:.3e}, max deflection {deflection:.3e}, max acceleration {acceleration:.3e} (tolerance {tol:e}); estimate {:.3e}; {} full solves ({} without reuse), {} by the factor, {} reused",
        s.max_estimate, s.full_solves, exact.solves.full_solves, s.factor_solves, s.reused
    );
    eprintln!("{message}");
    assert!(force_diff <= tol, "{message}");
    assert!(deflection <= tol, "{message}");
    assert!(acceleration <= tol, "{message}");
    assert!(
        force_diff <= s.max_estimate,
        "the estimate does not bound: {message}"
    );
    assert!(s.reused > 0, "{message}");
    (exact, reused)
}

/// The default scenario (one quarter car, BEM 32 × 32, random irregularity) with
/// reuse_tol = 3e-6 against full solves, within 1e-4 of the peaks (the accuracy asked of the reuse; the
/// peak midspan acceleration is the most sensitive: a step of the force error when a model is
/// replaced excites the high modes).
#[test]
fn default_scenario_reuse_within_1e_4() {
    let text = include_str!("../../../examples/vehicle_bridge_default.toml");
    let (_, reused) = compare("default", text, 3e-6, 1e-4);
    // The irregularity is under the wheel everywhere: the table is never built.
    assert_eq!(reused.solves.table_answers, 0);
    assert_eq!(reused.solves.table_solves, 0);
}

/// Four wheels: one Manchester bogie car (references.md §T4) at 50 m/s on a random
/// irregularity, BEM 16 × 16 at every wheel, 0.1 s.
#[test]
fn four_wheels_reuse_within_1e_4() {
    compare("four wheels", FOUR_WHEELS, 3e-6, 1e-4);
}

/// One car crossing the span and running onto the exit track at 300 km/h on a smooth rail
/// (issue #14's train case on one car): with reuse_tol = 3e-6 the wheels off the span are
/// answered by the shared response table, and the whole history stays within 1e-4 of the
/// peaks of the run solving every evaluation.
#[test]
fn one_car_crossing_with_the_table_within_1e_4() {
    let (exact, reused) = compare("one car crossing", ONE_CAR_CROSSING, 3e-6, 1e-4);
    let s = reused.solves;
    eprintln!(
        "table: {} answers from {} solves; {} detached car-steps",
        s.table_answers, s.table_solves, reused.detached_steps
    );
    assert!(s.table_answers > 1000 && s.table_solves > 0, "{s:?}");
    assert!(reused.detached_steps > 100 && exact.detached_steps > 100);
    assert_eq!(exact.solves.table_answers, 0);
}

/// Two cars of BEM wheels: the first, off the span, solved on its own (module `detached`)
/// against the same car in the coupled step with the second on the span (every evaluation
/// solved, reuse_tol = 0): the two iterate to the same coupling tolerance, so the histories
/// agree to that tolerance and the NormCG tolerance carried through the dynamics.
#[test]
fn detached_bem_car_equals_the_coupled_step() {
    let two_cars = ONE_CAR_CROSSING.replace(
        "preset = \"Manchester\"",
        "preset = \"Manchester\"\ncount = 2",
    );
    let detached = run_with(&two_cars, 0.0, true);
    let coupled = run_with(&two_cars, 0.0, false);
    assert!(detached.detached_steps > 100 && coupled.detached_steps == 0);
    let diff = force_history_difference(&coupled, &detached);
    let deflection = (detached.max_deflection / coupled.max_deflection - 1.0).abs();
    eprintln!("detached vs coupled BEM: force history {diff:.3e}, max deflection {deflection:.3e}");
    assert!(
        diff <= 1e-5 && deflection <= 1e-6,
        "{diff:e} {deflection:e}"
    );
}

/// A corrugation of wavelength 4 cm (about three patch lengths; the pressure distribution
/// changes shape from step to step) and amplitude 5 µm under the default quarter car,
/// reuse_tol = 1e-4, within 1e-3 of the peaks.
#[test]
fn corrugation_reuse_within_1e_3() {
    let text = include_str!("../../../examples/vehicle_bridge_default.toml");
    let start = text.find("[irregularity]").unwrap();
    let end = text.find("[integrator]").unwrap();
    let text = format!(
        "{}[irregularity]\nkind = \"corrugation\"\namplitude = 5e-6\nwavelength = 0.04\nstart = 0.0\nend = 25.0\n\n{}",
        &text[..start],
        &text[end..]
    )
    .replace("dt = 2.5e-4", "dt = 1e-4\nduration = 0.05");
    compare("corrugation", &text, 1e-4, 1e-3);
}

/// `reuse_tol` outside [0, 0.01], or with a model that does not solve, is refused with a
/// message naming the key and the value.
#[test]
fn reuse_tol_out_of_range_is_refused() {
    let text = include_str!("../../../examples/vehicle_bridge_default.toml");
    for bad in ["-1e-6", "0.5", "nan"] {
        let t = text.replace("[contact]", &format!("[contact]\nreuse_tol = {bad}"));
        let e = parse(&t).err().expect("refused").to_string();
        assert!(e.contains("reuse_tol") && e.contains("[0, 0.01]"), "{e}");
    }
    let hertz = text
        .replace("model = \"bem\"", "model = \"hertz\"")
        .replace("grid = 32\n", "")
        .replace("bem_tol = 1e-5\n", "")
        .replace("[contact]", "[contact]\nreuse_tol = 1e-4");
    let e = parse(&hertz).err().expect("refused").to_string();
    assert!(e.contains("reuse_tol") && e.contains("bem"), "{e}");
}

/// The wheels' contact laws are evaluated in parallel (rayon) when several wheels solve:
/// the four-wheel case gives bit-identical force histories and counts on one thread and on
/// two.
#[test]
fn four_wheels_independent_of_the_thread_count() {
    let on = |threads: usize, reuse_tol: f64| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| run(FOUR_WHEELS, reuse_tol))
    };
    for reuse_tol in [0.0, 3e-6] {
        let (one, two) = (on(1, reuse_tol), on(2, reuse_tol));
        assert_eq!(one.forces, two.forces, "reuse_tol {reuse_tol}");
        assert_eq!(one.solves, two.solves, "reuse_tol {reuse_tol}");
        assert_eq!(one.max_acceleration, two.max_acceleration);
    }
    // The response table (built by whichever wheel needs it first) as well.
    let pool = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    };
    let short = ONE_CAR_CROSSING.replace("duration = 0.7", "duration = 0.15");
    let one = pool(1).install(|| run(&short, 3e-6));
    let two = pool(2).install(|| run(&short, 3e-6));
    assert!(one.solves.table_answers > 0);
    assert_eq!(one.forces, two.forces);
    assert_eq!(one.solves, two.solves);
}

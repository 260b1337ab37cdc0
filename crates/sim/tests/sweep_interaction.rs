//! The sweep's interaction model (`[trains] model = "interaction"`): each passage is the
//! coupled vehicle–bridge run of the train's vehicle models. Checked against independent
//! references: the closed-form static influence line of a simply supported beam for a slow
//! passage (φ' → 1), the same passage run directly as a `vehicle_bridge` scenario, and the
//! refusal of trains that have no vehicle model (trains given by their axle loads).

mod support;

use sim::config::ScenarioConfig;
use sim::config::sweep::SweepConfig;
use support::{load, midspan_influence, passages};

const L: f64 = 20.0;
const EI: f64 = 1.95e10;
const BRIDGE: &str = "[bridge]\nlength = 20.0\nEI = 1.95e10\nmass_per_length = 12000.0\nsupports = \"simply_supported\"\nmodes = 3\ndamping_ratio = 0.01\n";

fn sweep(trains: &str, speeds: &str, extra: &str) -> SweepConfig {
    match load(&format!(
        "kind = \"sweep\"\n{BRIDGE}[trains]\nnames = [{trains}]\nmodel = \"interaction\"\n[speeds]\n{speeds}\n{extra}"
    )) {
        Ok(ScenarioConfig::Sweep(c)) => *c,
        Ok(_) => panic!("not a sweep"),
        Err(e) => panic!("{e}"),
    }
}

#[test]
fn a_slow_passage_deflects_the_span_like_the_static_influence_line() {
    // One AVE S-103 car (four 152.06 kN axles, 2.5 m wheelbase, 17.375 m bogie centres) at
    // 2 m/s (speed parameter v/(2 n0 L) = 0.01) with Hertz contact: the peak midspan deflection
    // is the closed-form static one (measured 2.9e-4 below it; asserted 2e-3, the size of the
    // dynamic effect at this speed), and the quasi-static deflection reported for φ' is the
    // same peak to 2e-3 (measured 8.4e-4: the truncation to 3 modes).
    let c = sweep(
        "\"AVE-S103-car\"",
        "list = [2.0]",
        "[contact]\nmodel = \"hertz\"\n",
    );
    let p = passages(&c);
    let axles = c.spec.trains[0].axles(9.81).unwrap();
    let mut peak = 0.0f64;
    for i in 0..=20_000 {
        let lead = (L + 20.0) * i as f64 / 20_000.0;
        let w: f64 = axles
            .iter()
            .map(|a| midspan_influence(L, EI, lead - a.offset, a.load))
            .sum();
        peak = peak.max(w);
    }
    let (w, stat) = (p[0].peaks.deflection[0], p[0].peaks.static_deflection[0]);
    println!("interaction {w:.6e} m, quasi-static {stat:.6e} m, closed form {peak:.6e} m");
    assert!((w / peak - 1.0).abs() < 2e-3, "{w} vs {peak}");
    assert!((stat / peak - 1.0).abs() < 2e-3, "{stat} vs {peak}");
}

#[test]
fn a_passage_equals_the_same_vehicle_bridge_run() {
    // The sweep's passage at 50 m/s is the vehicle_bridge scenario of the same train starting
    // with its leading axle at the span's entry, run to the last axle's exit plus 2/n0 of free
    // vibration: the same peak midspan deflection to round-off.
    let c = sweep(
        "\"AVE-S103-car\"",
        "list = [50.0]",
        "[contact]\nmodel = \"hertz\"\n",
    );
    let p = passages(&c);
    let n0 = c.first_frequency;
    let dt = match &c.spec.model {
        sim::sweep::SweepModel::Interaction(m) => m.trains[0].dt,
        _ => panic!("interaction"),
    };
    let duration = (L + 19.875) / 50.0 + 2.0 / n0;
    let text = format!(
        "kind = \"vehicle_bridge\"\n{BRIDGE}[train]\nspeed = 50.0\nposition = 0.0\n[[train.vehicles]]\npreset = \"AVE-S103-car\"\n[contact]\nmodel = \"hertz\"\n[integrator]\nmethod = \"newmark\"\ndt = {dt:e}\nduration = {duration:e}\n"
    );
    let Ok(ScenarioConfig::VehicleBridge(v)) = load(&text) else {
        panic!("vehicle_bridge scenario");
    };
    let mut sim = sim::vehicle_bridge::Simulation::with_vehicles(v.scenario, v.vehicles).unwrap();
    // A sweep's passage converges its steps by the contact laws' residual (its states then
    // differ from the default iteration's within the coupling tolerance, which moves this
    // light car's body acceleration by 8e-7: `sweep_interaction_law.rs`); the same here.
    sim.accept_by_law_residual(true);
    let mut peak = 0.0f64;
    let mut monitor = sim::train_response::TrainMonitor::new(&sim);
    let exit = (L + 19.875) / 50.0;
    let (mut unloading, mut min_force) = (0.0f64, f64::INFINITY);
    sim.run(|s| {
        peak = peak.max(s.output_point_response().0.abs());
        // The vehicles' peaks of the sweep cover the coupled part (to the last axle's exit).
        if s.t() <= exit + 1e-9 {
            monitor.observe(s);
            for (w, &load) in s.wheels().iter().zip(s.static_loads()) {
                unloading = unloading.max((load - w.contact.force) / load);
                min_force = min_force.min(w.contact.force);
            }
        }
    })
    .unwrap();
    let w = p[0].peaks.deflection[0];
    println!("sweep {w:.9e} m, vehicle_bridge {peak:.9e} m");
    assert!((w / peak - 1.0).abs() < 1e-9, "{w} vs {peak}");
    // The wheels' unloading and the body acceleration as the direct run's, taken from its
    // contact forces and static loads step by step (the same run: to round-off).
    let vp = p[0]
        .vehicles
        .expect("interaction passages carry the vehicles' peaks");
    let body = monitor.vehicles().unwrap()[0].max_body_acceleration;
    println!(
        "unloading {} / {unloading}, min force {} / {min_force} N, body {} / {body} m/s²",
        vp.max_unloading_ratio, vp.min_contact_force, vp.max_body_acceleration
    );
    assert!((vp.max_unloading_ratio - unloading).abs() < 1e-9);
    assert!((vp.min_contact_force / min_force - 1.0).abs() < 1e-9);
    assert!((vp.max_body_acceleration / body - 1.0).abs() < 1e-9);
    assert_eq!(vp.loss_of_contact_events, 0);
}

#[test]
fn a_slow_passage_keeps_the_static_wheel_loads_and_a_resonant_one_lifts_wheels() {
    // The bogie vehicle is statically determinate (the body on two bogies, each bogie on two
    // wheelsets): in a quasi-static passage (2 m/s) its wheel loads stay the static ones
    // whatever the deck's deflection, so the unloading ratio (W − F)/W stays near 0 and no
    // wheel lifts. Measured 4.4e-3 (the smallest force 4.5e-3 below the static load): the
    // dynamic part, the wheelsets' bounce on their contact springs where the axles pass the
    // kink between the rigid approach and the deck's end slope θ (a jump v θ in the wheel's
    // vertical velocity: measured proportional to v, 1.1e-3 / 2.2e-3 / 4.4e-3 / 8.8e-3 at
    // 0.5 / 1 / 2 / 4 m/s); asserted 1e-2.
    let c = sweep(
        "\"AVE-S103-car\"",
        "list = [2.0]",
        "[contact]\nmodel = \"hertz\"\n",
    );
    let slow = passages(&c)[0].vehicles.unwrap();
    println!("2 m/s: {slow:?}");
    assert!(slow.max_unloading_ratio.abs() < 1e-2, "{slow:?}");
    assert_eq!(slow.loss_of_contact_events, 0);
    let static_load = c.spec.trains[0].axles(9.81).unwrap()[0].load;
    assert!((slow.min_contact_force / static_load - 1.0).abs() < 1e-2);
    // The seven articulated Eurostar trailers at their first resonance (90 m/s on this span,
    // deck acceleration 11 m/s²) lift wheels: a wheel out of contact has F = 0, so the
    // largest unloading ratio is exactly 1 and the smallest force exactly 0; below the
    // resonance (50 m/s) no wheel lifts.
    let c = sweep(
        "\"Eurostar-EC2-EC8\"",
        "list = [50.0, 90.0]",
        "[contact]\nmodel = \"hertz\"\n",
    );
    let p = passages(&c);
    let (below, at) = (p[0].vehicles.unwrap(), p[1].vehicles.unwrap());
    println!("50 m/s: {below:?}\n90 m/s: {at:?}");
    assert_eq!(below.loss_of_contact_events, 0);
    assert!(below.max_unloading_ratio < 1.0 && below.min_contact_force > 0.0);
    assert!(at.loss_of_contact_events > 0);
    assert_eq!(at.max_unloading_ratio, 1.0);
    assert_eq!(at.min_contact_force, 0.0);
}

#[test]
fn trains_without_vehicle_models_are_refused() {
    let e = match load(&format!(
        "kind = \"sweep\"\n{BRIDGE}[trains]\nmodel = \"interaction\"\n[[trains.train]]\nname = \"axles\"\naxle_positions = [0.0, 3.0]\naxle_loads = [1.7e5, 1.7e5]\n[speeds]\nlist = [50.0]\n"
    )) {
        Err(e) => e,
        Ok(_) => panic!("an axle-load train accepted in the interaction model"),
    };
    assert!(
        e.contains("axles") && e.contains("moving_forces") && e.contains("vehicle models"),
        "{e}"
    );
    let e = match load(&format!(
        "kind = \"sweep\"\n{BRIDGE}[trains]\nnames = [\"AVE-S103-car\"]\n[contact]\nmodel = \"hertz\"\n[speeds]\nlist = [50.0]\n"
    )) {
        Err(e) => e,
        Ok(_) => panic!("[contact] accepted with moving forces"),
    };
    assert!(e.contains("[contact]") && e.contains("interaction"), "{e}");
}

#[test]
fn hslm_trains_get_vehicle_models_whose_wheels_carry_p() {
    // HSLM-A in the interaction model: the assumed vehicle models of
    // `train::hslm_vehicles` (power cars and one articulated rake). The coupled model's own
    // statics (its solve of the vehicles' stiffness matrices, independent of the lever rule
    // the masses were chosen by) gives every wheelset the standard's point force P, and the
    // train standing on the approach keeps it.
    let c = sweep(
        "\"HSLM-A\"",
        "list = [50.0]",
        "[contact]\nmodel = \"hertz\"\n",
    );
    let sim::sweep::SweepModel::Interaction(model) = &c.spec.model else {
        panic!("interaction");
    };
    assert_eq!(model.trains.len(), 10);
    for (i, vehicles) in model.trains.iter().enumerate() {
        let p = sim::train::hslm::parameters(i + 1).unwrap().point_force;
        let axles = c.spec.trains[i].axles(9.81).unwrap().len();
        assert_eq!(vehicles.wheels.len(), axles, "A{}", i + 1);
        if i > 1 {
            continue; // the coupled statics of A1 and A2 below (cost)
        }
        // The train entirely on the approach (its leading axle 1 m before the span), at rest.
        let wheels: Vec<_> = vehicles
            .wheels
            .iter()
            .map(|w| sim::vehicle_bridge::WheelSpec {
                position: w.position - 1.0,
                ..*w
            })
            .collect();
        let scenario = sim::vehicle_bridge::Scenario {
            bridge: Box::new(std::sync::Arc::clone(&model.basis)),
            damping: model.damping.clone(),
            wheels,
            moving_forces: Vec::new(),
            speed: 1e-6,
            contact: model.contact.clone(),
            geometry: model.geometry,
            irregularity: sim::vehicle_bridge::Irregularity::None,
            integrator: model.integrator,
            dt: vehicles.dt,
            duration: Some(20.0 * vehicles.dt),
            coupling: model.coupling,
            gravity: model.gravity,
            output_point: 10.0,
        };
        let mut s =
            sim::vehicle_bridge::Simulation::with_vehicles(scenario, vehicles.layouts.clone())
                .unwrap();
        let worst = s
            .static_loads()
            .iter()
            .fold(0.0f64, |m, f| m.max((f / p - 1.0).abs()));
        println!(
            "HSLM-A{}: static wheel loads within {worst:.1e} of P",
            i + 1
        );
        assert!(worst < 1e-9, "A{}: {worst}", i + 1);
        s.run(|_| {}).unwrap();
        let worst = s
            .wheels()
            .iter()
            .fold(0.0f64, |m, w| m.max((w.contact.force / p - 1.0).abs()));
        println!("HSLM-A{}: after 20 steps within {worst:.1e} of P", i + 1);
        assert!(worst < 1e-6, "A{}: {worst}", i + 1);
    }
}

/// Samples (t, w, ẅ).
type History = Vec<(f64, f64, f64)>;

/// Midspan (t, w, ẅ) of the AVE S-103 car's passage at 50 m/s (Hertz) at time step `dt`:
/// the sweep's history (coupled until the last axle's exit, then the exact free vibration of
/// the modes) and the same passage coupled to the end (`vehicle_bridge`).
fn tails(dt: f64) -> (History, History, f64) {
    let c = sweep(
        "\"AVE-S103-car\"",
        "list = [50.0]",
        &format!("[contact]\nmodel = \"hertz\"\n[integrator]\ndt = {dt:e}\n"),
    );
    let sim::sweep::SweepModel::Interaction(model) = &c.spec.model else {
        panic!("interaction");
    };
    let m = model.basis.n_modes();
    let mut shapes = vec![0.0; m];
    model
        .basis
        .eval_all(0.5 * L, beam::Derivative::Shape, &mut shapes)
        .unwrap();
    let free = c.spec.free_vibration;
    let sweep =
        sim::sweep::interaction::history(model, 0, 50.0, &shapes, free, usize::MAX).unwrap();
    let exit = (L + 19.875) / 50.0;
    let text = format!(
        "kind = \"vehicle_bridge\"\n{BRIDGE}[train]\nspeed = 50.0\nposition = 0.0\n[[train.vehicles]]\npreset = \"AVE-S103-car\"\n[contact]\nmodel = \"hertz\"\n[integrator]\nmethod = \"newmark\"\ndt = {dt:e}\nduration = {:e}\n",
        exit + free
    );
    let Ok(ScenarioConfig::VehicleBridge(v)) = load(&text) else {
        panic!("vehicle_bridge scenario");
    };
    let mut sim = sim::vehicle_bridge::Simulation::with_vehicles(v.scenario, v.vehicles).unwrap();
    let mut coupled = Vec::new();
    sim.run(|s| {
        let (w, _, a) = s.output_point_response();
        coupled.push((s.t(), w, a));
    })
    .unwrap();
    (sweep, coupled, exit)
}

#[test]
fn the_free_vibration_tail_is_the_limit_of_the_coupled_tail() {
    // After the last axle's exit the sweep continues with the exact modal recurrence; the
    // coupled run continues with the Newmark trapezoidal rule, whose error is O(Δt²). Before
    // the exit both are the same run (equal to round-off); after it, their difference is the
    // trapezoidal rule's error: small (measured 5.1e-5 of the peak deflection and 3.8e-3 of
    // the peak acceleration at 4e-4 s), and falling 4× when Δt halves (measured 3.98 and 4.01).
    let mut errors = Vec::new();
    for dt in [4e-4, 2e-4] {
        let (sweep, coupled, exit) = tails(dt);
        assert_eq!(sweep.len(), coupled.len());
        let scale_w = coupled.iter().fold(0.0f64, |m, s| m.max(s.1.abs()));
        let scale_a = coupled.iter().fold(0.0f64, |m, s| m.max(s.2.abs()));
        let (mut before, mut after_w, mut after_a) = (0.0f64, 0.0f64, 0.0f64);
        for (s, c) in sweep.iter().zip(&coupled) {
            assert!((s.0 - c.0).abs() < 1e-12, "{} vs {}", s.0, c.0);
            let (dw, da) = ((s.1 - c.1).abs() / scale_w, (s.2 - c.2).abs() / scale_a);
            if c.0 <= exit {
                before = before.max(dw).max(da);
            } else {
                after_w = after_w.max(dw);
                after_a = after_a.max(da);
            }
        }
        println!(
            "dt = {dt:e}: before the exit {before:.1e}, free vibration w {after_w:.2e}, a {after_a:.2e} (of the peaks)"
        );
        assert!(before < 1e-9, "{before}");
        assert!(after_w < 1e-4 && after_a < 8e-3, "{after_w} {after_a}");
        errors.push((after_w, after_a));
    }
    let (ratio_w, ratio_a) = (errors[0].0 / errors[1].0, errors[0].1 / errors[1].1);
    println!("ratio at halved dt: w {ratio_w:.2}, a {ratio_a:.2}");
    assert!(ratio_w > 3.0 && ratio_a > 3.0, "{ratio_w} {ratio_a}");
}

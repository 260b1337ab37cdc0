//! The train of `dyncontact bench trains` (Manchester bogie cars, Hertz contact, 25 m span with
//! 20 modes, 300 km/h, Δt = 1e-4 s) as a bare run, for instruction counts with
//! `valgrind --tool=callgrind` (docs/trains.md, "Not implemented yet"). Arguments: the number
//! of cars (8), the leading axle's start position \[m\] (0: the whole crossing), the duration
//! \[s\] (default: until the last wheel has left the span) and `every` to step every car in the
//! coupled step (no cars held at rest or solved on their own off the span). Run with
//! `cargo run --release -p sim --example profile_train_crossing -- 8 0.0`.

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let cars: usize = args.get(1).map_or(Ok(8), |s| s.parse())?;
    let position: f64 = args.get(2).map_or(Ok(0.0), |s| s.parse())?;
    let duration = match args.get(3) {
        Some(s) => format!("duration = {}\n", s.parse::<f64>()?),
        None => String::new(),
    };
    let every = args.get(4).is_some_and(|s| s == "every");
    let bridge = "[bridge]\nlength = 25.0\nEI = 8.323e9\nmass_per_length = 2303.0\nsupports = \"simply_supported\"\nmodes = 20\ndamping_ratio = 0.02\n";
    let car = "type = \"bogie_vehicle\"\nlength = 25.0\nbody_mass = 32000.0\nbody_pitch_inertia = 1.97e6\nbogie_spacing = 19.0\nbogie_mass = 2615.0\nbogie_pitch_inertia = 1476.0\nwheelbase = 2.56\nwheelset_mass = 1813.0\nprimary_stiffness = 2.4e6\nprimary_damping = 8.0e3\nsecondary_stiffness = 8.6e5\nsecondary_damping = 4.0e4\n";
    let text = format!(
        "kind = \"vehicle_bridge\"\n{bridge}[train]\nspeed = 83.333\nposition = {position}\n[[train.vehicles]]\ncount = {cars}\n{car}[contact]\nmodel = \"hertz\"\n[integrator]\nmethod = \"generalized_alpha\"\ndt = 1e-4\n{duration}"
    );
    let config = sim::config::vehicle_bridge::parse(&text)?;
    let mut sim = sim::vehicle_bridge::Simulation::with_vehicles(config.scenario, config.vehicles)?;
    sim.hold_resting_vehicles(!every);
    sim.solve_detached_vehicles(!every);
    let start = std::time::Instant::now();
    let run = sim.run(|_| {})?;
    let wall = start.elapsed().as_secs_f64();
    println!(
        "{} steps in {wall:.3} s ({:.2} µs/step), peak deflection {:e} m, {} coupled iterations, car-steps held at rest {}, solved on their own {}",
        run.solver.steps,
        1e6 * wall / run.solver.steps as f64,
        run.deflection.max_abs(),
        run.solver.iterations,
        sim.held_vehicle_steps(),
        sim.detached_vehicle_steps()
    );
    // The peaks a change of the coupling's round-off or tolerance must leave alone.
    let wheels = &run.wheels;
    let fold = |f: &dyn Fn(&sim::vehicle_bridge::WheelSummary) -> f64, max: bool| {
        wheels.iter().map(f).fold(
            if max {
                f64::NEG_INFINITY
            } else {
                f64::INFINITY
            },
            |m, v| if max { m.max(v) } else { m.min(v) },
        )
    };
    println!(
        "peaks: deflection {:e} / {:e} m, acceleration {:e} / {:e} m/s², contact force {:e} / {:e} N, body acceleration {:e} m/s², wheel acceleration {:e} m/s²",
        run.deflection.max.value,
        run.deflection.min.value,
        run.acceleration.max.value,
        run.acceleration.min.value,
        fold(&|w| w.force.max.value, true),
        fold(&|w| w.force.min.value, false),
        fold(&|w| w.max_body_acceleration, true),
        fold(&|w| w.max_wheel_acceleration, true),
    );
    Ok(())
}

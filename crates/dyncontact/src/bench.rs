//! `dyncontact bench ...`: performance tables (release builds).

use std::time::Instant;

use anyhow::{Result, anyhow};
use halfspace::convolution::FftConvolution;
use halfspace::influence::circulant_kernel;
use halfspace::{GapShape, Grid, Hertz, Material, NormalLoad, NormalSolver, SolverOptions};

/// Best-of-`repeats` wall time of `f` in seconds.
fn best_of(repeats: usize, mut f: impl FnMut()) -> f64 {
    (0..repeats)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Hertz sphere (steel on steel, R = 10 mm, F = 1 kN) on N × N grids whose half-width is
/// 1/0.3 of the contact radius, solved to tol = 1e-8 for a prescribed approach and for a
/// prescribed force (cold starts). `solve/conv` is the solve time over the time of its
/// convolutions if each cost as much as one dense padded convolution (`conv ms`). At the
/// largest N ≤ 512 the force-prescribed case is also solved by tamaas when it is installed
/// ([`crate::bench_tamaas`]) and the two times compared.
pub fn contact(max_n: usize) -> Result<()> {
    let (young, poisson) = (210e9, 0.3);
    let material = Material::identical(young, poisson).map_err(|e| anyhow!("{e}"))?;
    let radius = 0.01;
    let force = 1000.0;
    let hertz = Hertz::sphere(radius, material.e_star, force).map_err(|e| anyhow!("{e}"))?;
    // Hertz's own model of the sphere: the paraboloid h = r²/(2R).
    let shape = GapShape::Quadratic {
        a: 0.5 / radius,
        b: 0.5 / radius,
    };
    println!(
        "Hertz sphere, R = {radius} m, F = {force} N, steel/steel; contact radius a = {:.4e} m = 0.3 grid half-width; tol 1e-8; {} rayon threads",
        hertz.a,
        rayon::current_num_threads()
    );
    println!(
        "{:>6} {:>9} {:>6} {:>6} {:>10} {:>10} {:>10} {:>10} {:>11} {:>11} {:>11} {:>6}",
        "N",
        "load",
        "iter",
        "conv",
        "solve ms",
        "ms/iter",
        "conv ms",
        "solve/conv",
        "err δ",
        "err p0",
        "dF/dδ ms",
        "s-iter"
    );
    // The force-prescribed solve at the largest N ≤ 512: N, seconds, p0 error.
    let mut compared: Option<(usize, f64, f64)> = None;
    let mut n = 64;
    while n <= max_n {
        let half = hertz.a / 0.3;
        let d = 2.0 * half / n as f64;
        let grid = Grid::centred(n, n, d, d, 0.0, 0.0).map_err(|e| anyhow!("{e}"))?;
        let gap = shape.sample(&grid).map_err(|e| anyhow!("{e}"))?;
        // One padded convolution.
        let mut conv = FftConvolution::new(n, n);
        let spectrum = conv.kernel_spectrum(&circulant_kernel(&material, &grid));
        let p: Vec<f64> = (0..grid.len()).map(|k| (k % 7) as f64).collect();
        let mut u = vec![0.0; grid.len()];
        conv.apply(&spectrum, &p, &mut u);
        // Best of 10, and again after the solves (the smaller): on a loaded machine the two
        // sides of `solve/conv` are then both near their unloaded values.
        let mut conv_time = best_of(10, || conv.apply(&spectrum, &p, &mut u));
        for load in [
            NormalLoad::Approach(hertz.approach),
            NormalLoad::Force(force),
        ] {
            let mut solver = NormalSolver::new(grid, material).map_err(|e| anyhow!("{e}"))?;
            let cold = SolverOptions {
                warm_start: false,
                sensitivity: false,
                ..Default::default()
            };
            let t = Instant::now();
            let sol = solver
                .solve(&gap, load, &cold)
                .map_err(|e| anyhow!("N = {n}: {e}"))?;
            let first_time = t.elapsed().as_secs_f64();
            let convolutions = solver.convolutions();
            // Best of five cold solves (the first includes page faults of fresh buffers).
            let mut solve_time = first_time;
            for _ in 0..4 {
                let t = Instant::now();
                solver
                    .solve(&gap, load, &cold)
                    .map_err(|e| anyhow!("N = {n}: {e}"))?;
                solve_time = solve_time.min(t.elapsed().as_secs_f64());
            }
            let with_sens = SolverOptions {
                warm_start: false,
                ..Default::default()
            };
            let mut with_time = f64::INFINITY;
            let mut sens = None;
            for _ in 0..2 {
                // Forget the previous sensitivity too: time a cold linearised solve.
                solver.reset();
                let t = Instant::now();
                let s = solver
                    .solve(&gap, load, &with_sens)
                    .map_err(|e| anyhow!("N = {n}: {e}"))?;
                with_time = with_time.min(t.elapsed().as_secs_f64());
                sens = Some(s);
            }
            let sens = sens.expect("two solves ran");
            conv_time = conv_time.min(best_of(10, || conv.apply(&spectrum, &p, &mut u)));
            let sens_time = with_time - solve_time;
            let label = match load {
                NormalLoad::Approach(_) => "approach",
                NormalLoad::Force(_) => {
                    if n <= 512 {
                        compared =
                            Some((n, solve_time, sol.max_pressure / hertz.max_pressure - 1.0));
                    }
                    "force"
                }
            };
            println!(
                "{:>6} {:>9} {:>6} {:>6} {:>10.2} {:>10.3} {:>10.3} {:>10.2} {:>11.2e} {:>11.2e} {:>11.2} {:>6}",
                n,
                label,
                sol.iterations,
                convolutions,
                1e3 * solve_time,
                1e3 * solve_time / sol.iterations as f64,
                1e3 * conv_time,
                solve_time / (convolutions as f64 * conv_time),
                sol.approach / hertz.approach - 1.0,
                sol.max_pressure / hertz.max_pressure - 1.0,
                1e3 * sens_time.max(0.0),
                sens.sensitivity_iterations,
            );
        }
        n *= 2;
    }
    println!(
        "conv = FFT convolutions in the first (cold, no sensitivity) solve; err = relative error against Hertz;"
    );
    println!(
        "dF/dδ ms, s-iter = extra time and CG iterations of the linearised sensitivity solve (default tol 1e-6);"
    );
    println!(
        "solve/conv = solve ms / (conv × conv ms): the solve against the cost of its convolutions if each were dense."
    );
    crate::bench_small_grids::small_grids(material, radius, force, &hertz)?;
    if let Some((n, ours, err_p0)) = compared {
        let case = crate::bench_tamaas::Case {
            n,
            width: 2.0 * hertz.a / 0.3,
            e: young,
            nu: poisson,
            radius,
            force,
            tol: 1e-8,
        };
        match crate::bench_tamaas::run(&case) {
            crate::bench_tamaas::Outcome::Measured {
                version,
                seconds,
                max_pressure,
                force: f,
            } => {
                println!(
                    "tamaas {version} (Python, PolonskyKeerRey, tol 1e-8, periodic domain of the same width), {n} × {n}, force prescribed: best of 3 {:.3} s, err p0 {:.2e}, err F {:.1e}; dyncontact {:.3} s, err p0 {:.2e}: tamaas / dyncontact = {:.1}",
                    seconds,
                    max_pressure / hertz.max_pressure - 1.0,
                    f / force - 1.0,
                    ours,
                    err_p0,
                    seconds / ours
                );
            }
            crate::bench_tamaas::Outcome::Skipped(reason) => {
                println!("tamaas comparison at {n} × {n} skipped: {reason}");
            }
        }
    }
    Ok(())
}

/// Bridge workloads (issue targets: 100 modes at 10⁴ points, a 1000-element FE eigen-solve,
/// a 25 m bridge with 50 modes over the passage at Δt = 1e-4 s in well under a second).
pub fn beam() -> Result<()> {
    use beam::bench as work;
    let e = |err: beam::BeamError| anyhow!("{err}");
    println!("{:<58} {:>12}", "workload (best of 3, release)", "wall ms");
    let mut checksum = 0.0;
    let t = best_of(3, || {
        checksum += work::mode_evaluation(100, 10_000).unwrap_or(f64::NAN)
    });
    println!(
        "{:<58} {:>12.2}",
        "evaluate 100 clamped-clamped modes at 10^4 points",
        1e3 * t
    );
    let t = best_of(3, || {
        checksum += work::fe_eigen_solve(1000, 20, beam::EigenReduction::default())
            .map(|m| beam::ModalBasis::circular_frequencies(&m)[0])
            .unwrap_or(f64::NAN)
    });
    println!(
        "{:<58} {:>12.2}",
        "FE eigen-solve, 1000 elements, 20 modes (banded subspace)",
        1e3 * t
    );
    let run = work::moving_load_run(50, 1e-4).map_err(e)?;
    let t = best_of(3, || {
        checksum += work::moving_load_run(50, 1e-4)
            .map(|r| r.exit_time)
            .unwrap_or(f64::NAN)
    });
    println!(
        "{:<58} {:>12.2}",
        format!(
            "moving load, 25 m, 50 modes, dt = 1e-4 s ({} samples)",
            run.times.len()
        ),
        1e3 * t
    );
    // The track model (beam::track): Newmark step of the track + bridge under a moving force,
    // per step (the set-up with its factorisation timed separately and subtracted).
    let steps = 2000;
    for (approach, per_bay, split) in [
        (15.0, 4, false),
        (30.0, 4, false),
        (60.0, 4, false),
        (120.0, 4, false),
        (60.0, 2, false),
        (60.0, 2, true),
    ] {
        let track = work::ballasted_track_on_fryba_bridge(approach, per_bay).map_err(e)?;
        let setup = best_of(3, || {
            checksum += work::track_moving_force(&track, 1e-4, 0, split).unwrap_or(f64::NAN)
        });
        let total = best_of(3, || {
            checksum += work::track_moving_force(&track, 1e-4, steps, split).unwrap_or(f64::NAN)
        });
        println!(
            "{:<58} {:>12.2}",
            format!(
                "track {approach}+25+{approach} m, {per_bay} el./bay, {} DOFs{}: µs/step",
                track.n_dofs(),
                if split { ", split" } else { "" }
            ),
            1e6 * (total - setup) / steps as f64
        );
    }
    if !checksum.is_finite() {
        return Err(anyhow!("a benchmark workload failed"));
    }
    Ok(())
}

/// The HSLM-A envelope of issue #12: a 20 m simply supported bridge with f1 = 5 Hz
/// (EI from ω1 = (π/L)² √(EI/m), m = 12 t/m), 3 modes, ζ = 1 %, 10 trains × 57 speeds
/// (140 … 420 km/h by 5 km/h) = 570 passages with their free vibration.
pub const SWEEP_BENCH: &str = r#"kind = "sweep"
[bridge]
length = 20.0
EI = 1.9452e10
mass_per_length = 12000.0
supports = "simply_supported"
modes = 3
damping_ratio = 0.01
[trains]
names = ["HSLM-A"]
[speeds]
from = 38.88888888888889
to = 116.66666666666667
step = 1.3888888888888888
"#;

/// `dyncontact bench sweep`: wall time of the HSLM-A envelope on all cores and on one, and a
/// check that both give identical results.
pub fn sweep() -> Result<()> {
    let config =
        match sim::config::load(SWEEP_BENCH, std::path::Path::new("."), &Default::default())? {
            sim::config::ScenarioConfig::Sweep(c) => *c,
            _ => anyhow::bail!("the sweep benchmark is not a sweep scenario"),
        };
    let run = |threads: usize| -> Result<(f64, Vec<sim::sweep::Passage>)> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()?;
        let mut best = f64::INFINITY;
        let mut result = Vec::new();
        for _ in 0..3 {
            let start = Instant::now();
            result = pool.install(|| {
                sim::sweep::run(
                    config.bridge.basis.as_ref(),
                    &config.bridge.damping,
                    &config.spec,
                    sim::sweep::Shard::ALL,
                    &|| true,
                )
            })?;
            best = best.min(start.elapsed().as_secs_f64());
        }
        Ok((best, result))
    };
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let (t_all, all) = run(cores)?;
    let (t_one, one) = run(1)?;
    let steps: usize = all.iter().map(|p| p.peaks.steps).sum();
    println!(
        "HSLM-A envelope: 20 m simply supported, f1 = {:.3} Hz, {} modes, dt = {:.3e} s, {} passages, {} time steps in all",
        config.first_frequency,
        config.bridge.basis.n_modes(),
        config.spec.dt,
        all.len(),
        steps
    );
    println!(
        "{:>8} {:>12} {:>16} {:>14}",
        "threads", "wall [s]", "µs per passage", "ns per step"
    );
    for (threads, t) in [(cores, t_all), (1, t_one)] {
        println!(
            "{threads:>8} {t:>12.4} {:>16.1} {:>14.2}",
            1e6 * t / all.len() as f64,
            1e9 * t / steps as f64
        );
    }
    println!(
        "results with {cores} threads and 1 thread: {} (target: the envelope in <= 1 s on 2 cores)",
        if all == one { "identical" } else { "DIFFERENT" }
    );
    if all != one {
        anyhow::bail!("the sweep depends on the thread count");
    }
    sweep_interaction(cores)
}

/// The interaction model's row of `dyncontact bench sweep`: a representative subset of the
/// HSLM-A envelope (A1, the longest rake, and A10, the shortest, at 140, 280 and 420 km/h;
/// Hertz contact at the default Δt) run on all cores and on one, and the full envelope's time
/// extrapolated from the one-thread cost per step and the envelope's number of steps.
fn sweep_interaction(cores: usize) -> Result<()> {
    let interaction = |names: &str| -> Result<sim::config::sweep::SweepConfig> {
        let text = SWEEP_BENCH.replace(
            "names = [\"HSLM-A\"]\n",
            &format!("names = [{names}]\nmodel = \"interaction\"\n"),
        ) + "[contact]\nmodel = \"hertz\"\n";
        match sim::config::load(&text, std::path::Path::new("."), &Default::default())? {
            sim::config::ScenarioConfig::Sweep(c) => Ok(*c),
            _ => anyhow::bail!("the sweep benchmark is not a sweep scenario"),
        }
    };
    let full = interaction("\"HSLM-A\"")?;
    let subset = interaction("\"HSLM-A1\", \"HSLM-A10\"")?;
    let subset = sim::config::sweep::SweepConfig {
        spec: sim::sweep::SweepSpec {
            speeds: vec![38.88888888888889, 77.77777777777777, 116.66666666666667],
            ..subset.spec
        },
        ..subset
    };
    // The full envelope's steps (each passage: the exit of its last axle plus the free
    // vibration, at its train's Δt).
    let length = full.bridge.basis.length();
    let sim::sweep::SweepModel::Interaction(model) = &full.spec.model else {
        anyhow::bail!("the interaction benchmark is not an interaction sweep");
    };
    let mut full_steps = 0.0;
    for (i, t) in full.spec.trains.iter().enumerate() {
        for &v in &full.spec.speeds {
            full_steps +=
                ((length + t.length()) / v + full.spec.free_vibration) / model.trains[i].dt;
        }
    }
    // (wall [s], CPU time of the pool's threads [s] (one thread only: its own), passages)
    let run = |threads: usize| -> Result<(f64, f64, Vec<sim::sweep::Passage>)> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()?;
        let start = Instant::now();
        let (cpu, result) = pool.install(|| {
            let cpu0 = crate::bench_track::thread_cpu_time();
            let result = sim::sweep::run(
                subset.bridge.basis.as_ref(),
                &subset.bridge.damping,
                &subset.spec,
                sim::sweep::Shard::ALL,
                &|| true,
            );
            (crate::bench_track::thread_cpu_time() - cpu0, result)
        });
        Ok((start.elapsed().as_secs_f64(), cpu, result?))
    };
    let (t_all, _, all) = run(cores)?;
    let (t_one, cpu_one, one) = run(1)?;
    let steps: usize = all.iter().map(|p| p.peaks.steps).sum();
    println!(
        "interaction model (bogie power cars and an articulated rake, Hertz contact, default dt): HSLM-A1 and A10 at 140, 280, 420 km/h, {} passages, {steps} time steps",
        all.len()
    );
    println!(
        "{:>8} {:>12} {:>16} {:>14}",
        "threads", "wall [s]", "s per passage", "µs per step"
    );
    for (threads, t) in [(cores, t_all), (1, t_one)] {
        println!(
            "{threads:>8} {t:>12.3} {:>16.3} {:>14.2}",
            t / all.len() as f64,
            1e6 * t / steps as f64
        );
    }
    let per_step = 1e6 * cpu_one / steps as f64;
    let extrapolated = 1e-6 * per_step * full_steps / cores as f64;
    println!(
        "one thread: {cpu_one:.3} s of CPU, {per_step:.2} µs per step; full HSLM-A envelope ({} passages, {:.3e} steps): extrapolated {extrapolated:.0} s on {cores} idle cores (target <= 60 s); results with {cores} threads and 1 thread: {}",
        full.spec.trains.len() * full.spec.speeds.len(),
        full_steps,
        if all == one { "identical" } else { "DIFFERENT" }
    );
    if all != one {
        anyhow::bail!("the interaction sweep depends on the thread count");
    }
    Ok(())
}

/// `dyncontact bench trains`: µs per step of the coupled model against the number of wheels
/// (bogie vehicles of the Manchester car, Hertz contact, 25 m span with 20 modes, 300 km/h,
/// Δt = 1e-4 s, 0.1 s simulated), and HSLM-A1 as moving forces over the same span.
pub fn trains() -> Result<()> {
    let bridge = "[bridge]\nlength = 25.0\nEI = 8.323e9\nmass_per_length = 2303.0\nsupports = \"simply_supported\"\nmodes = 20\ndamping_ratio = 0.02\n";
    let car = "type = \"bogie_vehicle\"\nlength = 25.0\nbody_mass = 32000.0\nbody_pitch_inertia = 1.97e6\nbogie_spacing = 19.0\nbogie_mass = 2615.0\nbogie_pitch_inertia = 1476.0\nwheelbase = 2.56\nwheelset_mass = 1813.0\nprimary_stiffness = 2.4e6\nprimary_damping = 8.0e3\nsecondary_stiffness = 8.6e5\nsecondary_damping = 4.0e4\n";
    println!(
        "coupled model: Manchester bogie cars, Hertz contact, 25 m span, 20 modes, 83.33 m/s, dt = 1e-4 s, 0.1 s simulated"
    );
    println!(
        "(cars at rest ahead of the span are held out of the step, cars off the span solved on their own: docs/trains.md; the last column steps every car in the coupled step)"
    );
    println!(
        "{:>8} {:>6} {:>8} {:>10} {:>12} {:>14} {:>22}",
        "wheels", "cars", "steps", "wall [s]", "µs/step", "× real time", "µs/step, every car"
    );
    // One wheel: a quarter car with the Manchester wheelset and a quarter of the car above it.
    let quarter = "type = \"quarter_car\"\nlength = 25.0\nwheel_mass = 1813.0\nbody_mass = 9307.5\nsuspension_stiffness = 4.8e5\nsuspension_damping = 2.0e4\n";
    // (wheels, µs per step, µs per step with every car coupled) of each row, for the growth
    // lines below the table.
    let mut rows: Vec<(usize, f64, f64)> = Vec::new();
    for cars in [0usize, 1, 4, 8, 16] {
        let vehicles = if cars == 0 {
            format!("[[train.vehicles]]\n{quarter}")
        } else {
            format!("[[train.vehicles]]\ncount = {cars}\n{car}")
        };
        let text = format!(
            "kind = \"vehicle_bridge\"\n{bridge}[train]\nspeed = 83.333\nposition = 20.0\n{vehicles}[contact]\nmodel = \"hertz\"\n[integrator]\nmethod = \"generalized_alpha\"\ndt = 1e-4\nduration = 0.1\n"
        );
        // (wall time, steps) of the run, with the held and detached cars or every car coupled.
        let time = |every_car: bool| -> Result<(f64, usize)> {
            let config = sim::config::vehicle_bridge::parse(&text)?;
            let mut sim =
                sim::vehicle_bridge::Simulation::with_vehicles(config.scenario, config.vehicles)?;
            sim.hold_resting_vehicles(!every_car);
            sim.solve_detached_vehicles(!every_car);
            let start = Instant::now();
            let summary = sim.run(|_| {})?;
            Ok((start.elapsed().as_secs_f64(), summary.solver.steps))
        };
        let (wall, steps) = time(false)?;
        let (wall_every, steps_every) = time(true)?;
        println!(
            "{:>8} {cars:>6} {steps:>8} {wall:>10.4} {:>12.1} {:>14.2} {:>22.1}",
            (4 * cars).max(1),
            1e6 * wall / steps as f64,
            0.1 / wall,
            1e6 * wall_every / steps_every as f64
        );
        rows.push((
            (4 * cars).max(1),
            1e6 * wall / steps as f64,
            1e6 * wall_every / steps_every as f64,
        ));
    }
    // Issue #10: µs per step may grow no worse than linearly in the wheels.
    if let (Some(&(w0, t0, e0)), Some(&(w1, t1, e1))) = (rows.get(1), rows.last()) {
        println!(
            "growth {w0} -> {w1} wheels: {:.2}x the µs per step ({:.2}x with every car coupled) for {:.0}x the wheels (target: at most linear); 32 wheels target <= 5 µs/step (>= 20x real time)",
            t1 / t0,
            e1 / e0,
            w1 as f64 / w0 as f64
        );
    }
    // The whole crossing (leading axle at the span's entry until the last wheel has left):
    // the per-step cost averaged over cars ahead of, on and behind the span.
    let text = format!(
        "kind = \"vehicle_bridge\"\n{bridge}[train]\nspeed = 83.333\nposition = 0.0\n[[train.vehicles]]\ncount = 8\n{car}[contact]\nmodel = \"hertz\"\n[integrator]\nmethod = \"generalized_alpha\"\ndt = 1e-4\n"
    );
    let config = sim::config::vehicle_bridge::parse(&text)?;
    let mut sim = sim::vehicle_bridge::Simulation::with_vehicles(config.scenario, config.vehicles)?;
    let start = Instant::now();
    let summary = sim.run(|_| {})?;
    let wall = start.elapsed().as_secs_f64();
    let steps = summary.solver.steps;
    let simulated = steps as f64 * 1e-4;
    let car_steps = (8 * steps) as f64;
    println!(
        "whole crossing, 8 cars (32 wheels): {steps} steps, {simulated:.3} s simulated in {wall:.3} s: {:.1} µs/step, {:.2} × real time (target >= 20); car-steps at rest {:.0} %, off the span on their own {:.0} %",
        1e6 * wall / steps as f64,
        simulated / wall,
        100.0 * sim.held_vehicle_steps() as f64 / car_steps,
        100.0 * sim.detached_vehicle_steps() as f64 / car_steps
    );
    let hslm = sim::train::hslm::by_name("HSLM-A1").ok_or_else(|| anyhow!("no HSLM-A1"))?;
    let axles: Vec<beam::Axle> = hslm
        .axles(9.81)?
        .iter()
        .map(|a| beam::Axle {
            offset: a.offset,
            force: a.load,
        })
        .collect();
    let b = beam::AnalyticBeam::new(
        beam::Support::SimplySupported,
        beam::UniformBeam::new(25.0, 8.323e9, 2303.0)?,
        20,
    )?;
    // The same moving-force passage two ways: the sweep's passage kernel (exact modal steps,
    // peaks at midspan only) and `moving_load`'s recorded run (five histories every step).
    let damping = beam::ModalDamping::Uniform(0.02);
    let plan = beam::PassagePlan::new(&b, &damping, 1e-4, &[12.5])?;
    let mut work = plan.work();
    let start = Instant::now();
    let peaks = plan.peaks(&b, &axles, 83.333, 0.0, &mut work)?;
    let kernel_wall = start.elapsed().as_secs_f64();
    let kernel_simulated = peaks.steps as f64 * 1e-4;
    let loads = beam::MovingLoads::train(axles, 83.333)?;
    let settings = beam::MovingLoadSettings::new(1e-4, 0.0);
    let start = Instant::now();
    let r = beam::simulate_moving_loads(&b, &damping, &loads, &settings, &[12.5])?;
    let wall = start.elapsed().as_secs_f64();
    let simulated = r.times.last().copied().unwrap_or(0.0);
    println!(
        "HSLM-A1 as moving forces (50 axles) over the same span, exact modal steps at 1e-4 s:"
    );
    println!(
        "  passage kernel (peaks at midspan, as `sweep`): {kernel_simulated:.3} s simulated in {kernel_wall:.4} s ({:.0} × real time; target >= 500)",
        kernel_simulated / kernel_wall
    );
    println!(
        "  moving_load (histories of every step):         {simulated:.3} s simulated in {wall:.4} s ({:.0} × real time)",
        simulated / wall
    );
    Ok(())
}

//! `dyncontact`: contact in dynamical simulations.
//!
//! Subcommands: `run` (a scenario file, or the built-in default), `contact` (a quasi-static
//! normal contact case), `bench` (performance tables).
//!
//! Exit codes (see [`errors`]): 0 success, 1 the run failed or was interrupted, 2 bad input.

mod ball_drop_cli;
mod ball_drop_summary;
mod bench;
mod bench_coupling;
mod bench_small_grids;
mod bench_tamaas;
mod bench_tangential;
mod bench_track;
mod contact_case;
mod creep_curve_cli;
mod errors;
mod interrupt;
mod modes_cli;
mod moving_load_cli;
mod output;
mod plot;
mod profile_sweep_cli;
mod sweep_cli;
mod vehicle_bridge_cli;
mod vehicle_bridge_output;
mod wheel_rail_cli;

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand, ValueEnum};
use sim::config::ScenarioConfig;

use errors::bad_input;

/// The built-in default scenario of `dyncontact run` (the example file itself, embedded).
const DEFAULT_SCENARIO: &str = vehicle_bridge_cli::DEFAULT;
const DEFAULT_SCENARIO_PATH: &str = "examples/vehicle_bridge_default.toml";

#[derive(Parser)]
#[command(
    name = "dyncontact",
    version,
    about = "Contact in dynamical simulations: elastic half-space contact, time integrators, bridge dynamics",
    after_help = "Scenario kinds of `run`: ball_drop, contact, moving_load, sweep, vehicle_bridge.\n\
Examples of each in examples/ (copy one, or `dyncontact init KIND > my.toml`, to start your own);\n\
every key is documented in docs/*.md (README.md lists the pages). SI units everywhere.\n\
Exit codes: 0 ok, 1 run failed or interrupted, 2 bad input."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scenario file (dispatch on its `kind`), or the built-in default scenario.
    Run {
        /// Scenario file (TOML). Omit to run the built-in default scenario.
        file: Option<PathBuf>,
        /// Output directory for time series, summary and plots.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Print the JSON summary on standard output.
        #[arg(long)]
        json: bool,
        /// Override the `[integrator] method` of a ball_drop scenario: euler, rk4, dopri5,
        /// backward_euler, radau5, bdf, adams, verlet, leapfrog, newmark, hht,
        /// generalized_alpha. Other kinds set it in the file: vehicle_bridge newmark
        /// (trapezoidal), linear_acceleration, hht, generalized_alpha, backward_euler, radau5;
        /// moving_load exact or a structural method (docs/integrators.md).
        #[arg(long)]
        integrator: Option<String>,
        /// Largest estimated work of the run in floating-point operations (default 1e16, about 1e9 per second;
        /// docs/scenarios.md): runs estimated above it are refused before they start.
        #[arg(long)]
        max_work: Option<f64>,
    },
    /// Solve a quasi-static contact case (TOML): normal, and tangential (shift, rolling) when
    /// the case has `[friction]` and `[kinematics]`.
    Contact {
        /// Case file (TOML).
        file: PathBuf,
        /// Print one JSON object instead of the readable summary.
        #[arg(long)]
        json: bool,
        /// Output directory for pressure.csv, the plots and summary.json (and traction.csv
        /// with friction).
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
    /// Wheel–rail contact geometry and forces against the wheelset's lateral shift: contact
    /// points, rolling radius difference, contact angles, equivalent conicity (a contact case
    /// with `[gap] kind = "wheel_rail"`; docs/profiles.md).
    ProfileSweep {
        /// Case file (TOML) with `[gap] kind = "wheel_rail"`.
        file: PathBuf,
        /// First lateral shift, in metres.
        #[arg(long, default_value_t = -0.01, allow_hyphen_values = true)]
        from: f64,
        /// Last lateral shift, in metres.
        #[arg(long, default_value_t = 0.01, allow_hyphen_values = true)]
        to: f64,
        /// Step of the lateral shift, in metres.
        #[arg(long, default_value_t = 0.0005)]
        step: f64,
        /// Amplitudes of the equivalent conicity, in metres, comma-separated.
        #[arg(long, default_value = "0.001,0.002,0.003,0.004,0.005,0.006,0.008,0.01")]
        amplitudes: String,
        /// Output directory for profile_sweep.csv, conicity.csv, the plots and summary.json.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Print the JSON summary on standard output.
        #[arg(long)]
        json: bool,
    },
    /// Modal analysis of a bridge: table of n, βL, ω, f (from a file's `[bridge]` section).
    Modes {
        /// Bridge file (TOML with a `[bridge]` section, or any scenario file that has one).
        file: PathBuf,
        /// Print JSON (`modes`: list of `n`, `beta_l`, `omega`, `frequency`).
        #[arg(long)]
        json: bool,
        /// Output directory for mode_shapes.csv, modes.png and modes.json.
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
    /// Creep force against creepage in steady rolling: exact, FASTSIM and linear theory
    /// (a contact case with `[friction]`; see docs/tangential.md).
    CreepCurve {
        /// Case file (TOML) with `[friction] mu`.
        file: PathBuf,
        /// Sweep the longitudinal creepage: start:stop:count.
        #[arg(long, allow_hyphen_values = true)]
        creepage_x: Option<String>,
        /// Sweep the lateral creepage: start:stop:count.
        #[arg(long, allow_hyphen_values = true)]
        creepage_y: Option<String>,
        /// Sweep the spin [1/m]: start:stop:count.
        #[arg(long, allow_hyphen_values = true)]
        spin: Option<String>,
        /// Output directory for creep_curve.csv, creep_curve.json, creep_curve.png.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Print the JSON on standard output instead of the table.
        #[arg(long)]
        json: bool,
    },
    /// Speed sweep (`kind = "sweep"`): every train at every speed, the Eurocode deck
    /// acceleration check, plots (docs/sweep.md).
    Sweep {
        /// Sweep file (TOML, kind = "sweep").
        file: PathBuf,
        /// Output directory (summary.json, sweep.csv, plots; shard.json with --shard).
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Print the JSON summary on standard output.
        #[arg(long)]
        json: bool,
        /// Run only the K-th of N disjoint slices of the (train, speed) list and write
        /// shard.json (combine with `dyncontact sweep-merge`).
        #[arg(long)]
        shard: Option<String>,
    },
    /// Combine the shard.json of `dyncontact sweep --shard K/N` runs into the outputs of the
    /// whole sweep.
    SweepMerge {
        /// The shards' output directories.
        dirs: Vec<PathBuf>,
        /// Output directory.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Print the JSON summary on standard output.
        #[arg(long)]
        json: bool,
    },
    /// Write a commented template scenario of one kind (a copy of its example in examples/)
    /// to start your own: `dyncontact init vehicle_bridge > my.toml`.
    Init {
        /// Scenario kind: ball_drop, contact, moving_load, sweep, vehicle_bridge.
        kind: String,
        /// Write the template to this file (refused if it exists) instead of standard output.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Benchmarks: print a table of timings.
    Bench {
        /// What to benchmark.
        target: BenchTarget,
        /// Largest grid of the contact benchmark (N × N).
        #[arg(long, default_value_t = 1024)]
        max_n: usize,
    },
}

#[derive(Clone, Copy, ValueEnum)]
enum BenchTarget {
    /// The normal contact solver on Hertz spheres, N = 64 … 1024.
    Contact,
    /// Bridge modes: mode evaluation, FE eigen-solve, a moving-load run.
    Beam,
    /// The ball drop (1 s, 4 bounces) with every integrator at 1e-6 accuracy in the first
    /// peak force: wall time, steps, f-evaluations.
    Integrators,
    /// The default vehicle-bridge scenario with BEM contact (32 × 32) at every step, Picard
    /// and quasi-Newton coupling: wall time per step, simulated/wall time, iterations; an
    /// 8-car train with BEM contact at every wheel.
    Coupling,
    /// Tangential contact: steady rolling (Newton–Krylov with the line and the Jacobi
    /// preconditioner, Gauss–Seidel) on 44² … 400² (time, iterations, FFT products), a 41-point
    /// creep curve, a shift and transient rolling.
    Tangential,
    /// The HSLM-A envelope on a 20 m simply supported bridge (f1 = 5 Hz, 3 modes): 10 trains ×
    /// 57 speeds, 140 … 420 km/h.
    Sweep,
    /// Bogie-vehicle trains in the coupled model: µs per step against the number of wheels;
    /// HSLM-A1 as moving forces.
    Trains,
    /// A quarter car over a 25 m bridge on ballasted track (docs/track.md): µs per step
    /// against the approach and exit length (20, 60, 120 m), and without the track.
    Track,
}

fn main() {
    restore_default_sigpipe();
    interrupt::install();
    if let Err(e) = run_cli() {
        eprintln!("error: {}", errors::error_text(&e));
        std::process::exit(errors::exit_code(&e));
    }
    std::process::exit(errors::EXIT_OK);
}

/// Let `dyncontact ... | head` end quietly like other Unix tools instead of panicking on a
/// closed pipe (Rust ignores SIGPIPE by default).
fn restore_default_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called first thing in main, before any other thread exists; restoring the default
    // disposition of SIGPIPE has no other effect on the program.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// The name a scenario file goes by in plot headings: its file name.
fn scenario_name(file: &Path) -> String {
    file.file_name().map_or_else(
        || file.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

fn run_cli() -> Result<()> {
    let cli = Cli::parse();
    match &cli.command {
        Command::Run { file: None, .. } => {
            plot::set_scenario(format!("built-in default ({DEFAULT_SCENARIO_PATH})"))
        }
        Command::Run { file: Some(f), .. }
        | Command::Contact { file: f, .. }
        | Command::ProfileSweep { file: f, .. }
        | Command::Modes { file: f, .. }
        | Command::CreepCurve { file: f, .. }
        | Command::Sweep { file: f, .. } => plot::set_scenario(scenario_name(f)),
        Command::Init { .. } => {}
        Command::SweepMerge { dirs, .. } => plot::set_scenario(format!(
            "merged shards of {}",
            dirs.first()
                .map_or_else(String::new, |d| d.display().to_string())
        )),
        Command::Bench { .. } => {}
    }
    match cli.command {
        Command::Run {
            file,
            out,
            json,
            integrator,
            max_work,
        } => run_scenario(file.as_deref(), &out, json, integrator.as_deref(), max_work),
        Command::Contact { file, json, out } => {
            let text = read(&file)?;
            output::set_input(scenario_name(&file), text.clone());
            if let Ok(table) = text.parse::<toml::Table>()
                && let Some(kind) = table.get("kind").and_then(|k| k.as_str())
                && kind != "contact"
            {
                return Err(bad_input(anyhow::anyhow!(
                    "{} is a {kind} scenario (kind = \"{kind}\"), not a contact case: use `dyncontact run {}`",
                    file.display(),
                    file.display()
                )));
            }
            if let Some(case) = sim::config::wheel_rail::parse(&text, base_dir(&file))
                .map_err(|e| bad_input(e.into()))?
            {
                return run_wheel_rail(case, json, &out);
            }
            let case = contact_case::parse(&text, base_dir(&file)).map_err(bad_input)?;
            run_contact(case, json, Some(&out))
        }
        Command::ProfileSweep {
            file,
            from,
            to,
            step,
            amplitudes,
            out,
            json,
        } => {
            let text = read(&file)?;
            output::set_input(scenario_name(&file), text.clone());
            profile_sweep_cli::run(
                &text,
                base_dir(&file),
                (from, to, step),
                &amplitudes,
                &out,
                json,
            )
        }
        Command::Modes { file, json, out } => {
            let text = read(&file)?;
            output::set_input(scenario_name(&file), text.clone());
            modes_cli::run(&text, json, Some(&out))
        }
        Command::Bench { target, max_n } => match target {
            BenchTarget::Contact => bench::contact(max_n),
            BenchTarget::Beam => bench::beam(),
            BenchTarget::Integrators => ball_drop_cli::bench_integrators(1e-6),
            BenchTarget::Coupling => bench_coupling::bench(vehicle_bridge_cli::DEFAULT),
            BenchTarget::Tangential => bench_tangential::tangential(),
            BenchTarget::Sweep => bench::sweep(),
            BenchTarget::Trains => bench::trains(),
            BenchTarget::Track => bench_track::track(),
        },
        Command::Sweep {
            file,
            out,
            json,
            shard,
        } => {
            let shard = match shard {
                Some(s) => sweep_cli::parse_shard(&s)?,
                None => sim::sweep::Shard::ALL,
            };
            let text = read(&file)?;
            output::set_input(scenario_name(&file), text.clone());
            match sim::config::load(&text, base_dir(&file), &Default::default())
                .map_err(|e| bad_input(e.into()))?
            {
                ScenarioConfig::Sweep(config) => {
                    sweep_cli::run(*config, &text, base_dir(&file), &out, json, shard)
                }
                other => Err(bad_input(anyhow::anyhow!(
                    "{} is a {} scenario, not a sweep: use `dyncontact run`",
                    file.display(),
                    other.kind()
                ))),
            }
        }
        Command::SweepMerge { dirs, out, json } => sweep_cli::merge(&dirs, &out, json),
        Command::Init { kind, out } => init(&kind, out.as_deref()),
        Command::CreepCurve {
            file,
            creepage_x,
            creepage_y,
            spin,
            out,
            json,
        } => creep_curve_cli::run(
            &{
                let text = read(&file)?;
                output::set_input(scenario_name(&file), text.clone());
                text
            },
            base_dir(&file),
            [
                creepage_x.as_deref(),
                creepage_y.as_deref(),
                spin.as_deref(),
            ],
            &out,
            json,
        ),
    }
}

/// The template of each scenario kind: its example file (commented, tested by
/// `tests/examples_golden.rs`).
const TEMPLATES: [(&str, &str, &str); 5] = [
    (
        "ball_drop",
        "examples/ball_drop_steel.toml",
        include_str!("../../../examples/ball_drop_steel.toml"),
    ),
    (
        "contact",
        "examples/hertz_sphere.toml",
        include_str!("../../../examples/hertz_sphere.toml"),
    ),
    (
        "moving_load",
        "examples/moving_load_fryba.toml",
        include_str!("../../../examples/moving_load_fryba.toml"),
    ),
    (
        "sweep",
        "examples/sweep_hslm.toml",
        include_str!("../../../examples/sweep_hslm.toml"),
    ),
    ("vehicle_bridge", DEFAULT_SCENARIO_PATH, DEFAULT_SCENARIO),
];

/// `dyncontact init KIND [--out FILE]`.
fn init(kind: &str, out: Option<&Path>) -> Result<()> {
    let Some((_, source, text)) = TEMPLATES.iter().find(|(k, _, _)| *k == kind) else {
        let kinds: Vec<&str> = TEMPLATES.iter().map(|t| t.0).collect();
        return Err(bad_input(anyhow::anyhow!(
            "init: unknown scenario kind \"{kind}\" (known: {})",
            kinds.join(", ")
        )));
    };
    let header = format!(
        "# Template for kind = \"{kind}\", a copy of {source}. Edit the values (SI units);\n\
         # every key is documented in docs/ (README.md lists the pages). Run it with\n\
         # `dyncontact run FILE --out DIR`.\n"
    );
    match out {
        None => print!("{header}{text}"),
        Some(path) => {
            if path.exists() {
                return Err(bad_input(anyhow::anyhow!(
                    "init: {} exists; not overwritten",
                    path.display()
                )));
            }
            std::fs::write(path, format!("{header}{text}"))
                .with_context(|| format!("cannot write {}", path.display()))
                .map_err(bad_input)?;
            eprintln!(
                "wrote {} (kind = \"{kind}\"); run it with `dyncontact run {} --out DIR`",
                path.display(),
                path.display()
            );
        }
    }
    Ok(())
}

fn read(path: &Path) -> Result<String> {
    std::fs::read_to_string(path)
        .with_context(|| format!("cannot read {}", path.display()))
        .map_err(bad_input)
}

fn base_dir(path: &Path) -> &Path {
    path.parent().unwrap_or(Path::new("."))
}

fn run_scenario(
    file: Option<&Path>,
    out: &Path,
    json: bool,
    integrator: Option<&str>,
    max_work: Option<f64>,
) -> Result<()> {
    let (text, base) = match file {
        Some(f) => (read(f)?, base_dir(f).to_path_buf()),
        None => {
            eprintln!("running the built-in default scenario ({DEFAULT_SCENARIO_PATH})");
            (DEFAULT_SCENARIO.to_string(), PathBuf::from("."))
        }
    };
    output::set_input(
        file.map_or_else(
            || format!("built-in default ({DEFAULT_SCENARIO_PATH})"),
            scenario_name,
        ),
        text.clone(),
    );
    let options = sim::config::LoadOptions {
        integrator: integrator.map(str::to_string),
        max_work,
    };
    if is_wheel_rail(&text)
        && integrator.is_none()
        && let Some(case) =
            sim::config::wheel_rail::parse(&text, &base).map_err(|e| bad_input(e.into()))?
    {
        return run_wheel_rail(case, json, out);
    }
    match sim::config::load(&text, &base, &options).map_err(|e| bad_input(e.into()))? {
        ScenarioConfig::BallDrop(config) => ball_drop_cli::run(*config, out, json),
        ScenarioConfig::Contact(case) => run_contact(*case, json, Some(out)),
        ScenarioConfig::MovingLoad(config) => moving_load_cli::run(*config, out, json),
        ScenarioConfig::VehicleBridge(config) => vehicle_bridge_cli::run(*config, out, json),
        ScenarioConfig::Sweep(config) => {
            sweep_cli::run(*config, &text, &base, out, json, sim::sweep::Shard::ALL)
        }
    }
}

/// A contact case whose `[gap]` has `kind = "wheel_rail"`.
fn is_wheel_rail(text: &str) -> bool {
    let Ok(table) = text.parse::<toml::Table>() else {
        return false;
    };
    table.get("kind").and_then(|k| k.as_str()) == Some("contact")
        && table
            .get("gap")
            .and_then(|g| g.get("kind"))
            .and_then(|k| k.as_str())
            == Some("wheel_rail")
}

fn run_wheel_rail(
    case: sim::config::wheel_rail::WheelRailConfig,
    json: bool,
    out: &Path,
) -> Result<()> {
    let run_out = output::RunOutput::create(out, wheel_rail_cli::OUTPUT_SET)?;
    let outcome = sim::wheel_rail_case::solve(&case)?;
    if json {
        println!("{}", output::json_text(&outcome.summary)?);
    } else {
        wheel_rail_cli::print_summary(&outcome.summary);
    }
    wheel_rail_cli::write_outputs(&run_out, &case.wheelset, &outcome)?;
    run_out.commit()?;
    if !json {
        let written: Vec<&str> = wheel_rail_cli::OUTPUT_SET
            .iter()
            .copied()
            .filter(|name| out.join(name).exists())
            .collect();
        println!("wrote {}/{}", out.display(), written.join(", "));
    }
    Ok(())
}

fn run_contact(case: contact_case::PreparedCase, json: bool, out: Option<&Path>) -> Result<()> {
    let run_out = out
        .map(|dir| output::RunOutput::create(dir, contact_case::OUTPUT_SET))
        .transpose()?;
    let outcome = contact_case::solve(&case)?;
    if json {
        println!("{}", output::json_text(&outcome.summary)?);
    } else {
        contact_case::print_summary(&outcome.summary);
    }
    if let (Some(dir), Some(run_out)) = (out, run_out) {
        contact_case::write_outputs(&run_out, &outcome)?;
        run_out.commit()?;
        if !json {
            let written: Vec<&str> = contact_case::OUTPUT_SET
                .iter()
                .copied()
                .filter(|name| dir.join(name).exists())
                .collect();
            println!("wrote {}/{}", dir.display(), written.join(", "));
        }
    }
    if !outcome.summary.converged {
        bail!(
            "NormCG did not converge in {} iterations (relative change {:.3e}); the output is marked converged = false",
            outcome.summary.iterations,
            outcome.summary.residual
        );
    }
    Ok(())
}

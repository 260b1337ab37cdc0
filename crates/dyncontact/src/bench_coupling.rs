//! `dyncontact bench coupling`: the default `vehicle_bridge` scenario (BEM contact) with each
//! coupling solver and with the reuse of full solves, and issue #14's 8-car BEM train
//! (docs/vehicle_bridge.md).

use anyhow::{Result, anyhow};
use sim::vehicle_bridge::{ContactModel, CouplingSolver};

use crate::vehicle_bridge_cli::{simulate, simulate_full};

/// The `reuse_tol` of the reuse row of `dyncontact bench coupling` (the default scenario's
/// force history, peak deflection and peak acceleration within 1e-4 of the full solves':
/// `crates/sim/tests/vehicle_bridge_bem_reuse.rs`).
pub const BENCH_REUSE_TOL: f64 = 3e-6;

/// `dyncontact bench coupling`: the default scenario (BEM contact, 32 × 32 grid) with Picard
/// and quasi-Newton coupling, and quasi-Newton with the reuse of full solves
/// (`reuse_tol` = [`BENCH_REUSE_TOL`], references.md §C8.4); wall time per step, simulated
/// seconds per wall second, mean coupling and contact-solver iterations per step, full solves.
pub fn bench(default_scenario: &str) -> Result<()> {
    println!(
        "default vehicle_bridge scenario, BEM contact 32 x 32 at every step; {} rayon threads",
        rayon::current_num_threads()
    );
    println!(
        "{:>13} {:>9} {:>8} {:>11} {:>12} {:>13} {:>13} {:>16} {:>8} {:>11} {:>13}",
        "solver",
        "reuse_tol",
        "steps",
        "wall [s]",
        "µs/step",
        "sim s/wall s",
        "iter/step",
        "contact it/step",
        "failed",
        "full solves",
        "factor solves"
    );
    for (solver, reuse_tol) in [
        ("picard", 0.0),
        ("quasi_newton", 0.0),
        ("quasi_newton", BENCH_REUSE_TOL),
    ] {
        let mut scenario = sim::config::vehicle_bridge::parse(default_scenario)?.scenario;
        scenario.contact = match scenario.contact {
            ContactModel::Bem { tol, .. } => ContactModel::Bem {
                elements: 32,
                tol,
                reuse_tol,
            },
            _ => ContactModel::Bem {
                elements: 32,
                tol: 1e-8,
                reuse_tol,
            },
        };
        scenario.coupling.solver = CouplingSolver::by_name(solver).expect("known name");
        match simulate(scenario, usize::MAX, 0) {
            Ok(o) => {
                let s = &o.summary;
                println!(
                    "{:>13} {:>9.0e} {:>8} {:>11.3} {:>12.1} {:>13.2} {:>13.2} {:>16.2} {:>8} {:>11} {:>13}",
                    solver,
                    reuse_tol,
                    s.solver.steps,
                    s.wall_time_s,
                    1e6 * s.wall_time_s / s.solver.steps.max(1) as f64,
                    s.simulated_time_s / s.wall_time_s,
                    s.solver.mean_iterations_per_step,
                    s.solver.mean_contact_iterations_per_step,
                    s.solver.failed_steps,
                    s.contact.full_solves.unwrap_or(0),
                    s.contact.factor_solves.unwrap_or(0)
                );
            }
            Err(e) => println!("{solver:>13} failed: {}", crate::errors::error_text(&e)),
        }
    }
    bench_bem_train(default_scenario)
}

/// The train row of `dyncontact bench coupling` (issue #14): the default scenario's bridge,
/// contact, integrator and coupling tables with eight Manchester bogie cars (32 wheels,
/// docs/trains.md) at 300 km/h instead of its quarter car and without its irregularity, BEM
/// contact at every wheel with the reuse of full solves ([`BENCH_REUSE_TOL`]). The leading axle
/// starts 1 m before the span; the first second (four cars cross the span).
const BENCH_BEM_TRAIN: &str = "[train]\nspeed = 83.333333\nposition = -1.0\n[[train.vehicles]]\npreset = \"Manchester\"\ncount = 8\n";

/// The table `[name]` of a scenario text: from its header to the next table header.
fn toml_table<'a>(text: &'a str, name: &str) -> Result<&'a str> {
    let header = format!("\n[{name}]\n");
    let start = text
        .find(&header)
        .ok_or_else(|| anyhow!("the default scenario has no [{name}] table"))?
        + 1;
    let end = text[start + header.len() - 1..]
        .find("\n[")
        .map_or(text.len(), |i| start + header.len() - 1 + i + 1);
    Ok(&text[start..end])
}

fn bench_bem_train(default_scenario: &str) -> Result<()> {
    let text = format!(
        "kind = \"vehicle_bridge\"\n{}{BENCH_BEM_TRAIN}{}reuse_tol = {BENCH_REUSE_TOL:e}\n{}duration = 1.0\n{}",
        toml_table(default_scenario, "bridge")?,
        toml_table(default_scenario, "contact")?,
        toml_table(default_scenario, "integrator")?,
        toml_table(default_scenario, "coupling")?,
    );
    let mut config = sim::config::vehicle_bridge::parse(&text)?;
    println!(
        "\n8 Manchester cars (32 wheels), BEM 32 x 32 at every wheel, reuse_tol = {BENCH_REUSE_TOL:.0e}, \
         the default bridge, 83.33 m/s, dt = {:e} s, the first 1 s; {} rayon threads",
        config.scenario.dt,
        rayon::current_num_threads()
    );
    let parts = config.take_parts();
    let outcome = simulate_full(config.scenario, parts, config.train, usize::MAX, 0, None)?;
    let s = &outcome.summary;
    println!(
        "{:>8} {:>11} {:>12} {:>13} {:>13} {:>12} {:>13} {:>10} {:>12} {:>12} {:>12}",
        "steps",
        "wall [s]",
        "µs/step",
        "sim s/wall s",
        "iter/step",
        "full solves",
        "factor solves",
        "reused",
        "table evals",
        "table solves",
        "max estimate"
    );
    println!(
        "{:>8} {:>11.3} {:>12.1} {:>13.2} {:>13.2} {:>12} {:>13} {:>10} {:>12} {:>12} {:>12.2e}",
        s.solver.steps,
        s.wall_time_s,
        1e6 * s.wall_time_s / s.solver.steps.max(1) as f64,
        s.simulated_time_s / s.wall_time_s,
        s.solver.mean_iterations_per_step,
        s.contact.full_solves.unwrap_or(0),
        s.contact.factor_solves.unwrap_or(0),
        s.contact.reused_evaluations.unwrap_or(0),
        s.contact.table_evaluations.unwrap_or(0),
        s.contact.table_solves.unwrap_or(0),
        s.contact.max_reuse_error_estimate.unwrap_or(0.0),
    );
    Ok(())
}

//! `dyncontact creep-curve CASE.toml --creepage-x 0:0.004:41` (or `--creepage-y`, `--spin`):
//! creep force against creepage in steady rolling, with the exact half-space solver, FASTSIM
//! and Kalker's linear theory side by side. Writes creep_curve.csv, creep_curve.json and
//! creep_curve.png. See docs/tangential.md.

use std::path::Path;

use anyhow::{Result, anyhow, bail};
use sim::creep_curve::{self, CreepCurve, CreepVariable, CurvePoint};

use crate::contact_case;
use crate::errors::{BadInput, bad_input};
use crate::output::{self, RunOutput};
use crate::plot;

/// Parse `start:stop:count` into `count` equally spaced values (count ≥ 1; count = 1 gives
/// `start`).
pub fn parse_range(spec: &str, flag: &str) -> Result<Vec<f64>> {
    let parts: Vec<&str> = spec.split(':').collect();
    if parts.len() != 3 {
        bail!("{flag} = \"{spec}\": expected start:stop:count, e.g. 0:0.004:41");
    }
    let start: f64 = parts[0]
        .trim()
        .parse()
        .map_err(|e| anyhow!("{flag}: start \"{}\": {e}", parts[0]))?;
    let stop: f64 = parts[1]
        .trim()
        .parse()
        .map_err(|e| anyhow!("{flag}: stop \"{}\": {e}", parts[1]))?;
    let count: usize = parts[2]
        .trim()
        .parse()
        .map_err(|e| anyhow!("{flag}: count \"{}\": {e}", parts[2]))?;
    if !start.is_finite() || !stop.is_finite() {
        bail!("{flag} = \"{spec}\": start and stop must be finite numbers");
    }
    if count == 0 || count > 100_000 {
        bail!("{flag} = \"{spec}\": count must lie in 1..=100000");
    }
    Ok((0..count)
        .map(|k| {
            if count == 1 {
                start
            } else {
                start + (stop - start) * k as f64 / (count - 1) as f64
            }
        })
        .collect())
}

/// Run the subcommand.
pub fn run(
    text: &str,
    base: &Path,
    sweeps: [Option<&str>; 3],
    out: &Path,
    json: bool,
) -> Result<()> {
    let flags = ["--creepage-x", "--creepage-y", "--spin"];
    let chosen: Vec<usize> = (0..3).filter(|&i| sweeps[i].is_some()).collect();
    if chosen.len() != 1 {
        return Err(BadInput::error(
            "give exactly one of --creepage-x, --creepage-y, --spin (start:stop:count)",
        ));
    }
    let which = chosen[0];
    let values = parse_range(sweeps[which].expect("chosen"), flags[which]).map_err(bad_input)?;
    let case = contact_case::parse(text, base).map_err(bad_input)?;
    creep_curve::check(&case).map_err(|e| bad_input(e.into()))?;
    let run_out = RunOutput::create(out, OUTPUT_SET)?;
    let variable = [
        CreepVariable::CreepageX,
        CreepVariable::CreepageY,
        CreepVariable::Spin,
    ][which];
    let curve = creep_curve::compute(&case, variable, &values, flags[which], &|| true)?;
    let not_converged: Vec<f64> = curve
        .points
        .iter()
        .zip(&values)
        .filter(|(p, _)| !p.exact_converged)
        .map(|(_, &v)| v)
        .collect();
    for v in &not_converged {
        eprintln!(
            "warning: exact solver at {} = {v:e} did not converge; the point is kept, flagged exact_converged = false",
            flags[which]
        );
    }
    write(&run_out, &curve, which)?;
    run_out.commit()?;
    if json {
        println!("{}", output::json_text(&curve)?);
    } else {
        print_table(&curve, which);
        println!(
            "wrote {}/creep_curve.csv, creep_curve.json, creep_curve.png",
            out.display()
        );
    }
    if !not_converged.is_empty() {
        bail!(
            "the exact solver did not converge at {} of {} points ({} = {}); they are kept in the outputs with exact_converged = false",
            not_converged.len(),
            values.len(),
            flags[which],
            not_converged
                .iter()
                .map(|v| format!("{v:e}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    Ok(())
}

fn swept(p: &CurvePoint, which: usize) -> f64 {
    [p.creepage_x, p.creepage_y, p.spin][which]
}

fn print_table(c: &CreepCurve, which: usize) {
    let lim = c.mu * c.normal_force;
    let comp = if which == 0 { "F_x" } else { "F_y" };
    println!(
        "creep curve: {comp}/(mu Fn) against {} (mu Fn = {lim:.4e} N, {} x {} grid, exact solver {:.3} s in total)",
        c.variable, c.grid_nx, c.grid_ny, c.exact_time_s
    );
    println!(
        "{:>12} {:>10} {:>10} {:>10} {:>6} {:>6} {:>7}",
        c.variable, "exact", "FASTSIM", "linear", "adh", "slip", "iters"
    );
    let opt = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{:.5}", v / lim));
    for p in &c.points {
        let (e, f, l) = if which == 0 {
            (p.exact_force_x, p.fastsim_force_x, p.linear_force_x)
        } else {
            (p.exact_force_y, p.fastsim_force_y, p.linear_force_y)
        };
        println!(
            "{:>12.4e} {:>10.5} {:>10} {:>10} {:>6} {:>6} {:>7}",
            swept(p, which),
            e / lim,
            opt(f),
            opt(l),
            p.exact_adhesion_elements,
            p.exact_slip_elements,
            p.exact_sweeps
        );
    }
}

/// The files `creep-curve` writes (one run's output set).
const OUTPUT_SET: &[&str] = &["creep_curve.csv", "creep_curve.json", "creep_curve.png"];

fn write(dir: &RunOutput, c: &CreepCurve, which: usize) -> Result<()> {
    let nan = |v: Option<f64>| v.unwrap_or(f64::NAN);
    output::write_csv(
        &dir.path("creep_curve.csv"),
        &[
            "creepage_x",
            "creepage_y",
            "spin_1_m",
            "exact_fx_n",
            "exact_fy_n",
            "exact_mz_n_m",
            "exact_adhesion",
            "exact_slip",
            "fastsim_fx_n",
            "fastsim_fy_n",
            "linear_fx_n",
            "linear_fy_n",
            "exact_converged",
        ],
        c.points.iter().map(|p| {
            vec![
                p.creepage_x,
                p.creepage_y,
                p.spin,
                p.exact_force_x,
                p.exact_force_y,
                p.exact_spin_moment,
                p.exact_adhesion_elements as f64,
                p.exact_slip_elements as f64,
                nan(p.fastsim_force_x),
                nan(p.fastsim_force_y),
                nan(p.linear_force_x),
                nan(p.linear_force_y),
                if p.exact_converged { 1.0 } else { 0.0 },
            ]
        }),
    )?;
    output::write_summary(&dir.path("creep_curve.json"), c)?;
    let lim = c.mu * c.normal_force;
    let pick = |p: &CurvePoint, k: usize| -> Option<f64> {
        match (k, which == 0) {
            (0, true) => Some(p.exact_force_x),
            (0, false) => Some(p.exact_force_y),
            (1, true) => p.fastsim_force_x,
            (1, false) => p.fastsim_force_y,
            (_, true) => p.linear_force_x,
            (_, false) => p.linear_force_y,
        }
    };
    let mut series = Vec::new();
    for (k, label) in [
        "exact (half-space)",
        "FASTSIM",
        "linear theory (Kalker's coefficients)",
    ]
    .into_iter()
    .enumerate()
    {
        let pts: Vec<(f64, f64)> = c
            .points
            .iter()
            .filter_map(|p| pick(p, k).map(|f| (swept(p, which), f / lim)))
            .collect();
        if pts.is_empty() {
            continue;
        }
        // The linear theory grows without bound: a reference clipped to the axes the
        // saturating curves set.
        series.push(if k == 2 {
            plot::Series::reference(label, pts)
        } else {
            plot::Series::new(label, pts)
        });
    }
    let comp = if which == 0 { "F_x" } else { "F_y" };
    let unit = if which == 2 { " [1/m]" } else { " [-]" };
    // Say why FASTSIM and the linear theory are missing (they need a Hertzian gap).
    let only_exact = if series.len() == 1 {
        " (exact only: FASTSIM and linear theory need a Hertzian gap)"
    } else {
        ""
    };
    plot::panels(
        &dir.path("creep_curve.png"),
        &[plot::Panel {
            title: format!("creep force {comp} against {}{only_exact}", c.variable),
            x_label: format!("{}{unit}", c.variable),
            y_label: format!("{comp} / (μ F_n) [-]"),
            series,
        }],
    )
}

//! `dyncontact creep-curve CASE.toml --creepage-x 0:0.004:41` (or `--creepage-y`, `--spin`):
//! creep force against creepage in steady rolling, with the exact half-space solver, FASTSIM
//! and Kalker's linear theory side by side. Writes creep_curve.csv, creep_curve.json and
//! creep_curve.png. See docs/tangential.md.

use std::path::Path;
use std::time::Instant;

use anyhow::{Result, anyhow, bail};
use halfspace::{
    ContactError, CoupledOptions, CoupledProblem, Creepages, NormalSolver, RollingLoad,
    TangentialMethod, TangentialOptions, TangentialSolver, TangentialStrategy, linear_forces,
    solve_coupled, tangential_strategy,
};
use serde::Serialize;

use crate::contact_case::{self, TangentialTask};
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

/// One point of the curve (forces on body 1 \[N\], moment [N m]).
#[derive(Debug, Serialize)]
pub struct CurvePoint {
    pub creepage_x: f64,
    pub creepage_y: f64,
    pub spin: f64,
    /// Whether the exact solver converged at this point (false: the exact columns are null
    /// in JSON, NaN in CSV).
    pub exact_converged: bool,
    pub exact_force_x: f64,
    pub exact_force_y: f64,
    pub exact_spin_moment: f64,
    pub exact_adhesion_elements: usize,
    pub exact_slip_elements: usize,
    pub exact_sweeps: usize,
    pub fastsim_force_x: Option<f64>,
    pub fastsim_force_y: Option<f64>,
    pub linear_force_x: Option<f64>,
    pub linear_force_y: Option<f64>,
}

/// The exact solver's result at one point.
struct ExactPoint {
    force_x: f64,
    force_y: f64,
    moment_z: f64,
    adhesion_elements: usize,
    slip_elements: usize,
    sweeps: usize,
}

impl ExactPoint {
    fn of(s: &halfspace::TangentialSolution) -> Self {
        ExactPoint {
            force_x: s.force_x,
            force_y: s.force_y,
            moment_z: s.moment_z,
            adhesion_elements: s.adhesion_elements,
            slip_elements: s.slip_elements,
            sweeps: s.iterations,
        }
    }
}

/// The JSON file.
#[derive(Debug, Serialize)]
pub struct CreepCurve {
    /// "creepage_x", "creepage_y" or "spin".
    pub variable: String,
    pub mu: f64,
    pub normal_force: f64,
    /// Hertz semi-axes used by FASTSIM and the linear theory \[m\] (null for non-Hertzian gaps).
    pub hertz_a: Option<f64>,
    pub hertz_b: Option<f64>,
    pub grid_nx: usize,
    pub grid_ny: usize,
    pub exact_time_s: f64,
    pub points: Vec<CurvePoint>,
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
    let mu = case
        .mu
        .ok_or_else(|| BadInput::error("[friction]: a creep curve needs `mu`"))?;
    let base_creep = match case.tangential.map(|t| t.task) {
        None => Creepages::default(),
        Some(TangentialTask::Rolling(RollingLoad::Creepages(c))) => c,
        Some(_) => {
            return Err(BadInput::error(
                "[kinematics]: a creep curve sweeps creepages; give creepages (the unswept ones are held) or omit [kinematics]",
            ));
        }
    };
    let run_out = RunOutput::create(out, OUTPUT_SET)?;
    let mut normal_solver =
        NormalSolver::new(case.grid, case.material).map_err(|e| anyhow!("{e}"))?;
    let normal = normal_solver
        .solve(&case.gap, case.load, &case.options)
        .map_err(|e| match e {
            ContactError::NotConverged { .. } => anyhow!("normal problem: {e}"),
            other => anyhow!("{other}"),
        })?;
    let axes = contact_case::hertz_axes(&case, normal.normal_force).ok();
    let mut solver = TangentialSolver::new(case.grid, case.material).map_err(|e| anyhow!("{e}"))?;
    let opts = TangentialOptions::default();
    // The exact curve follows `contact`'s rule: with K != 0 every point is a coupled
    // normal-tangential solve (the normal pressure changes with the tractions).
    let coupled =
        tangential_strategy(TangentialMethod::Exact, &case.material) == TangentialStrategy::Coupled;
    let mut points = Vec::with_capacity(values.len());
    let mut exact_time = 0.0;
    let mut not_converged: Vec<f64> = Vec::new();
    for &v in &values {
        let mut c = base_creep;
        match which {
            0 => c.xi = v,
            1 => c.eta = v,
            _ => c.phi = v,
        }
        let t0 = Instant::now();
        let load = RollingLoad::Creepages(c);
        let exact = if c.xi == 0.0 && c.eta == 0.0 && c.phi == 0.0 {
            // No creepage: the unique steady-rolling solution is traction-free, every loaded
            // element in adhesion (no slip velocity). The iterative solver's relative-change
            // test has nothing to measure against here, so it is not called.
            let loaded = normal.pressure.iter().filter(|&&p| p > 0.0).count();
            Ok(ExactPoint {
                force_x: 0.0,
                force_y: 0.0,
                moment_z: 0.0,
                adhesion_elements: loaded,
                slip_elements: 0,
                sweeps: 0,
            })
        } else if coupled {
            solve_coupled(
                &mut normal_solver,
                &mut solver,
                &case.gap,
                case.load,
                mu,
                CoupledProblem::SteadyRolling(load),
                &case.options,
                &opts,
                &CoupledOptions::default(),
            )
            .map(|c| ExactPoint::of(&c.tangential))
        } else {
            solver
                .steady_rolling(&normal.pressure, mu, load, &opts)
                .map(|s| ExactPoint::of(&s))
        };
        let (s, converged) = match exact {
            Ok(s) => (s, true),
            Err(
                e @ (ContactError::TangentialNotConverged { .. }
                | ContactError::NotConverged { .. }
                | ContactError::NewtonNotConverged { .. }),
            ) => {
                // Keep the run: the point is written with exact_converged = false and no
                // exact forces; the other points stand.
                eprintln!(
                    "warning: exact solver at {} = {v:e}: {e}; the point is kept, flagged exact_converged = false",
                    flags[which]
                );
                not_converged.push(v);
                let nan = ExactPoint {
                    force_x: f64::NAN,
                    force_y: f64::NAN,
                    moment_z: f64::NAN,
                    adhesion_elements: 0,
                    slip_elements: 0,
                    sweeps: opts.max_iter,
                };
                (nan, false)
            }
            Err(e) => return Err(anyhow!("exact solver at {} = {v:e}: {e}", flags[which])),
        };
        exact_time += t0.elapsed().as_secs_f64();
        let (mut fsx, mut fsy, mut lx, mut ly) = (None, None, None, None);
        if let Some((a, b)) = axes {
            let f = contact_case::fastsim_on(&case, mu, normal.normal_force, a, b, c)?;
            fsx = Some(f.force_x);
            fsy = Some(f.force_y);
            let (x, y) = linear_forces(case.material.g, case.material.nu, a, b, c.xi, c.eta, c.phi)
                .map_err(|e| anyhow!("linear theory: {e}"))?;
            lx = Some(x);
            ly = Some(y);
        }
        points.push(CurvePoint {
            creepage_x: c.xi,
            creepage_y: c.eta,
            spin: c.phi,
            exact_converged: converged,
            exact_force_x: s.force_x,
            exact_force_y: s.force_y,
            exact_spin_moment: s.moment_z,
            exact_adhesion_elements: s.adhesion_elements,
            exact_slip_elements: s.slip_elements,
            exact_sweeps: s.sweeps,
            fastsim_force_x: fsx,
            fastsim_force_y: fsy,
            linear_force_x: lx,
            linear_force_y: ly,
        });
    }
    let curve = CreepCurve {
        variable: ["creepage_x", "creepage_y", "spin"][which].into(),
        mu,
        normal_force: normal.normal_force,
        hertz_a: axes.map(|a| a.0),
        hertz_b: axes.map(|a| a.1),
        grid_nx: case.grid.nx,
        grid_ny: case.grid.ny,
        exact_time_s: exact_time,
        points,
    };
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
        c.variable, "exact", "FASTSIM", "linear", "adh", "slip", "sweeps"
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
    output::write_json(&dir.path("creep_curve.json"), c)?;
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
    plot::panels(
        &dir.path("creep_curve.png"),
        &[plot::Panel {
            title: format!("creep force {comp} against {}", c.variable),
            x_label: format!("{}{unit}", c.variable),
            y_label: format!("{comp} / (μ F_n) [-]"),
            series,
        }],
    )
}

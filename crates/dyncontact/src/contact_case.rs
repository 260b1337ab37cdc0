//! `dyncontact contact CASE.toml`: the quasi-static normal contact problem from a case file.
//!
//! Every key is in SI units; unknown keys are errors. See the README for the schema, and
//! docs/tangential.md for the \[friction\] and \[kinematics\] sections (tangential contact).

use std::path::Path;
use std::time::Instant;

use anyhow::{Result, anyhow, bail};
use halfspace::{
    ContactError, CoupledOptions, CoupledProblem, Creepages, ElementState, FastsimInput, GapShape,
    Hertz, LineHertz, NormalLoad, NormalSolution, NormalSolver, RollingLoad, TangentialOptions,
    TangentialSolution, TangentialSolver, TangentialStrategy, fastsim, linear_forces,
    solve_coupled, tangential_strategy,
};
use serde::Serialize;

use crate::output::{self, RunOutput};
use crate::plot;

pub use sim::config::contact::{PreparedCase, TangentialCase, TangentialMethod, TangentialTask};

/// Parse a case file's text (`base` resolves relative table paths).
pub fn parse(text: &str, base: &Path) -> Result<PreparedCase> {
    Ok(sim::config::contact::parse(text, base)?)
}

/// The JSON summary of a contact case.
#[derive(Debug, Serialize)]
pub struct ContactSummary {
    pub normal_force: f64,
    pub approach: f64,
    pub max_pressure: f64,
    pub contact_area: f64,
    pub elements_in_contact: usize,
    pub iterations: usize,
    pub residual: f64,
    pub converged: bool,
    pub dfn_dapproach: Option<f64>,
    pub solve_time_s: f64,
    pub centre_of_pressure: [f64; 2],
    pub grid: GridSummary,
    pub material: MaterialSummary,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hertz: Option<HertzSummary>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hertz_line: Option<LineHertzSummary>,
    /// Tangential results (top-level keys), when \[kinematics\] is given.
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub tangential: Option<TangentialSummary>,
}

/// Tangential results in the JSON summary (SI units; forces on body 1).
#[derive(Debug, Serialize)]
pub struct TangentialSummary {
    pub tangential_method: String,
    pub tangential_problem: String,
    pub mu: f64,
    pub tangential_force_x: f64,
    pub tangential_force_y: f64,
    /// M_z [N m] about the coordinate origin (null for the linear theory: C₃₃ is not tabulated).
    pub spin_moment: Option<f64>,
    pub adhesion_elements: Option<usize>,
    pub slip_elements: Option<usize>,
    /// Rolling: creepages used or found.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub creepage_x: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub creepage_y: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spin: Option<f64>,
    /// Shift: rigid shift used or found \[m\].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shift_x: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shift_y: Option<f64>,
    /// Rolling: frictional power per unit rolling speed \[N\] (× V gives W); shift: work \[J\].
    pub frictional_power: Option<f64>,
    pub tangential_iterations: Option<usize>,
    pub newton_iterations: Option<usize>,
    /// Normal–tangential outer iterations (K ≠ 0 with the exact method; absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub outer_iterations: Option<usize>,
    pub tangential_time_s: f64,
}

#[derive(Debug, Serialize)]
pub struct GridSummary {
    pub nx: usize,
    pub ny: usize,
    pub dx: f64,
    pub dy: f64,
    pub x0: f64,
    pub y0: f64,
}

#[derive(Debug, Serialize)]
pub struct MaterialSummary {
    #[serde(rename = "G")]
    pub g: f64,
    pub nu: f64,
    #[serde(rename = "K")]
    pub k: f64,
    pub e_star: f64,
}

#[derive(Debug, Serialize)]
pub struct HertzSummary {
    pub approach: f64,
    pub max_pressure: f64,
    pub a: f64,
    pub b: f64,
    pub normal_force: f64,
}

#[derive(Debug, Serialize)]
pub struct LineHertzSummary {
    pub a: f64,
    pub max_pressure: f64,
    pub force_per_length: f64,
}

/// Outcome of solving a case: the summary, and the solution (also when not converged).
pub struct CaseOutcome {
    pub summary: ContactSummary,
    pub solution: NormalSolution,
    /// The exact tangential solution, when \[kinematics\] with method = "exact" is given.
    pub tangential: Option<TangentialSolution>,
}

/// The Hertz ellipse (a, b) \[m\] of the case's quadratic gap at normal force `fn_`.
pub fn hertz_axes(case: &PreparedCase, fn_: f64) -> Result<(f64, f64)> {
    let h = case
        .shape
        .hertz(&case.material, NormalLoad::Force(fn_))
        .ok_or_else(|| anyhow!("[gap]: FASTSIM and the linear theory need a Hertzian gap"))?;
    Ok((h.a, h.b))
}

/// Solve the tangential problem of a case for the normal solution `normal`.
pub fn solve_tangential(
    case: &PreparedCase,
    t: &TangentialCase,
    normal: &NormalSolution,
) -> Result<(TangentialSummary, Option<TangentialSolution>)> {
    let start = Instant::now();
    let problem = match t.task {
        TangentialTask::Rolling(_) => "rolling",
        TangentialTask::Shift(_) => "shift",
    };
    let m = case.material;
    let mut summary = TangentialSummary {
        tangential_method: t.method.name().into(),
        tangential_problem: problem.into(),
        mu: t.mu,
        tangential_force_x: 0.0,
        tangential_force_y: 0.0,
        spin_moment: None,
        adhesion_elements: None,
        slip_elements: None,
        creepage_x: None,
        creepage_y: None,
        spin: None,
        shift_x: None,
        shift_y: None,
        frictional_power: None,
        tangential_iterations: None,
        newton_iterations: None,
        outer_iterations: None,
        tangential_time_s: 0.0,
    };
    let mut exact = None;
    match (t.method, t.task) {
        (TangentialMethod::Exact, task) => {
            let mut solver =
                TangentialSolver::new(case.grid, m).map_err(|e| anyhow!("tangential: {e}"))?;
            let opts = TangentialOptions::default();
            let sol = match task {
                TangentialTask::Rolling(load) => {
                    solver.steady_rolling(&normal.pressure, t.mu, load, &opts)
                }
                TangentialTask::Shift(load) => solver.shift(&normal.pressure, t.mu, load, &opts),
            }
            .map_err(|e| anyhow!("tangential problem: {e}"))?;
            summary.tangential_force_x = sol.force_x;
            summary.tangential_force_y = sol.force_y;
            summary.spin_moment = Some(sol.moment_z);
            summary.adhesion_elements = Some(sol.adhesion_elements);
            summary.slip_elements = Some(sol.slip_elements);
            if problem == "rolling" {
                summary.creepage_x = Some(sol.creepages.xi);
                summary.creepage_y = Some(sol.creepages.eta);
                summary.spin = Some(sol.creepages.phi);
            } else {
                summary.shift_x = Some(sol.shift.0);
                summary.shift_y = Some(sol.shift.1);
            }
            summary.frictional_power = Some(sol.frictional_power);
            summary.tangential_iterations = Some(sol.iterations);
            summary.newton_iterations = Some(sol.newton_iterations);
            exact = Some(sol);
        }
        (method, TangentialTask::Rolling(RollingLoad::Creepages(c))) => {
            let (a, b) = hertz_axes(case, normal.normal_force)?;
            summary.creepage_x = Some(c.xi);
            summary.creepage_y = Some(c.eta);
            summary.spin = Some(c.phi);
            if method == TangentialMethod::Fastsim {
                let f = fastsim_on(case, t.mu, normal.normal_force, a, b, c)?;
                summary.tangential_force_x = f.force_x;
                summary.tangential_force_y = f.force_y;
                summary.spin_moment = Some(f.moment_z);
                summary.adhesion_elements = Some(f.adhesion_elements);
                summary.slip_elements = Some(f.slip_elements);
                summary.frictional_power = Some(f.frictional_power_per_speed);
            } else {
                let (fx, fy) = linear_forces(m.g, m.nu, a, b, c.xi, c.eta, c.phi)
                    .map_err(|e| anyhow!("linear theory: {e}"))?;
                summary.tangential_force_x = fx;
                summary.tangential_force_y = fy;
            }
        }
        (method, _) => bail!(
            "[kinematics] `method` = \"{}\" needs creepages",
            method.name()
        ),
    }
    summary.tangential_time_s = start.elapsed().as_secs_f64();
    Ok((summary, exact))
}

/// The coupled normal–tangential solve of a case with K ≠ 0 (Panagiotopoulos' process).
fn solve_coupled_case(
    case: &PreparedCase,
    t: &TangentialCase,
) -> Result<(NormalSolution, TangentialSummary, TangentialSolution)> {
    let start = Instant::now();
    let mut normal = NormalSolver::new(case.grid, case.material).map_err(|e| anyhow!("{e}"))?;
    let mut tang = TangentialSolver::new(case.grid, case.material).map_err(|e| anyhow!("{e}"))?;
    let problem = match t.task {
        TangentialTask::Rolling(l) => CoupledProblem::SteadyRolling(l),
        TangentialTask::Shift(l) => CoupledProblem::Shift(l),
    };
    let c = solve_coupled(
        &mut normal,
        &mut tang,
        &case.gap,
        case.load,
        t.mu,
        problem,
        &case.options,
        &TangentialOptions::default(),
        &CoupledOptions::default(),
    )
    .map_err(|e| anyhow!("coupled normal-tangential problem (K != 0): {e}"))?;
    // The tangential summary of the final tangential solution.
    let exact_only = TangentialCase {
        method: TangentialMethod::Exact,
        ..*t
    };
    let mut summary = summary_of_exact(&exact_only, &c.tangential);
    summary.outer_iterations = Some(c.outer_iterations);
    summary.tangential_time_s = start.elapsed().as_secs_f64();
    Ok((c.normal, summary, c.tangential))
}

fn summary_of_exact(t: &TangentialCase, sol: &TangentialSolution) -> TangentialSummary {
    let rolling = matches!(t.task, TangentialTask::Rolling(_));
    TangentialSummary {
        tangential_method: t.method.name().into(),
        tangential_problem: if rolling { "rolling" } else { "shift" }.into(),
        mu: t.mu,
        tangential_force_x: sol.force_x,
        tangential_force_y: sol.force_y,
        spin_moment: Some(sol.moment_z),
        adhesion_elements: Some(sol.adhesion_elements),
        slip_elements: Some(sol.slip_elements),
        creepage_x: rolling.then_some(sol.creepages.xi),
        creepage_y: rolling.then_some(sol.creepages.eta),
        spin: rolling.then_some(sol.creepages.phi),
        shift_x: (!rolling).then_some(sol.shift.0),
        shift_y: (!rolling).then_some(sol.shift.1),
        frictional_power: Some(sol.frictional_power),
        tangential_iterations: Some(sol.iterations),
        newton_iterations: Some(sol.newton_iterations),
        outer_iterations: None,
        tangential_time_s: 0.0,
    }
}

/// FASTSIM on the Hertz ellipse (a, b) with the case grid's nx × ny elements.
pub fn fastsim_on(
    case: &PreparedCase,
    mu: f64,
    normal_force: f64,
    a: f64,
    b: f64,
    c: Creepages,
) -> Result<halfspace::FastsimSolution> {
    let input = FastsimInput {
        a,
        b,
        g: case.material.g,
        nu: case.material.nu,
        mu,
        normal_force,
        xi: c.xi,
        eta: c.eta,
        phi: c.phi,
    };
    fastsim(&input, case.grid.nx.max(2), case.grid.ny.max(2)).map_err(|e| anyhow!("FASTSIM: {e}"))
}

/// Solve a prepared case. A non-converged solve is returned with `converged = false`; the
/// caller must report it as a failure.
pub fn solve(case: &PreparedCase) -> Result<CaseOutcome> {
    let mut solver = NormalSolver::new(case.grid, case.material).map_err(|e| anyhow!("{e}"))?;
    let start = Instant::now();
    let solution = match solver.solve(&case.gap, case.load, &case.options) {
        Ok(s) => s,
        Err(ContactError::NotConverged { last, .. }) => *last,
        Err(e) => return Err(anyhow!("{e}")),
    };
    let mut solve_time_s = start.elapsed().as_secs_f64();
    let (solution, tangential_summary, tangential) = match &case.tangential {
        Some(t)
            if solution.converged
                && tangential_strategy(t.method, &case.material) == TangentialStrategy::Coupled =>
        {
            // Dissimilar materials: alternate normal and tangential solves.
            let (n, s, e) = solve_coupled_case(case, t)?;
            solve_time_s = start.elapsed().as_secs_f64();
            (n, Some(s), Some(e))
        }
        Some(t) if solution.converged => {
            let (s, e) = solve_tangential(case, t, &solution)?;
            (solution, Some(s), e)
        }
        _ => (solution, None, None),
    };
    let g = case.grid;
    let m = case.material;
    let hertz_load = match case.load {
        NormalLoad::Force(f) => NormalLoad::Force(f),
        NormalLoad::Approach(_) if solution.normal_force > 0.0 => {
            NormalLoad::Force(solution.normal_force)
        }
        NormalLoad::Approach(d) => NormalLoad::Approach(d),
    };
    let hertz = case
        .shape
        .hertz(&m, hertz_load)
        .map(|h: Hertz| HertzSummary {
            approach: h.approach,
            max_pressure: h.max_pressure,
            a: h.a,
            b: h.b,
            normal_force: h.normal_force,
        });
    let hertz_line = match &case.shape {
        GapShape::Cylinder { radius, length } if solution.normal_force > 0.0 => {
            LineHertz::new(*radius, m.e_star, solution.normal_force / length)
                .ok()
                .map(|l| LineHertzSummary {
                    a: l.a,
                    max_pressure: l.max_pressure,
                    force_per_length: l.force_per_length,
                })
        }
        _ => None,
    };
    let summary = ContactSummary {
        normal_force: solution.normal_force,
        approach: solution.approach,
        max_pressure: solution.max_pressure,
        contact_area: solution.contact_area,
        elements_in_contact: solution.elements_in_contact,
        iterations: solution.iterations,
        residual: solution.residual,
        converged: solution.converged,
        dfn_dapproach: solution.dfn_dapproach,
        solve_time_s,
        centre_of_pressure: [solution.centre_of_pressure.0, solution.centre_of_pressure.1],
        grid: GridSummary {
            nx: g.nx,
            ny: g.ny,
            dx: g.dx,
            dy: g.dy,
            x0: g.x0,
            y0: g.y0,
        },
        material: MaterialSummary {
            g: m.g,
            nu: m.nu,
            k: m.k,
            e_star: m.e_star,
        },
        hertz,
        hertz_line,
        tangential: tangential_summary,
    };
    Ok(CaseOutcome {
        summary,
        solution,
        tangential,
    })
}

/// Human-readable summary.
pub fn print_summary(s: &ContactSummary) {
    println!(
        "normal contact ({} × {} grid, {:.3e} × {:.3e} m elements)",
        s.grid.nx, s.grid.ny, s.grid.dx, s.grid.dy
    );
    println!(
        "  combined G = {:.4e} Pa, nu = {:.4}, K = {:.4}, E* = {:.4e} Pa",
        s.material.g, s.material.nu, s.material.k, s.material.e_star
    );
    println!("  normal force      {:>14.6e} N", s.normal_force);
    println!("  approach          {:>14.6e} m", s.approach);
    println!("  max pressure      {:>14.6e} Pa", s.max_pressure);
    println!(
        "  contact area      {:>14.6e} m^2 ({} elements)",
        s.contact_area, s.elements_in_contact
    );
    println!(
        "  centre of press.  ({:.4e}, {:.4e}) m",
        s.centre_of_pressure[0], s.centre_of_pressure[1]
    );
    if let Some(k) = s.dfn_dapproach {
        println!("  dFn/d(approach)   {:>14.6e} N/m", k);
    }
    println!(
        "  NormCG            {} iterations, relative change {:.2e}, {}, {:.3} ms",
        s.iterations,
        s.residual,
        if s.converged {
            "converged"
        } else {
            "NOT CONVERGED"
        },
        1e3 * s.solve_time_s
    );
    if let Some(h) = &s.hertz {
        println!("Hertz (quadratic gap) at F = {:.6e} N:", h.normal_force);
        println!(
            "  approach {:.6e} m ({:+.3} %), p0 {:.6e} Pa ({:+.3} %), a {:.4e} m, b {:.4e} m",
            h.approach,
            100.0 * (s.approach / h.approach - 1.0),
            h.max_pressure,
            100.0 * (s.max_pressure / h.max_pressure - 1.0),
            h.a,
            h.b
        );
    }
    if let Some(h) = &s.hertz_line {
        println!(
            "Hertz line contact at F' = {:.6e} N/m: a {:.4e} m, p0 {:.6e} Pa ({:+.3} %)",
            h.force_per_length,
            h.a,
            h.max_pressure,
            100.0 * (s.max_pressure / h.max_pressure - 1.0)
        );
    }
    if let Some(t) = &s.tangential {
        println!(
            "tangential contact ({}, {}), mu = {}",
            t.tangential_problem, t.tangential_method, t.mu
        );
        println!(
            "  force x, y        {:>14.6e} N, {:.6e} N  (|F|/(mu Fn) = {:.4})",
            t.tangential_force_x,
            t.tangential_force_y,
            t.tangential_force_x.hypot(t.tangential_force_y) / (t.mu * s.normal_force)
        );
        if let Some(m) = t.spin_moment {
            println!("  spin moment       {m:>14.6e} N m");
        }
        if let (Some(x), Some(y)) = (t.creepage_x, t.creepage_y) {
            println!(
                "  creepages         xi = {x:.6e}, eta = {y:.6e}, spin = {:.6e} 1/m",
                t.spin.unwrap_or(0.0)
            );
        }
        if let (Some(x), Some(y)) = (t.shift_x, t.shift_y) {
            println!("  shift             ({x:.6e}, {y:.6e}) m");
        }
        if let (Some(a), Some(sl)) = (t.adhesion_elements, t.slip_elements) {
            println!("  adhesion / slip   {a} / {sl} elements");
        }
        if let Some(p) = t.frictional_power {
            let unit = if t.tangential_problem == "rolling" {
                "N (power per unit rolling speed)"
            } else {
                "J (work of the shift)"
            };
            println!("  friction loss     {p:>14.6e} {unit}");
        }
        if let Some(o) = t.outer_iterations {
            println!(
                "  K != 0: {o} normal-tangential outer iterations (the normal results above include the coupling)"
            );
        }
        if let Some(i) = t.tangential_iterations {
            println!(
                "  Gauss-Seidel      {i} sweeps, {} Newton iterations, {:.3} ms",
                t.newton_iterations.unwrap_or(0),
                1e3 * t.tangential_time_s
            );
        }
    }
}

/// Every file `contact --out` may write (one run's output set).
pub const OUTPUT_SET: &[&str] = &[
    "pressure.csv",
    "pressure.png",
    "pressure_profile.png",
    "summary.json",
    "traction.csv",
    "traction_x.png",
    "traction_y.png",
    "adhesion_slip.png",
];

/// Write pressure.csv, pressure.png, pressure_profile.png and summary.json (and the tangential
/// files) into the run's output set.
pub fn write_outputs(dir: &RunOutput, outcome: &CaseOutcome) -> Result<()> {
    let sol = &outcome.solution;
    let g = sol.grid;
    output::write_csv(
        &dir.path("pressure.csv"),
        &["x_m", "y_m", "p_pa"],
        (0..g.len()).map(|k| {
            let (x, y) = g.centre(k);
            vec![x, y, sol.pressure[k]]
        }),
    )?;
    let mpa: Vec<f64> = sol.pressure.iter().map(|p| p * 1e-6).collect();
    let outside: Vec<bool> = sol.pressure.iter().map(|&p| p <= 0.0).collect();
    let title = format!(
        "contact pressure (normal force {:.4e} N)",
        outcome.summary.normal_force
    );
    if g.ny == 1 {
        // A single row (a 2-D, line-contact case): the profile is the whole picture.
        plot::panels(
            &dir.path("pressure.png"),
            &[plot::Panel {
                title: format!("{title}, single grid row (2-D case)"),
                x_label: "x [mm]".into(),
                y_label: "pressure p [MPa]".into(),
                series: vec![plot::Series::steps(
                    "boundary elements",
                    &(0..g.nx)
                        .map(|ix| (g.x(ix) * 1e3, mpa[ix]))
                        .collect::<Vec<_>>(),
                    g.dx * 1e3,
                )],
            }],
        )?;
    } else {
        plot::map(
            &dir.path("pressure.png"),
            &plot::Map {
                title,
                x_label: "x [mm]",
                y_label: "y [mm]",
                field: plot::Field {
                    nx: g.nx,
                    ny: g.ny,
                    x0: g.x0 * 1e3,
                    y0: g.y0 * 1e3,
                    dx: g.dx * 1e3,
                    dy: g.dy * 1e3,
                    values: &mpa,
                },
                scale: plot::Scale::Continuous {
                    label: "p [MPa]",
                    exterior: Some((&outside, "no contact (p = 0)")),
                },
            },
        )?;
    }
    plot::panels(&dir.path("pressure_profile.png"), &[profile_panel(outcome)])?;
    if let Some(t) = &outcome.tangential {
        write_tangential_outputs(dir, t)?;
    }
    output::write_summary(&dir.path("summary.json"), &outcome.summary)
}

/// State code of an element in outputs: 0 exterior, 1 adhesion, 2 slip.
fn state_code(s: ElementState) -> f64 {
    match s {
        ElementState::Exterior => 0.0,
        ElementState::Adhesion => 1.0,
        ElementState::Slip => 2.0,
    }
}

/// traction.csv, traction_x.png, traction_y.png and adhesion_slip.png.
fn write_tangential_outputs(dir: &RunOutput, t: &TangentialSolution) -> Result<()> {
    let g = t.grid;
    output::write_csv(
        &dir.path("traction.csv"),
        &["x_m", "y_m", "px_pa", "py_pa", "state", "slip_x", "slip_y"],
        (0..g.len()).map(|k| {
            let (x, y) = g.centre(k);
            vec![
                x,
                y,
                t.traction_x[k],
                t.traction_y[k],
                state_code(t.state[k]),
                t.slip_x[k],
                t.slip_y[k],
            ]
        }),
    )?;
    let field = |values: &[f64]| -> Vec<f64> { values.iter().map(|v| v * 1e-6).collect() };
    let (px, py) = (field(&t.traction_x), field(&t.traction_y));
    let exterior: Vec<bool> = t
        .state
        .iter()
        .map(|&s| s == ElementState::Exterior)
        .collect();
    let states: Vec<f64> = t.state.iter().map(|&s| state_code(s)).collect();
    let grid_field = |values| plot::Field {
        nx: g.nx,
        ny: g.ny,
        x0: g.x0 * 1e3,
        y0: g.y0 * 1e3,
        dx: g.dx * 1e3,
        dy: g.dy * 1e3,
        values,
    };
    if g.ny == 1 {
        // A single row (2-D case, e.g. Carter's): line plots along x.
        let cells = |values: &[f64]| -> Vec<(f64, f64)> {
            (0..g.nx).map(|ix| (g.x(ix) * 1e3, values[ix])).collect()
        };
        for (name, title, label, values) in [
            (
                "traction_x.png",
                "tangential traction p_x",
                "p_x [MPa]",
                &px,
            ),
            (
                "traction_y.png",
                "tangential traction p_y",
                "p_y [MPa]",
                &py,
            ),
        ] {
            plot::panels(
                &dir.path(name),
                &[plot::Panel {
                    title: format!("{title}, single grid row (2-D case)"),
                    x_label: "x [mm]".into(),
                    y_label: label.into(),
                    series: vec![plot::Series::steps(
                        "boundary elements",
                        &cells(values),
                        g.dx * 1e3,
                    )],
                }],
            )?;
        }
        let count = |want: ElementState| t.state.iter().filter(|&&s| s == want).count();
        plot::panels(
            &dir.path("adhesion_slip.png"),
            &[plot::Panel {
                title: format!(
                    "element state along x (single grid row): {} adhesion, {} slip elements",
                    count(ElementState::Adhesion),
                    count(ElementState::Slip)
                ),
                x_label: "x [mm]".into(),
                y_label: "state [0 outside, 1 adhesion, 2 slip]".into(),
                series: vec![plot::Series::steps(
                    "element state",
                    &cells(&states),
                    g.dx * 1e3,
                )],
            }],
        )?;
        return Ok(());
    }
    for (name, title, label, values) in [
        (
            "traction_x.png",
            "tangential traction p_x",
            "p_x [MPa]",
            &px,
        ),
        (
            "traction_y.png",
            "tangential traction p_y",
            "p_y [MPa]",
            &py,
        ),
    ] {
        plot::map(
            &dir.path(name),
            &plot::Map {
                title: title.to_string(),
                x_label: "x [mm]",
                y_label: "y [mm]",
                field: grid_field(values),
                scale: plot::Scale::Continuous {
                    label,
                    exterior: Some((&exterior, "outside the contact")),
                },
            },
        )?;
    }
    plot::map(
        &dir.path("adhesion_slip.png"),
        &plot::Map {
            title: "adhesion and slip areas (element count in the legend)".to_string(),
            x_label: "x [mm]",
            y_label: "y [mm]",
            field: grid_field(&states),
            scale: plot::Scale::Categorical(&[
                ("outside the contact", plot::EXTERIOR),
                ("adhesion", plot::RGBColor(44, 160, 44)),
                ("slip", plot::RGBColor(214, 39, 40)),
            ]),
        },
    )?;
    Ok(())
}

/// Pressure along x on the grid row through the centre of pressure, with Hertz's profile
/// p₀√(1 − x²/a²) of the same force when the gap is quadratic.
fn profile_panel(outcome: &CaseOutcome) -> plot::Panel {
    let sol = &outcome.solution;
    let g = sol.grid;
    let yc = sol.centre_of_pressure.1;
    let iy = (((yc - g.y0) / g.dy - 0.5).round().max(0.0) as usize).min(g.ny - 1);
    let bem: Vec<(f64, f64)> = (0..g.nx)
        .map(|ix| (g.x(ix) * 1e3, sol.pressure[iy * g.nx + ix] * 1e-6))
        .collect();
    // Each element carries a constant pressure: drawn as steps.
    let mut series = vec![plot::Series::steps(
        "boundary elements (constant per element)",
        &bem,
        g.dx * 1e3,
    )];
    let hertz_curve = |a: f64, p0: f64| -> Vec<(f64, f64)> {
        (0..=400)
            .map(|k| {
                let x = g.x0 + (g.nx as f64 * g.dx) * k as f64 / 400.0;
                let s = 1.0 - ((x - sol.centre_of_pressure.0) / a).powi(2);
                (x * 1e3, if s > 0.0 { p0 * s.sqrt() * 1e-6 } else { 0.0 })
            })
            .collect()
    };
    if let Some(h) = &outcome.summary.hertz {
        let y = g.y(iy) - yc;
        let scale = (1.0 - (y / h.b).powi(2)).max(0.0).sqrt();
        series.push(plot::Series::reference(
            "Hertz theory, same force",
            hertz_curve(h.a * scale, h.max_pressure * scale),
        ));
    }
    if let Some(h) = &outcome.summary.hertz_line {
        series.push(plot::Series::reference(
            "Hertz line-contact theory, same force per length",
            hertz_curve(h.a, h.max_pressure),
        ));
    }
    plot::Panel {
        title: format!(
            "pressure along x on the grid row through the centre of pressure (y = {:.4} mm)",
            g.y(iy) * 1e3
        ),
        x_label: "x [mm]".into(),
        y_label: "pressure p [MPa]".into(),
        series,
    }
}

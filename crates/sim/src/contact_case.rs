//! A contact case (`kind = "contact"`, `dyncontact contact`) solved: the normal problem by
//! NormCG, the tangential problem when the case has `[friction]` and `[kinematics]` (exact
//! shift or rolling, FASTSIM, Kalker's linear theory; alternating normal–tangential solves when
//! K ≠ 0, references.md §C5), and the summary the CLI prints as JSON and the Python package
//! returns. No I/O: the CLI writes the files, the Python package builds its arrays.

use std::time::Instant;

use halfspace::{
    ContactError, CoupledOptions, CoupledProblem, Creepages, FastsimInput, GapShape, Hertz,
    LineHertz, NormalLoad, NormalSolution, NormalSolver, RollingLoad, TangentialOptions,
    TangentialSolution, TangentialSolver, TangentialStrategy, fastsim, linear_forces,
    solve_coupled, tangential_strategy,
};
use serde::Serialize;

use crate::config::contact::{PreparedCase, TangentialCase, TangentialMethod, TangentialTask};

/// A contact case that could not be solved (the message names the stage that failed).
#[derive(Debug, thiserror::Error)]
pub enum ContactCaseError {
    /// The solvers could not be set up for the case's grid and material.
    #[error("{0}")]
    Setup(ContactError),
    /// A solve failed; `stage` says which (`tangential problem`, `FASTSIM`, …).
    #[error("{stage}: {source}")]
    Solve {
        /// The stage that failed.
        stage: &'static str,
        /// The cause.
        #[source]
        source: ContactError,
    },
    /// FASTSIM and the linear theory need the Hertz ellipse of a quadratic gap.
    #[error("[gap]: FASTSIM and the linear theory need a Hertzian gap")]
    NotHertzian,
    /// An approximate tangential method was given a prescribed force instead of creepages.
    #[error("[kinematics] `method` = \"{0}\" needs creepages")]
    NeedsCreepages(&'static str),
}

type Result<T> = std::result::Result<T, ContactCaseError>;

fn stage(stage: &'static str) -> impl FnOnce(ContactError) -> ContactCaseError {
    move |source| ContactCaseError::Solve { stage, source }
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
        .ok_or(ContactCaseError::NotHertzian)?;
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
            let mut solver = TangentialSolver::new(case.grid, m).map_err(stage("tangential"))?;
            let opts = TangentialOptions::default();
            let sol = match task {
                TangentialTask::Rolling(load) => {
                    solver.steady_rolling(&normal.pressure, t.mu, load, &opts)
                }
                TangentialTask::Shift(load) => solver.shift(&normal.pressure, t.mu, load, &opts),
            }
            .map_err(stage("tangential problem"))?;
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
                    .map_err(stage("linear theory"))?;
                summary.tangential_force_x = fx;
                summary.tangential_force_y = fy;
            }
        }
        (method, _) => return Err(ContactCaseError::NeedsCreepages(method.name())),
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
    let mut normal =
        NormalSolver::new(case.grid, case.material).map_err(ContactCaseError::Setup)?;
    let mut tang =
        TangentialSolver::new(case.grid, case.material).map_err(ContactCaseError::Setup)?;
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
    .map_err(stage("coupled normal-tangential problem (K != 0)"))?;
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
    fastsim(&input, case.grid.nx.max(2), case.grid.ny.max(2)).map_err(stage("FASTSIM"))
}

/// Solve a prepared case. A non-converged solve is returned with `converged = false`; the
/// caller must report it as a failure.
pub fn solve(case: &PreparedCase) -> Result<CaseOutcome> {
    let mut solver =
        NormalSolver::new(case.grid, case.material).map_err(ContactCaseError::Setup)?;
    let start = Instant::now();
    let solution = match solver.solve(&case.gap, case.load, &case.options) {
        Ok(s) => s,
        Err(ContactError::NotConverged { last, .. }) => *last,
        Err(e) => return Err(ContactCaseError::Setup(e)),
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

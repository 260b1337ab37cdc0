//! Creep curves (`dyncontact creep-curve`, `dyncontact.creep_curve` in Python): the creep
//! force against one swept creepage in steady rolling, with the exact half-space solver,
//! FASTSIM and Kalker's linear theory side by side (references.md §C4, docs/tangential.md).
//! With K ≠ 0 every exact point is a coupled normal–tangential solve, as in
//! [`crate::contact_case::solve`].

use std::time::Instant;

use halfspace::{
    ContactError, CoupledOptions, CoupledProblem, Creepages, NormalSolver, RollingLoad,
    TangentialMethod, TangentialOptions, TangentialSolver, TangentialStrategy, linear_forces,
    solve_coupled, tangential_strategy,
};
use serde::Serialize;

use crate::config::contact::{PreparedCase, TangentialTask};
use crate::contact_case::{ContactCaseError, fastsim_on, hertz_axes};

/// The creepage a curve sweeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CreepVariable {
    /// Longitudinal creepage ξ.
    CreepageX,
    /// Lateral creepage η.
    CreepageY,
    /// Spin φ \[1/m\].
    Spin,
}

impl CreepVariable {
    /// The key of the variable (`creepage_x`, `creepage_y`, `spin`).
    pub fn key(self) -> &'static str {
        match self {
            Self::CreepageX => "creepage_x",
            Self::CreepageY => "creepage_y",
            Self::Spin => "spin",
        }
    }
}

/// One point of the curve (forces on body 1 \[N\], moment \[N m\]).
#[derive(Debug, Clone, Serialize)]
pub struct CurvePoint {
    pub creepage_x: f64,
    pub creepage_y: f64,
    pub spin: f64,
    /// Whether the exact solver converged at this point (false: the exact forces are NaN,
    /// null in JSON; the point is kept and the caller reports it).
    pub exact_converged: bool,
    pub exact_force_x: f64,
    pub exact_force_y: f64,
    pub exact_spin_moment: f64,
    pub exact_adhesion_elements: usize,
    pub exact_slip_elements: usize,
    /// Iterations of the exact solver at this point (Newton steps of the default
    /// steady-rolling solver, sweeps of the Gauss–Seidel reference; the key keeps its
    /// historical name).
    pub exact_sweeps: usize,
    pub fastsim_force_x: Option<f64>,
    pub fastsim_force_y: Option<f64>,
    pub linear_force_x: Option<f64>,
    pub linear_force_y: Option<f64>,
}

/// A creep curve (the CLI's `creep_curve.json`).
#[derive(Debug, Clone, Serialize)]
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

/// A creep curve that cannot be computed.
#[derive(Debug, thiserror::Error)]
pub enum CreepCurveError {
    /// The case has no friction coefficient.
    #[error("[friction]: a creep curve needs `mu`")]
    NoMu,
    /// The case's `[kinematics]` prescribes forces or a shift.
    #[error(
        "[kinematics]: a creep curve sweeps creepages; give creepages (the unswept ones are held) or omit [kinematics]"
    )]
    NotCreepages,
    /// The solvers could not be set up.
    #[error("{0}")]
    Setup(ContactError),
    /// The normal problem did not converge.
    #[error("normal problem: {0}")]
    Normal(ContactError),
    /// The exact solver failed at one point of the curve.
    #[error("exact solver at {label} = {value:e}: {source}")]
    Exact {
        /// The swept variable as the caller names it.
        label: String,
        /// Its value.
        value: f64,
        /// The cause.
        #[source]
        source: ContactError,
    },
    /// FASTSIM or the linear theory failed.
    #[error("{0}")]
    Approximate(#[from] ContactCaseError),
    /// Stopped by the caller (an interrupt).
    #[error("the creep curve was interrupted after {0} points")]
    Interrupted(usize),
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

/// The friction coefficient and the held creepages of a creep-curve case (checked before any
/// solve).
pub fn check(case: &PreparedCase) -> Result<(f64, Creepages), CreepCurveError> {
    let mu = case.mu.ok_or(CreepCurveError::NoMu)?;
    let base = match case.tangential.map(|t| t.task) {
        None => Creepages::default(),
        Some(TangentialTask::Rolling(RollingLoad::Creepages(c))) => c,
        Some(_) => return Err(CreepCurveError::NotCreepages),
    };
    Ok((mu, base))
}

/// The creep curve of `case` over `values` of `variable` (the other creepages held at the
/// case's `[kinematics]`, or 0). `label` names the variable in error messages; `proceed` is
/// called before each point and returns false to stop (an interrupt).
pub fn compute(
    case: &PreparedCase,
    variable: CreepVariable,
    values: &[f64],
    label: &str,
    proceed: &dyn Fn() -> bool,
) -> Result<CreepCurve, CreepCurveError> {
    compute_with(
        case,
        variable,
        values,
        label,
        proceed,
        &TangentialOptions::default(),
    )
}

/// [`compute`] with the exact solver's options (`TangentialOptions::default()` there).
pub fn compute_with(
    case: &PreparedCase,
    variable: CreepVariable,
    values: &[f64],
    label: &str,
    proceed: &dyn Fn() -> bool,
    tangential: &TangentialOptions,
) -> Result<CreepCurve, CreepCurveError> {
    let (mu, base_creep) = check(case)?;
    let mut normal_solver =
        NormalSolver::new(case.grid, case.material).map_err(CreepCurveError::Setup)?;
    let normal = normal_solver
        .solve(&case.gap, case.load, &case.options)
        .map_err(|e| match e {
            ContactError::NotConverged { .. } => CreepCurveError::Normal(e),
            other => CreepCurveError::Setup(other),
        })?;
    let axes = hertz_axes(case, normal.normal_force).ok();
    let mut solver =
        TangentialSolver::new(case.grid, case.material).map_err(CreepCurveError::Setup)?;
    let opts = *tangential;
    // The exact curve follows `contact`'s rule: with K != 0 every point is a coupled
    // normal-tangential solve (the normal pressure changes with the tractions).
    let coupled =
        tangential_strategy(TangentialMethod::Exact, &case.material) == TangentialStrategy::Coupled;
    let mut points = Vec::with_capacity(values.len());
    let mut exact_time = 0.0;
    for &v in values {
        if !proceed() {
            return Err(CreepCurveError::Interrupted(points.len()));
        }
        let mut c = base_creep;
        match variable {
            CreepVariable::CreepageX => c.xi = v,
            CreepVariable::CreepageY => c.eta = v,
            CreepVariable::Spin => c.phi = v,
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
            // Keep the curve: the point is kept with exact_converged = false and no exact
            // forces; the other points stand.
            Err(
                ContactError::TangentialNotConverged { .. }
                | ContactError::NotConverged { .. }
                | ContactError::NewtonNotConverged { .. },
            ) => (
                ExactPoint {
                    force_x: f64::NAN,
                    force_y: f64::NAN,
                    moment_z: f64::NAN,
                    adhesion_elements: 0,
                    slip_elements: 0,
                    sweeps: opts.max_iter,
                },
                false,
            ),
            Err(source) => {
                return Err(CreepCurveError::Exact {
                    label: label.to_string(),
                    value: v,
                    source,
                });
            }
        };
        exact_time += t0.elapsed().as_secs_f64();
        let (mut fsx, mut fsy, mut lx, mut ly) = (None, None, None, None);
        if let Some((a, b)) = axes {
            let f = fastsim_on(case, mu, normal.normal_force, a, b, c)?;
            fsx = Some(f.force_x);
            fsy = Some(f.force_y);
            let (x, y) = linear_forces(case.material.g, case.material.nu, a, b, c.xi, c.eta, c.phi)
                .map_err(|source| ContactCaseError::Solve {
                    stage: "linear theory",
                    source,
                })?;
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
    Ok(CreepCurve {
        variable: variable.key().into(),
        mu,
        normal_force: normal.normal_force,
        hertz_a: axes.map(|a| a.0),
        hertz_b: axes.map(|a| a.1),
        grid_nx: case.grid.nx,
        grid_ny: case.grid.ny,
        exact_time_s: exact_time,
        points,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point where the exact solver does not converge is kept, flagged
    /// (`exact_converged = false`, NaN forces), and the other points stand: here a sweep
    /// limit of 2 on Carter's 2-D case (which needs about 300 sweeps) fails every point but
    /// ξ = 0, whose traction-free solution needs no iteration. With the default limit every
    /// point converges.
    #[test]
    fn a_non_converged_point_is_kept_and_flagged() {
        let text = include_str!("../../../examples/tangential_carter.toml");
        let case = crate::config::contact::parse(text, std::path::Path::new(".")).unwrap();
        let values = [-4e-4, -2e-4, 0.0];
        let tight = TangentialOptions {
            max_iter: 2,
            ..TangentialOptions::default()
        };
        let c = compute_with(
            &case,
            CreepVariable::CreepageX,
            &values,
            "x",
            &|| true,
            &tight,
        )
        .unwrap();
        assert_eq!(c.points.len(), 3);
        for p in &c.points[..2] {
            assert!(!p.exact_converged && p.exact_force_x.is_nan(), "{p:?}");
            assert!(p.fastsim_force_x.is_none(), "a 2-D case has no FASTSIM");
        }
        assert!(c.points[2].exact_converged && c.points[2].exact_force_x == 0.0);
        let c = compute(&case, CreepVariable::CreepageX, &values, "x", &|| true).unwrap();
        assert!(c.points.iter().all(|p| p.exact_converged));
    }
}

//! Normal–tangential coupling for dissimilar materials (K ≠ 0): Panagiotopoulos' process.
//!
//! With K ≠ 0 the normal pressure displaces the surfaces tangentially (A_tn p_n) and the
//! tangential tractions displace them normally (u_n = A_nx p_x + A_ny p_y, A_nx = −A_xn;
//! references.md §C3.1–3.2). CONTACT alternates a normal solve with the gap h + u_n(p_t) and a
//! tangential solve for the new pressure until neither changes (MAXOUT ≈ 20). For K = 0 one
//! pass is exact (Johnson's process).
//!
//! Stopping rule: ‖Δp_n‖_rms ≤ tol ‖p_n‖_rms and ‖Δp_t‖_rms ≤ tol ‖p_t‖_rms (or p_t = 0)
//! between outer iterations; otherwise [`ContactError::CoupledNotConverged`].

use crate::error::{ContactError, positive};
use crate::normcg::{NormalLoad, NormalSolver, SolverOptions};
use crate::operator::{InfluenceOperator, TangentialInfluenceOperator};
use crate::solution::NormalSolution;
use crate::tangential::{
    RollingLoad, ShiftLoad, StepMotion, TangentialOptions, TangentialSolution, TangentialSolver,
};

/// The tangential problem of a coupled solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CoupledProblem {
    /// Shift from the unloaded state (normal and tangential load applied together).
    Shift(ShiftLoad),
    /// Steady rolling.
    SteadyRolling(RollingLoad),
}

/// Controls of the outer loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoupledOptions {
    /// Relative change of p_n and p_t between outer iterations (default 1e-6).
    pub tol: f64,
    /// Outer iteration limit (default 30).
    pub max_outer: usize,
}

impl Default for CoupledOptions {
    fn default() -> Self {
        CoupledOptions {
            tol: 1e-6,
            max_outer: 30,
        }
    }
}

/// Result of a coupled solve.
#[derive(Debug, Clone)]
pub struct CoupledSolution {
    pub normal: NormalSolution,
    pub tangential: TangentialSolution,
    /// Outer iterations (1 for K = 0).
    pub outer_iterations: usize,
    /// The gap the last normal solve used, h + u_n(p_t) \[m\].
    pub effective_gap: Vec<f64>,
}

/// Relative rms change of the pressure and of the traction between two outer iterations,
/// whichever is larger (infinite on the first iteration).
fn outer_change(
    prev_pn: Option<&[f64]>,
    prev_pt: Option<&(Vec<f64>, Vec<f64>)>,
    pn: &[f64],
    (px, py): (&[f64], &[f64]),
) -> f64 {
    let (dn, nn) = match prev_pn {
        Some(p) => rms_change(pn, p),
        None => (f64::INFINITY, 1.0),
    };
    let (dt, nt) = match prev_pt {
        Some((x, y)) => {
            let (a, b) = rms_change(px, x);
            let (c, d) = rms_change(py, y);
            (a.hypot(c), b.hypot(d))
        }
        None => (f64::INFINITY, 1.0),
    };
    (dn / nn.max(f64::MIN_POSITIVE)).max(if nt > 0.0 { dt / nt } else { 0.0 })
}

fn rms_change(new: &[f64], old: &[f64]) -> (f64, f64) {
    let d: f64 = new.iter().zip(old).map(|(a, b)| (a - b) * (a - b)).sum();
    let n: f64 = new.iter().map(|a| a * a).sum();
    (d.sqrt(), n.sqrt())
}

/// Solve the coupled normal and tangential problem (module documentation).
#[allow(clippy::too_many_arguments)]
pub fn solve_coupled<N: InfluenceOperator, T: TangentialInfluenceOperator>(
    normal: &mut NormalSolver<N>,
    tangential: &mut TangentialSolver<T>,
    gap: &[f64],
    load: NormalLoad,
    mu: f64,
    problem: CoupledProblem,
    normal_options: &SolverOptions,
    tangential_options: &TangentialOptions,
    options: &CoupledOptions,
) -> Result<CoupledSolution, ContactError> {
    validate(normal, tangential, options)?;
    outer_loop(
        normal,
        tangential,
        gap,
        gap.to_vec(),
        load,
        normal_options,
        options,
        |tangential, pressure| match problem {
            CoupledProblem::Shift(l) => tangential.shift(pressure, mu, l, tangential_options),
            CoupledProblem::SteadyRolling(l) => {
                tangential.steady_rolling(pressure, mu, l, tangential_options)
            }
        },
    )
}

/// One coupled transient step (K ≠ 0): the outer loop of [`solve_coupled`] around
/// [`TangentialSolver::transient_step`] with the previous step's tractions and pressure
/// (`previous_traction`, `previous_pressure`; zeros for the first step). With
/// `motion.delta_q = 0` this is a quasi-static loading stage, as in CONTACT's Spence example
/// (a sequence of normal loads linked by the previous tractions).
#[allow(clippy::too_many_arguments)]
pub fn solve_coupled_step<N: InfluenceOperator, T: TangentialInfluenceOperator>(
    normal: &mut NormalSolver<N>,
    tangential: &mut TangentialSolver<T>,
    gap: &[f64],
    load: NormalLoad,
    mu: f64,
    previous_traction: (&[f64], &[f64]),
    previous_pressure: &[f64],
    motion: StepMotion,
    normal_options: &SolverOptions,
    tangential_options: &TangentialOptions,
    options: &CoupledOptions,
) -> Result<CoupledSolution, ContactError> {
    validate(normal, tangential, options)?;
    // Start from the previous tractions' normal displacement.
    let mut un = vec![0.0; gap.len()];
    tangential.normal_displacement(previous_traction.0, previous_traction.1, &mut un)?;
    let effective: Vec<f64> = gap.iter().zip(&un).map(|(h, u)| h + u).collect();
    outer_loop(
        normal,
        tangential,
        gap,
        effective,
        load,
        normal_options,
        options,
        |tangential, pressure| {
            tangential.set_previous_pressure(previous_pressure)?;
            tangential.transient_step(pressure, mu, previous_traction, motion, tangential_options)
        },
    )
}

/// The checks shared by both entry points.
fn validate<N: InfluenceOperator, T: TangentialInfluenceOperator>(
    normal: &NormalSolver<N>,
    tangential: &TangentialSolver<T>,
    options: &CoupledOptions,
) -> Result<(), ContactError> {
    positive("coupled tol", options.tol)?;
    if options.max_outer == 0 {
        return Err(ContactError::InvalidParameter {
            name: "max_outer",
            value: 0.0,
            reason: "must be at least 1",
        });
    }
    if normal.grid() != tangential.grid() {
        return Err(ContactError::InvalidParameter {
            name: "grid",
            value: f64::NAN,
            reason: "the normal and tangential solvers must share the grid",
        });
    }
    Ok(())
}

/// The outer loop (module documentation): normal solve on `effective`, then
/// `solve_tangential` on its pressure, until p_n and p_t stop changing; one pass for K = 0.
#[allow(clippy::too_many_arguments)]
fn outer_loop<N: InfluenceOperator, T: TangentialInfluenceOperator>(
    normal: &mut NormalSolver<N>,
    tangential: &mut TangentialSolver<T>,
    gap: &[f64],
    mut effective: Vec<f64>,
    load: NormalLoad,
    normal_options: &SolverOptions,
    options: &CoupledOptions,
    mut solve_tangential: impl FnMut(
        &mut TangentialSolver<T>,
        &[f64],
    ) -> Result<TangentialSolution, ContactError>,
) -> Result<CoupledSolution, ContactError> {
    let decoupled = normal.material().k == 0.0;
    let mut un = vec![0.0; gap.len()];
    let mut prev_pn: Option<Vec<f64>> = None;
    let mut prev_pt: Option<(Vec<f64>, Vec<f64>)> = None;
    let mut change = f64::INFINITY;
    for outer in 1..=options.max_outer {
        let ns = normal.solve(&effective, load, normal_options)?;
        let ts = solve_tangential(tangential, &ns.pressure)?;
        change = outer_change(
            prev_pn.as_deref(),
            prev_pt.as_ref(),
            &ns.pressure,
            (&ts.traction_x, &ts.traction_y),
        );
        if decoupled || change <= options.tol {
            return Ok(CoupledSolution {
                normal: ns,
                tangential: ts,
                outer_iterations: outer,
                effective_gap: effective,
            });
        }
        tangential.normal_displacement(&ts.traction_x, &ts.traction_y, &mut un)?;
        for ((e, h), u) in effective.iter_mut().zip(gap).zip(&un) {
            *e = h + u;
        }
        prev_pn = Some(ns.pressure);
        prev_pt = Some((ts.traction_x, ts.traction_y));
    }
    Err(ContactError::CoupledNotConverged {
        iterations: options.max_outer,
        residual: change,
    })
}

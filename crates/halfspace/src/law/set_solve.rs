//! The normal problem at prescribed approach solved by active-set updates of the dense
//! factor of A_CC (references.md §C8.4, "Set changes by the factor"), started from the contact
//! set of the previous solve.
//!
//! The discrete problem p ≥ 0, e = h − δ + A p ≥ 0, pᵀe = 0 (A symmetric positive definite)
//! has a unique solution; on its contact set C, A_CC p_C = δ − h_C. Starting from the last
//! set, each round solves that system with the factor (exact to round-off), drops the
//! elements of C with p_e < 0, or else adds the elements off C with e_j < 0 (one convolution
//! for A p), until neither exists: then p is *the* solution. A change of a few elements at
//! the patch's edge (the usual change between time steps) costs O(r m²) for the factor and
//! one convolution per round instead of a NormCG solve. Without convergence in
//! [`MAX_ROUNDS`] rounds (the add/drop iteration is not guaranteed to converge for a matrix
//! with positive off-diagonal entries) the caller solves with NormCG.

use super::set_factor::SetFactor;
use crate::error::ContactError;
use crate::normcg::NormalSolver;
use crate::solution::NormalSolution;

/// Rounds of the add/drop iteration before giving up.
const MAX_ROUNDS: usize = 8;

/// Elements off C enter when e_j < −[`ENTER_TOL`] × δ: below the round-off of A p (≈ 1e-15 of
/// the displacement), so that an element at e_j ≈ 0 does not cycle in and out.
const ENTER_TOL: f64 = 1e-12;

/// Scratch of [`solve`].
#[derive(Debug, Default)]
pub(super) struct SetSolveWork {
    /// The set: the start on entry to [`solve`], then the iterate.
    pub(super) in_contact: Vec<bool>,
    /// Per member of the factor: δ − h_e and the shapes b_k(e) on entry to the factor's
    /// solve, then p_e and y_k,e = (A_CC⁻¹ b_k)_e (lanes 1…3) of the last round.
    pub(super) block: Vec<[f64; 4]>,
}

/// The solution at approach `delta` for the undeformed gap `gap` (per element), started from
/// the set `work.in_contact` (one flag per element). Each round solves for the pressure and,
/// in the same pass over the factor, for the responses to the three gap shapes `shapes`
/// (per element), which `work.block` holds on return (the new model's responses); `None` when the iteration does not converge or the set empties (the
/// caller solves with NormCG). The factor is left on the solution's set.
pub(super) fn solve(
    factor: &mut SetFactor,
    solver: &mut NormalSolver,
    gap: &[f64],
    delta: f64,
    shapes: &[Vec<f64>; 3],
    work: &mut SetSolveWork,
) -> Result<Option<NormalSolution>, ContactError> {
    let grid = *solver.grid();
    let n = grid.len();
    let mut pressure = vec![0.0; n];
    let mut displacement = vec![0.0; n];
    for _ in 0..MAX_ROUNDS {
        factor.sync(&work.in_contact)?;
        let members = factor.members();
        if members.is_empty() {
            return Ok(None);
        }
        work.block.clear();
        work.block.extend(
            members
                .iter()
                .map(|&e| [delta - gap[e], shapes[0][e], shapes[1][e], shapes[2][e]]),
        );
        factor.solve_block(&mut work.block);
        let mut dropped = false;
        for (&e, row) in members.iter().zip(&work.block) {
            if row[0] < 0.0 {
                work.in_contact[e] = false;
                dropped = true;
            }
        }
        if dropped {
            continue;
        }
        pressure.fill(0.0);
        for (&e, row) in members.iter().zip(&work.block) {
            pressure[e] = row[0];
        }
        solver.displacement(&pressure, &mut displacement)?;
        let threshold = -ENTER_TOL * delta.abs();
        let mut added = false;
        for e in 0..n {
            if !work.in_contact[e] && gap[e] - delta + displacement[e] < threshold {
                work.in_contact[e] = true;
                added = true;
            }
        }
        if !added {
            return Ok(Some(solution(
                grid,
                gap,
                delta,
                pressure,
                displacement,
                &work.in_contact,
            )));
        }
    }
    Ok(None)
}

/// The [`NormalSolution`] of the converged set (its deformed distance on C is the round-off
/// residual of the factor's solve).
fn solution(
    grid: crate::grid::Grid,
    gap: &[f64],
    delta: f64,
    pressure: Vec<f64>,
    displacement: Vec<f64>,
    in_contact: &[bool],
) -> NormalSolution {
    let area = grid.element_area();
    let deformed_distance: Vec<f64> = gap
        .iter()
        .zip(&displacement)
        .map(|(h, u)| h - delta + u)
        .collect();
    let (mut force, mut max_pressure, mut count) = (0.0, 0.0_f64, 0);
    let (mut mx, mut my) = (0.0, 0.0);
    for (k, &p) in pressure.iter().enumerate() {
        if in_contact[k] {
            force += p * area;
            max_pressure = max_pressure.max(p);
            count += 1;
            mx += p * area * grid.x(k % grid.nx);
            my += p * area * grid.y(k / grid.nx);
        }
    }
    let centre_of_pressure = if force > 0.0 {
        (mx / force, my / force)
    } else {
        (grid.x0, grid.y0)
    };
    NormalSolution {
        grid,
        pressure,
        in_contact: in_contact.to_vec(),
        deformed_distance,
        displacement,
        normal_force: force,
        approach: delta,
        max_pressure,
        contact_area: count as f64 * area,
        elements_in_contact: count,
        centre_of_pressure,
        iterations: 0,
        residual: 0.0,
        converged: true,
        dfn_dapproach: None,
        sensitivity_iterations: 0,
    }
}

#[cfg(test)]
mod tests {
    use super::{SetSolveWork, solve};
    use crate::grid::Grid;
    use crate::law::set_factor::SetFactor;
    use crate::material::Material;
    use crate::normcg::{NormalLoad, NormalSolver, SolverOptions};

    /// A wheel-on-rail gap (R = 0.46 m along x, 0.3 m across, tilted by 1e-3) on a 20 × 20
    /// grid: from a wrong start set (a 3 × 3 block off the centre) and then from the previous
    /// solution at a 10 % larger approach, the factor's active-set solve equals NormCG at
    /// tolerance 1e-13 (the independent path) to 1e-9 of the peak pressure, with the same
    /// contact set.
    #[test]
    fn equals_normcg() {
        let grid = Grid::centred(20, 20, 5e-4, 4e-4, 0.0, 0.0).unwrap();
        let material = Material::identical(210e9, 0.3).unwrap();
        let gap = grid.sample(|x, y| x * x / 0.92 + y * y / 0.6 + 1e-3 * x);
        let mut solver = NormalSolver::new(grid, material).unwrap();
        let mut unit = vec![0.0; grid.len()];
        unit[0] = 1.0;
        let mut kernel = vec![0.0; grid.len()];
        solver.displacement(&unit, &mut kernel).unwrap();
        let mut factor = SetFactor::new(kernel, grid.nx);
        let mut work = SetSolveWork {
            in_contact: (0..grid.len())
                .map(|e| (6..9).contains(&(e % 20)) && (6..9).contains(&(e / 20)))
                .collect(),
            ..SetSolveWork::default()
        };
        let options = SolverOptions {
            tol: 1e-13,
            max_iter: 2000,
            ..SolverOptions::default()
        };
        let shapes = [
            vec![1.0; grid.len()],
            vec![0.0; grid.len()],
            vec![0.0; grid.len()],
        ];
        for delta in [4e-5, 4.4e-5] {
            let exact = solver
                .solve(&gap, NormalLoad::Approach(delta), &options)
                .unwrap();
            let fast = solve(&mut factor, &mut solver, &gap, delta, &shapes, &mut work)
                .unwrap()
                .expect("converges");
            assert_eq!(fast.in_contact, exact.in_contact);
            for (a, b) in fast.pressure.iter().zip(&exact.pressure) {
                assert!((a - b).abs() <= 1e-9 * exact.max_pressure, "{a} vs {b}");
            }
            assert!((fast.normal_force / exact.normal_force - 1.0).abs() <= 1e-9);
            // The response to b = 1 (lane 1) is dF/dδ: NormCG's sensitivity solve to 1e-7.
            let k: f64 = work.block.iter().map(|r| r[1]).sum::<f64>() * grid.element_area();
            let reference = solver
                .solve(
                    &gap,
                    NormalLoad::Approach(delta),
                    &SolverOptions {
                        sensitivity: true,
                        sensitivity_tol: 1e-12,
                        ..options
                    },
                )
                .unwrap()
                .dfn_dapproach
                .unwrap();
            assert!((k / reference - 1.0).abs() <= 1e-7, "{k} vs {reference}");
            work.in_contact = fast.in_contact.clone();
        }
    }
}

//! Prescribed tangential forces: Newton's method on two parameters (the creepages ξ, η in
//! rolling, the shift (w_x, w_y) in a shift), with the 2 × 2 Jacobian by forward differences
//! and step halving (references.md §C3.5).

use super::{TangentialOptions, TangentialSolver};
use crate::error::{ContactError, finite};
use crate::operator::TangentialInfluenceOperator;

impl<T: TangentialInfluenceOperator> TangentialSolver<T> {
    pub(super) fn check_force_target(
        &self,
        fx: f64,
        fy: f64,
        limit: f64,
    ) -> Result<[f64; 2], ContactError> {
        finite("force_x", fx)?;
        finite("force_y", fy)?;
        let f = fx.hypot(fy);
        if f >= limit {
            return Err(ContactError::ForceExceedsFriction { force: f, limit });
        }
        Ok([fx, fy])
    }

    /// Newton's method on two parameters (creepages or shift) for prescribed forces.
    /// `solve(self, param, options)` sets up and solves the problem for `param`.
    pub(super) fn newton(
        &mut self,
        target: [f64; 2],
        limit: f64,
        options: &TangentialOptions,
        mut solve: impl FnMut(
            &mut Self,
            [f64; 2],
            &TangentialOptions,
        ) -> Result<(usize, f64), ContactError>,
    ) -> Result<([f64; 2], usize, usize, f64), ContactError> {
        let tol = options.force_tol * limit;
        let mut sweeps = 0;
        // Full-adhesion stiffness from two linear probes (bound lifted).
        let saved = self.bound.clone();
        for g in self.bound.iter_mut() {
            if *g > 0.0 {
                *g = f64::INFINITY;
            }
        }
        let mut k0 = [[0.0; 2]; 2];
        for col in 0..2 {
            let mut p = [0.0; 2];
            p[col] = 1.0;
            self.px.fill(0.0);
            self.py.fill(0.0);
            let (its, _) = solve(self, p, options)?;
            sweeps += its;
            let f = self.forces();
            k0[0][col] = f.0;
            k0[1][col] = f.1;
        }
        self.bound.copy_from_slice(&saved);
        let mut param = solve2(&k0, target).ok_or(ContactError::NewtonNotConverged {
            iterations: 0,
            residual: f64::NAN,
        })?;
        let scale = param[0].hypot(param[1]).max(f64::MIN_POSITIVE);
        self.px.fill(0.0);
        self.py.fill(0.0);
        let (its, mut res) = solve(self, param, options)?;
        sweeps += its;
        let mut f = self.forces();
        let mut err = [f.0 - target[0], f.1 - target[1]];
        for iteration in 1..=options.max_newton {
            let norm = err[0].hypot(err[1]);
            if norm <= tol {
                return Ok((param, sweeps, iteration - 1, res));
            }
            // Jacobian by forward differences (warm-started solves), falling back to the
            // full-adhesion stiffness when it is singular (saturated patch).
            let h = 1e-6 * scale.max(param[0].hypot(param[1]));
            let (bpx, bpy) = (self.px.clone(), self.py.clone());
            let mut jac = [[0.0; 2]; 2];
            for col in 0..2 {
                let mut p = param;
                p[col] += h;
                self.px.copy_from_slice(&bpx);
                self.py.copy_from_slice(&bpy);
                let (its, _) = solve(self, p, options)?;
                sweeps += its;
                let fp = self.forces();
                jac[0][col] = (fp.0 - f.0) / h;
                jac[1][col] = (fp.1 - f.1) / h;
            }
            let step = solve2(&jac, [-err[0], -err[1]])
                .or_else(|| solve2(&k0, [-err[0], -err[1]]))
                .ok_or(ContactError::NewtonNotConverged {
                    iterations: iteration,
                    residual: norm,
                })?;
            // Step halving until the force error decreases.
            let mut lambda = 1.0;
            loop {
                let trial = [param[0] + lambda * step[0], param[1] + lambda * step[1]];
                self.px.copy_from_slice(&bpx);
                self.py.copy_from_slice(&bpy);
                let (its, r) = solve(self, trial, options)?;
                sweeps += its;
                let ft = self.forces();
                let et = [ft.0 - target[0], ft.1 - target[1]];
                if et[0].hypot(et[1]) < norm || lambda < 1e-3 {
                    param = trial;
                    f = ft;
                    err = et;
                    res = r;
                    break;
                }
                lambda *= 0.5;
            }
        }
        let norm = err[0].hypot(err[1]);
        if norm <= tol {
            return Ok((param, sweeps, options.max_newton, res));
        }
        Err(ContactError::NewtonNotConverged {
            iterations: options.max_newton,
            residual: norm,
        })
    }

    /// Total forces of the current tractions.
    pub(super) fn forces(&self) -> (f64, f64) {
        let a = self.grid().element_area();
        (
            a * self.px.iter().sum::<f64>(),
            a * self.py.iter().sum::<f64>(),
        )
    }
}

/// Solve the 2 × 2 system m x = r; `None` when singular. A zero row with a zero right-hand
/// side (a force component that vanishes by symmetry) keeps that unknown at zero.
fn solve2(m: &[[f64; 2]; 2], r: [f64; 2]) -> Option<[f64; 2]> {
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let scale = (m[0][0].abs() + m[0][1].abs()) * (m[1][0].abs() + m[1][1].abs());
    if det.abs() > 1e-12 * scale && det.is_finite() {
        return Some([
            (r[0] * m[1][1] - m[0][1] * r[1]) / det,
            (m[0][0] * r[1] - m[1][0] * r[0]) / det,
        ]);
    }
    // Decoupled fallbacks (e.g. a 2D grid where F_y does not respond to η).
    if m[0][0] != 0.0 && r[1] == 0.0 {
        return Some([r[0] / m[0][0], 0.0]);
    }
    if m[1][1] != 0.0 && r[0] == 0.0 {
        return Some([0.0, r[1] / m[1][1]]);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solve2_handles_decoupled_singular_systems() {
        assert_eq!(
            solve2(&[[2.0, 0.0], [0.0, 4.0]], [2.0, 8.0]),
            Some([1.0, 2.0])
        );
        // F_y does not respond (2D strip, η has no effect): keep η at zero.
        assert_eq!(
            solve2(&[[2.0, 0.0], [0.0, 0.0]], [2.0, 0.0]),
            Some([1.0, 0.0])
        );
        assert_eq!(solve2(&[[0.0, 0.0], [0.0, 0.0]], [1.0, 1.0]), None);
    }
}

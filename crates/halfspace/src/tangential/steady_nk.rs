//! Steady rolling by a semismooth Newton–Krylov iteration on the adhesion/slip split
//! (module documentation of [`super`], "Steady-rolling solver").

use super::gmres::{GmresWork, LinearProblem, gmres, gmres_with};
use super::nk_precondition::{Class, NewtonSystem};
use super::two_level::TwoLevel;
use super::{NkPreconditioner, TangentialOptions, TangentialSolver};
use crate::operator::{TangentialInfluenceOperator, TangentialKernel, Update};

/// GMRES restart length.
const RESTART: usize = 40;
/// Product limit of one inner solve.
const INNER_PRODUCTS: usize = 200;
/// The smallest grid (elements) on which [`NkPreconditioner::TwoLevel`] adds its coarse
/// correction; smaller grids (the 44 × 44 case, the coarse levels of a nested start) use the
/// line solve alone, which costs less there (docs/tangential.md "Performance").
const TWO_LEVEL_MIN: usize = 6000;
/// Newton-step limit before the Gauss–Seidel fallback (at most `max_iter`): the measured cases
/// need 5–15.
const MAX_NEWTON: usize = 100;

/// The Newton system J d = −F of one iteration, matrix-free (module documentation).
struct Jacobian<'a, T: TangentialInfluenceOperator> {
    op: &'a mut T,
    sys: NewtonSystem<'a>,
    /// The two-level correction ([`NkPreconditioner::TwoLevel`]), built for `sys`.
    two_level: Option<&'a mut TwoLevel>,
    products: usize,
    wx: Vec<f64>,
    wy: Vec<f64>,
    ux: Vec<f64>,
    uy: Vec<f64>,
}

impl<T: TangentialInfluenceOperator> LinearProblem for Jacobian<'_, T> {
    /// x holds (d_x, d_y) of the adhesion elements in the slots k and n + k, dθ of the slip
    /// elements in slot k.
    fn apply(&mut self, x: &[f64], out: &mut [f64]) {
        let sys = &self.sys;
        let n = sys.class.len();
        for k in 0..n {
            (self.ux[k], self.uy[k]) = sys.traction_change(x, k);
        }
        self.op.traction_product(
            TangentialKernel::Steady,
            Update::Set,
            (&self.ux, &self.uy),
            (&mut self.wx, &mut self.wy),
        );
        self.products += 1;
        for k in 0..n {
            (out[k], out[n + k]) = match sys.class[k] {
                Class::Exterior => (0.0, 0.0),
                Class::Adhesion => (self.wx[k], self.wy[k]),
                Class::Slip => (
                    sys.tx[k] * self.wx[k] + sys.ty[k] * self.wy[k] + sys.slip_speed[k] * x[k],
                    0.0,
                ),
            };
        }
    }

    /// The upstream line solve or the diagonal of J ([`NkPreconditioner`]).
    fn precondition(&mut self, r: &[f64], out: &mut [f64]) {
        match self.two_level.as_deref_mut() {
            Some(t) => t.apply(&self.sys, r, out),
            None => self.sys.precondition(r, out),
        }
    }
}

/// What a Newton–Krylov solve did.
#[derive(Debug, Clone, Copy)]
pub(super) struct NkReport {
    pub(super) newton: usize,
    pub(super) change: f64,
}

impl<T: TangentialInfluenceOperator> TangentialSolver<T> {
    /// (C_xx, C_xy, C_yy) of the steady kernel at offset (−1, 0): the influence of an element's
    /// upstream neighbour (one element further in +x) on it; zeros on a grid one element
    /// long in x.
    fn upstream_coefficients(&self) -> (f64, f64, f64) {
        let g = self.grid();
        if g.nx < 2 {
            return (0.0, 0.0, 0.0);
        }
        let n = g.len();
        let column = |change| {
            let (mut ux, mut uy) = (vec![0.0; n], vec![0.0; n]);
            self.operator.add_column(
                TangentialKernel::Steady,
                (1, 0),
                change,
                (&mut ux, &mut uy),
                (0, 0),
                (0, 0),
            );
            (ux[0], uy[0])
        };
        let (bxx, bxy) = column((1.0, 0.0));
        let (_, byy) = column((0.0, 1.0));
        (bxx, bxy, byy)
    }

    /// Steady rolling S = b + C p with C = A − A_v (prepared) by semismooth Newton–Krylov
    /// from the current p. Err(report) when it did not converge within
    /// min(`options.max_iter`, 100) Newton steps (the caller falls back to the Gauss–Seidel
    /// reference).
    pub(super) fn solve_steady_nk(
        &mut self,
        options: &TangentialOptions,
    ) -> Result<NkReport, NkReport> {
        let g = *self.grid();
        let n = g.len();
        let mut report = NkReport {
            newton: 0,
            change: f64::INFINITY,
        };
        let own = self.operator.own_coefficients(TangentialKernel::Steady);
        let upstream = match options.nk_preconditioner {
            NkPreconditioner::Jacobi => None,
            NkPreconditioner::UpstreamLine | NkPreconditioner::TwoLevel => {
                Some(self.upstream_coefficients())
            }
        };
        // Below TWO_LEVEL_MIN elements the line solve alone is cheaper.
        let mut two_level = (options.nk_preconditioner == NkPreconditioner::TwoLevel
            && n >= TWO_LEVEL_MIN)
            .then(|| {
                (
                    TwoLevel::new(&self.operator),
                    GmresWork::new(2 * n, RESTART, true),
                )
            });
        if !options.warm_start && !self.has_previous {
            self.px.fill(0.0);
            self.py.fill(0.0);
        }
        let mut class = vec![Class::Exterior; n];
        for k in 0..n {
            let bound = self.bound[k];
            if bound <= 0.0 {
                self.px[k] = 0.0;
                self.py[k] = 0.0;
                continue;
            }
            let t = self.px[k].hypot(self.py[k]);
            class[k] = if t >= bound * (1.0 - 1e-9) {
                self.px[k] *= bound / t;
                self.py[k] *= bound / t;
                Class::Slip
            } else {
                Class::Adhesion
            };
        }
        let (mut tx, mut ty) = (vec![0.0; n], vec![0.0; n]);
        let mut slip_speed = vec![0.0; n];
        let mut f = vec![0.0; 2 * n];
        let mut d = vec![0.0; 2 * n];
        let mut jac_scratch = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut eta: f64 = 0.1;
        let result = loop {
            if report.newton >= options.max_iter.min(MAX_NEWTON) {
                break Err(());
            }
            report.newton += 1;
            self.refresh_shift(TangentialKernel::Steady);
            // Active-set update: adhesion beyond the bound slips in its traction's direction;
            // slip whose S points along p (no dissipation) adheres.
            let mut changed = 0;
            for k in 0..n {
                let bound = self.bound[k];
                match class[k] {
                    Class::Exterior => {}
                    Class::Adhesion => {
                        let t = self.px[k].hypot(self.py[k]);
                        if t > bound {
                            self.px[k] *= bound / t;
                            self.py[k] *= bound / t;
                            class[k] = Class::Slip;
                            changed += 1;
                        }
                    }
                    Class::Slip => {
                        if self.sx[k] * self.px[k] + self.sy[k] * self.py[k] > 0.0 {
                            class[k] = Class::Adhesion;
                            changed += 1;
                        }
                    }
                }
            }
            if changed > 0 {
                self.refresh_shift(TangentialKernel::Steady);
            }
            // Residual F: S in adhesion, S·t in slip.
            let mut f2 = 0.0;
            for k in 0..n {
                let bound = self.bound[k];
                (f[k], f[n + k]) = match class[k] {
                    Class::Exterior => (0.0, 0.0),
                    Class::Adhesion => (-self.sx[k], -self.sy[k]),
                    Class::Slip => {
                        let (cx, cy) = (self.px[k] / bound, self.py[k] / bound);
                        (tx[k], ty[k]) = (-cy, cx);
                        slip_speed[k] = (-(cx * self.sx[k] + cy * self.sy[k])).max(0.0);
                        (-(tx[k] * self.sx[k] + ty[k] * self.sy[k]), 0.0)
                    }
                };
                f2 += f[k] * f[k] + f[n + k] * f[n + k];
            }
            if f2 == 0.0 {
                report.change = 0.0;
                break Ok(());
            }
            let (wx, wy, ux, uy) = std::mem::take(&mut jac_scratch);
            let sys = NewtonSystem {
                class: &class,
                tx: &tx,
                ty: &ty,
                slip_speed: &slip_speed,
                bound: &self.bound,
                own,
                upstream,
                nx: g.nx,
            };
            let (coarse, work) = match two_level.as_mut() {
                Some((t, w)) => {
                    // E is rebuilt when the split changed; with the same split it is kept
                    // (only the slip tangents and speeds differ).
                    if changed > 0 || report.newton == 1 {
                        t.build(&sys);
                    }
                    (Some(t), Some(w))
                }
                None => (None, None),
            };
            let mut jac = Jacobian {
                op: &mut self.operator,
                sys,
                two_level: coarse,
                products: 0,
                wx,
                wy,
                ux,
                uy,
            };
            // The relative residual GMRES reached: η, or more when it stopped at its product
            // limit; the stopping test below uses the larger, so a step solved less tightly
            // than asked cannot end the iteration early (docs/tangential.md).
            let reached = match work {
                Some(w) => gmres_with(&mut jac, &f, &mut d, eta, INNER_PRODUCTS, w),
                None => gmres(&mut jac, &f, &mut d, eta, RESTART, INNER_PRODUCTS),
            }
            .max(eta);
            self.products += jac.products;
            jac_scratch = (jac.wx, jac.wy, jac.ux, jac.uy);
            // Update: tractions in adhesion, angles in slip (a step of at most 0.5 rad).
            let (mut dp2, mut p2) = (0.0, 0.0);
            for k in 0..n {
                let (ox, oy) = (self.px[k], self.py[k]);
                match class[k] {
                    Class::Exterior => continue,
                    Class::Adhesion => {
                        self.px[k] += d[k];
                        self.py[k] += d[n + k];
                    }
                    Class::Slip => {
                        let bound = self.bound[k];
                        let theta = oy.atan2(ox) + d[k].clamp(-0.5, 0.5);
                        self.px[k] = bound * theta.cos();
                        self.py[k] = bound * theta.sin();
                    }
                }
                let (ddx, ddy) = (self.px[k] - ox, self.py[k] - oy);
                dp2 += ddx * ddx + ddy * ddy;
                p2 += self.px[k] * self.px[k] + self.py[k] * self.py[k];
            }
            report.change = if p2 > 0.0 { (dp2 / p2).sqrt() } else { 0.0 };
            let violated = (0..n).any(|k| {
                class[k] == Class::Adhesion
                    && self.px[k].hypot(self.py[k]) > self.bound[k] * (1.0 + 1e-9)
            });
            if report.change * reached <= options.tol && changed == 0 && !violated {
                break Ok(());
            }
            // Inexact Newton: the inner tolerance follows the step size.
            // Once the split is settled and the steps are small (the asymptotic regime), the
            // last step is solved tightly enough for its remaining error η‖Δp‖ to meet tol.
            eta = if changed > 0 || report.change > 1e-2 {
                0.1
            } else {
                (0.3 * options.tol / report.change).clamp(1e-3, 0.1)
            };
        };
        self.has_previous = true;
        // The exact S of the final tractions, the slip flags for the solution.
        for k in 0..n {
            self.slipping[k] = class[k] == Class::Slip;
        }
        self.refresh_shift(TangentialKernel::Steady);
        match result {
            Ok(()) => Ok(report),
            Err(()) => Err(report),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::grid::Grid;
    use crate::material::Material;
    use crate::operator::{
        DirectTangentialInfluence, FftTangentialInfluence, TangentialInfluenceOperator,
        TangentialKernel,
    };
    use crate::tangential::TangentialSolver;

    /// The coupling to the upstream neighbour that the line preconditioner uses is the
    /// negative of the own coefficient (A_v(δx) is A moved by exactly one element; xy vanishes
    /// on the row by symmetry), read from the FFT tables and from the direct oracle (closed-form
    /// coefficients, no table), on a non-square grid with dx ≠ dy.
    #[test]
    fn upstream_coupling_is_minus_the_own_coefficient() {
        let m = Material::from_combined(82e9, 0.28).unwrap();
        let grid = Grid::centred(6, 5, 0.4e-3, 0.7e-3, 0.0, 0.0).unwrap();
        let mut fft = FftTangentialInfluence::new(grid, &m).unwrap();
        fft.prepare(TangentialKernel::Steady);
        let direct = DirectTangentialInfluence::new(grid, m).unwrap();
        let a = TangentialSolver::with_operator(fft).unwrap();
        let b = TangentialSolver::with_operator(direct).unwrap();
        for (up, own) in [
            (
                a.upstream_coefficients(),
                a.operator.own_coefficients(TangentialKernel::Steady),
            ),
            (
                b.upstream_coefficients(),
                b.operator.own_coefficients(TangentialKernel::Steady),
            ),
        ] {
            assert!(own.0 > 0.0 && own.1 > 0.0);
            assert!((up.0 + own.0).abs() <= 1e-12 * own.0, "{up:?} {own:?}");
            assert!(up.1.abs() <= 1e-12 * own.0, "{up:?}");
            assert!((up.2 + own.1).abs() <= 1e-12 * own.1, "{up:?} {own:?}");
        }
    }
}

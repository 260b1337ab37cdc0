//! Steady rolling by a semismooth Newton–Krylov iteration on the adhesion/slip split
//! (module documentation of [`super`], "Steady-rolling solver").

use super::gmres::{LinearProblem, gmres};
use super::{TangentialOptions, TangentialSolver};
use crate::operator::{TangentialInfluenceOperator, TangentialKernel, Update};

/// Element class during the iteration.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Class {
    Exterior,
    Adhesion,
    Slip,
}

/// GMRES restart length.
const RESTART: usize = 40;
/// Product limit of one inner solve.
const INNER_PRODUCTS: usize = 200;
/// Newton-step limit before the Gauss–Seidel fallback (at most `max_iter`): the measured cases
/// need 5–15.
const MAX_NEWTON: usize = 100;

/// The Newton system J d = −F of one iteration, matrix-free (module documentation).
struct Jacobian<'a, T: TangentialInfluenceOperator> {
    op: &'a mut T,
    class: &'a [Class],
    /// Unit tangent t = (−sin θ, cos θ) of the slip elements.
    tx: &'a [f64],
    ty: &'a [f64],
    /// −p̂·S ≥ 0 of the slip elements (the slip speed |S| at the solution).
    slip_speed: &'a [f64],
    bound: &'a [f64],
    own: (f64, f64),
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
        let n = self.class.len();
        for k in 0..n {
            (self.ux[k], self.uy[k]) = match self.class[k] {
                Class::Exterior => (0.0, 0.0),
                Class::Adhesion => (x[k], x[n + k]),
                Class::Slip => {
                    let g = self.bound[k] * x[k];
                    (g * self.tx[k], g * self.ty[k])
                }
            };
        }
        self.op.traction_product(
            TangentialKernel::Steady,
            Update::Set,
            (&self.ux, &self.uy),
            (&mut self.wx, &mut self.wy),
        );
        self.products += 1;
        for k in 0..n {
            (out[k], out[n + k]) = match self.class[k] {
                Class::Exterior => (0.0, 0.0),
                Class::Adhesion => (self.wx[k], self.wy[k]),
                Class::Slip => (
                    self.tx[k] * self.wx[k] + self.ty[k] * self.wy[k] + self.slip_speed[k] * x[k],
                    0.0,
                ),
            };
        }
    }

    /// The diagonal of J (Jacobi): the own coefficients in adhesion, the slip row's
    /// diagonal in slip.
    fn precondition(&mut self, r: &[f64], out: &mut [f64]) {
        let n = self.class.len();
        let (dx, dy) = self.own;
        for k in 0..n {
            (out[k], out[n + k]) = match self.class[k] {
                Class::Exterior => (0.0, 0.0),
                Class::Adhesion => (r[k] / dx, r[n + k] / dy),
                Class::Slip => {
                    let (tx, ty) = (self.tx[k], self.ty[k]);
                    let d = self.slip_speed[k] + self.bound[k] * (tx * tx * dx + ty * ty * dy);
                    (if d > 0.0 { r[k] / d } else { 0.0 }, 0.0)
                }
            };
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
            let mut jac = Jacobian {
                op: &mut self.operator,
                class: &class,
                tx: &tx,
                ty: &ty,
                slip_speed: &slip_speed,
                bound: &self.bound,
                own,
                products: 0,
                wx,
                wy,
                ux,
                uy,
            };
            let _residual = gmres(&mut jac, &f, &mut d, eta, RESTART, INNER_PRODUCTS);
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
            if report.change * eta <= options.tol && changed == 0 && !violated {
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

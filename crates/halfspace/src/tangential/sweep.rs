//! The Gauss–Seidel sweep over the elements in contact (ConvexGS/SteadyGS) and the exact
//! solve of one element's Coulomb problem (module documentation of [`super`]).

use super::anderson::Anderson;
use super::coupling::add;
use super::{Creepages, ElementState, TangentialOptions, TangentialSolution, TangentialSolver};
use crate::error::ContactError;
use crate::operator::{TangentialInfluenceOperator, TangentialKernel, Update};

impl<T: TangentialInfluenceOperator> TangentialSolver<T> {
    /// Gauss–Seidel on S = b + C p with C the operator's `op` kernel (A or A − A_v, prepared)
    /// and the bound in `self.bound`, from the current p (zeroed where the bound is zero).
    /// Returns (sweeps, last relative change).
    pub(super) fn solve_current(
        &mut self,
        op: TangentialKernel,
        options: &TangentialOptions,
    ) -> Result<(usize, f64), ContactError> {
        let g = *self.grid();
        let (nx, ny) = (g.nx, g.ny);
        if !options.warm_start && !self.has_previous {
            self.px.fill(0.0);
            self.py.fill(0.0);
        }
        // Contact bounding box.
        let (mut ix0, mut ix1, mut iy0, mut iy1) = (nx, 0, ny, 0);
        for (k, &b) in self.bound.iter().enumerate() {
            if b > 0.0 {
                let (ix, iy) = (k % nx, k / nx);
                ix0 = ix0.min(ix);
                ix1 = ix1.max(ix);
                iy0 = iy0.min(iy);
                iy1 = iy1.max(iy);
            } else {
                self.px[k] = 0.0;
                self.py[k] = 0.0;
            }
        }
        if ix0 > ix1 {
            return Err(ContactError::NoContact {
                reason: "the pressure is zero everywhere",
            });
        }
        self.refresh_shift(op);
        let (dxx, dyy) = self.operator.own_coefficients(op);
        // Steady rolling: the operator is far from symmetric and plain GS can oscillate;
        // start at ω ≤ 0.5 and reduce ω by 0.6 whenever a sweep changes p more than the
        // previous one did (down to 0.05).
        let mut omega = match op {
            TangentialKernel::Steady => options.omega.min(0.5),
            _ => options.omega,
        };
        let mut change = f64::INFINITY;
        let mut previous_change = f64::INFINITY;
        let depth = options.anderson_depth;
        let n = g.len();
        let mut anderson = (depth > 0).then(|| Anderson::new(depth, 2 * n));
        let mut accelerated = false;
        for sweep in 1..=options.max_iter {
            if accelerated && iy1 == iy0 {
                self.refresh_shift(op);
            }
            accelerated = false;
            if let Some(a) = anderson.as_mut() {
                a.x[..n].copy_from_slice(&self.px);
                a.x[n..].copy_from_slice(&self.py);
            }
            // Rows are swept from iy0 up; a traction change updates S only in its own and the
            // later rows (the ones still to be visited in this sweep). The earlier rows are
            // brought up to date here by FFT convolution, so every element sees exactly the
            // S of full Gauss–Seidel at half the dense work.
            if sweep > 1 && iy1 > iy0 {
                self.refresh_shift(op);
            }
            let (mut dp2, mut p2) = (0.0, 0.0);
            for iy in iy0..=iy1 {
                for ix in (ix0..=ix1).rev() {
                    let k = iy * nx + ix;
                    let bound = self.bound[k];
                    if bound <= 0.0 {
                        continue;
                    }
                    let (ox, oy) = (self.px[k], self.py[k]);
                    let rx = self.sx[k] - dxx * ox;
                    let ry = self.sy[k] - dyy * oy;
                    let (mut nxv, mut nyv, slipping) = local_solve(rx, ry, dxx, dyy, bound);
                    if !slipping || op == TangentialKernel::Steady {
                        nxv = ox + omega * (nxv - ox);
                        nyv = oy + omega * (nyv - oy);
                    }
                    self.slipping[k] = slipping;
                    let (ddx, ddy) = (nxv - ox, nyv - oy);
                    self.px[k] = nxv;
                    self.py[k] = nyv;
                    p2 += nxv * nxv + nyv * nyv;
                    if ddx == 0.0 && ddy == 0.0 {
                        continue;
                    }
                    dp2 += ddx * ddx + ddy * ddy;
                    self.operator.add_column(
                        op,
                        (ix, iy),
                        (ddx, ddy),
                        (&mut self.sx, &mut self.sy),
                        (ix0, ix1),
                        (iy, iy1),
                    );
                }
            }
            change = if p2 > 0.0 { (dp2 / p2).sqrt() } else { 0.0 };
            if op == TangentialKernel::Steady && sweep > 2 && change > previous_change {
                omega = (0.6 * omega).max(0.05);
            }
            previous_change = change;
            if change > options.tol
                && let Some(a) = anderson.as_mut()
            {
                a.gx[..n].copy_from_slice(&self.px);
                a.gx[n..].copy_from_slice(&self.py);
                a.step();
                for k in 0..n {
                    let bound = self.bound[k];
                    let (mut x, mut y) = (a.x[k], a.x[n + k]);
                    if bound <= 0.0 {
                        x = 0.0;
                        y = 0.0;
                    } else {
                        let t = x.hypot(y);
                        if t > bound {
                            x *= bound / t;
                            y *= bound / t;
                        }
                    }
                    self.px[k] = x;
                    self.py[k] = y;
                }
                accelerated = true;
            }
            if change <= options.tol {
                self.has_previous = true;
                // Relaxed (or accelerated) updates leave slip elements within O(tol) of the
                // bound: put them on it, then compute the exact S for the reported slip.
                for k in 0..n {
                    if self.slipping[k] && self.bound[k] > 0.0 {
                        let t = self.px[k].hypot(self.py[k]);
                        if t > 0.0 {
                            let f = self.bound[k] / t;
                            self.px[k] *= f;
                            self.py[k] *= f;
                        }
                    }
                }
                self.refresh_shift(op);
                return Ok((sweep, change));
            }
        }
        self.has_previous = true;
        Err(ContactError::TangentialNotConverged {
            iterations: options.max_iter,
            residual: change,
        })
    }

    /// S = C p + b exactly (one operator product): at the start of a solve, before each
    /// sweep over several rows, after an acceleration step and at convergence.
    pub(super) fn refresh_shift(&mut self, op: TangentialKernel) {
        self.products += 1;
        self.operator.traction_product(
            op,
            Update::Set,
            (&self.px, &self.py),
            (&mut self.sx, &mut self.sy),
        );
        add(&mut self.sx, &self.bx);
        add(&mut self.sy, &self.by);
    }

    pub(super) fn solution(
        &self,
        delta_q: f64,
        creepages: Creepages,
        shift: (f64, f64),
        iterations: usize,
        newton_iterations: usize,
        residual: f64,
    ) -> TangentialSolution {
        let g = *self.grid();
        let n = g.len();
        let area = g.element_area();
        let scale = if delta_q > 0.0 { 1.0 / delta_q } else { 1.0 };
        let mut state = vec![ElementState::Exterior; n];
        let mut slip_x = vec![0.0; n];
        let mut slip_y = vec![0.0; n];
        let (mut fx, mut fy, mut mz, mut power) = (0.0, 0.0, 0.0, 0.0);
        let (mut adhesion, mut slip) = (0, 0);
        for k in 0..n {
            let (x, y) = g.centre(k);
            let (px, py) = (self.px[k], self.py[k]);
            fx += px;
            fy += py;
            mz += x * py - y * px;
            if self.bound[k] <= 0.0 {
                continue;
            }
            if self.slipping[k] {
                state[k] = ElementState::Slip;
                slip += 1;
                slip_x[k] = self.sx[k] * scale;
                slip_y[k] = self.sy[k] * scale;
                power -= px * slip_x[k] + py * slip_y[k];
            } else {
                state[k] = ElementState::Adhesion;
                adhesion += 1;
            }
        }
        TangentialSolution {
            grid: g,
            traction_x: self.px.clone(),
            traction_y: self.py.clone(),
            state,
            slip_x,
            slip_y,
            force_x: fx * area,
            force_y: fy * area,
            moment_z: mz * area,
            adhesion_elements: adhesion,
            slip_elements: slip,
            frictional_power: power * area,
            creepages,
            shift,
            delta_q,
            iterations,
            newton_iterations,
            residual,
            products: self.products,
            steady_fallback: self.fallback,
            coarse_products: self.coarse_products.clone(),
        }
    }
}

/// Exact solution of one element's problem (module documentation): returns (p_x, p_y, slips).
fn local_solve(rx: f64, ry: f64, cx: f64, cy: f64, g: f64) -> (f64, f64, bool) {
    let (ax, ay) = (-rx / cx, -ry / cy);
    if ax.hypot(ay) <= g {
        return (ax, ay, false);
    }
    // Slip: λ = |S| > 0 with (r_x/(λ + g c_x))² + (r_y/(λ + g c_y))² = 1.
    let (gx, gy) = (g * cx, g * cy);
    let lambda = if (cx - cy).abs() <= 1e-12 * cx.abs().max(cy.abs()) {
        (rx.hypot(ry) - gx).max(0.0)
    } else {
        let mut l: f64 = 0.0;
        for _ in 0..100 {
            let (ux, uy) = (rx / (l + gx), ry / (l + gy));
            let f = ux * ux + uy * uy - 1.0;
            let df = -2.0 * (ux * ux / (l + gx) + uy * uy / (l + gy));
            let step = f / df;
            l -= step;
            if step.abs() <= 1e-15 * (l.abs() + gx.min(gy)) {
                break;
            }
        }
        l.max(0.0)
    };
    let (tx, ty) = (rx / (lambda + gx), ry / (lambda + gy));
    let t = tx.hypot(ty);
    (-g * tx / t, -g * ty / t, true)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn element_solve_satisfies_coulomb_exactly() {
        // For anisotropic own coefficients (C_xx ≠ C_yy) the slip solution must lie on the
        // bound, with the resulting shift S = r + D p opposite to p (Coulomb's law), checked
        // directly for a fan of right-hand sides; inside the bound S = 0.
        let (cx, cy, g) = (1.3, 0.7, 2.0);
        for k in 0..24 {
            let t = k as f64 * std::f64::consts::PI / 12.0 + 0.1;
            for mag in [0.5, 2.0, 10.0] {
                let (rx, ry) = (mag * t.cos(), mag * t.sin());
                let (px, py, slip) = local_solve(rx, ry, cx, cy, g);
                let (sx, sy) = (rx + cx * px, ry + cy * py);
                if slip {
                    assert!((px.hypot(py) - g).abs() < 1e-12 * g);
                    // S ∥ −p with a positive factor.
                    let cross = sx * py - sy * px;
                    assert!(cross.abs() < 1e-10 * mag * g, "{cross}");
                    assert!(sx * px + sy * py < 0.0);
                } else {
                    assert!(px.hypot(py) <= g * (1.0 + 1e-12));
                    assert!(sx.hypot(sy) < 1e-14 * mag);
                }
            }
        }
        // Isotropic fast path: the same law.
        let (px, py, slip) = local_solve(3.0, 4.0, 1.0, 1.0, 1.0);
        assert!(slip);
        assert!((px + 0.6).abs() < 1e-15 && (py + 0.8).abs() < 1e-15);
    }
}

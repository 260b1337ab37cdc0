//! Preconditioners of the linear systems J d = −F of the steady-rolling Newton–Krylov solver
//! (module documentation of [`super`], "Steady rolling"; references.md §C3.9, §C3.10): the
//! diagonal of J (Jacobi) and the upstream line solve (the default).
//!
//! **Upstream line solve.** With δq = δx the kernel A_v(δx) is A with the observation point
//! moved by exactly one element, so the steady coefficients C = A − A_v satisfy
//! C(o_x − 1, o_y) = A(o_x − 1, o_y) − A(o_x, o_y) and in particular C(−1, 0) = −C(0, 0) for the
//! symmetric A_xx, A_yy: the coupling of an element to its upstream neighbour (the element one
//! step further in +x, towards the leading edge) is as strong as its own coefficient, the
//! discrete derivative along the rolling direction. A diagonal preconditioner leaves this
//! transport operator to GMRES, which then needs about one iteration per element of a grid
//! row to carry information from the leading to the trailing edge. The line solve keeps the
//! diagonal blocks of J and the blocks of the upstream neighbour and solves that
//! block-lower-bidiagonal system exactly, marching each grid row from the leading edge (the
//! SteadyGS order, references.md §C3.5; FASTSIM marches the same way): O(N) per application.

/// Element class during the Newton iteration.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Class {
    Exterior,
    Adhesion,
    Slip,
}

/// The structure of one Newton system: the classes, the slip tangents and the kernel
/// coefficients the preconditioners use. Unknowns: (d_x, d_y) of an adhesion element k in the
/// slots k and n + k, dθ of a slip element in slot k (slot n + k unused, zero).
pub(super) struct NewtonSystem<'a> {
    pub(super) class: &'a [Class],
    /// Unit tangent t = (−sin θ, cos θ) of the slip elements.
    pub(super) tx: &'a [f64],
    pub(super) ty: &'a [f64],
    /// −p̂·S ≥ 0 of the slip elements (the slip speed |S| at the solution).
    pub(super) slip_speed: &'a [f64],
    pub(super) bound: &'a [f64],
    /// (C_xx, C_yy) of an element on itself.
    pub(super) own: (f64, f64),
    /// (C_xx, C_xy, C_yy) of an element on its upstream neighbour's traction (offset −1 in x);
    /// `None` selects the Jacobi preconditioner.
    pub(super) upstream: Option<(f64, f64, f64)>,
    /// Elements per grid row (x fastest).
    pub(super) nx: usize,
}

impl NewtonSystem<'_> {
    /// The diagonal entry of the slip row of element k: |S| + g t·C(0) t.
    pub(super) fn slip_diagonal(&self, k: usize) -> f64 {
        let (dx, dy) = self.own;
        let (tx, ty) = (self.tx[k], self.ty[k]);
        self.slip_speed[k] + self.bound[k] * (tx * tx * dx + ty * ty * dy)
    }

    /// The traction change of element k for the unknowns `x` (zero outside the contact).
    pub(super) fn traction_change(&self, x: &[f64], k: usize) -> (f64, f64) {
        let n = self.class.len();
        match self.class[k] {
            Class::Exterior => (0.0, 0.0),
            Class::Adhesion => (x[k], x[n + k]),
            Class::Slip => {
                let g = self.bound[k] * x[k];
                (g * self.tx[k], g * self.ty[k])
            }
        }
    }

    /// out = M r (module documentation).
    pub(super) fn precondition(&self, r: &[f64], out: &mut [f64]) {
        match self.upstream {
            None => self.solve_rows(r, out, (0.0, 0.0, 0.0)),
            Some(b) => self.solve_rows(r, out, b),
        }
    }

    /// Solve (diagonal + upstream-neighbour blocks of J) out = r, row by row from the leading
    /// edge (largest x); with `b` = 0 this is the Jacobi preconditioner.
    fn solve_rows(&self, r: &[f64], out: &mut [f64], (bxx, bxy, byy): (f64, f64, f64)) {
        let n = self.class.len();
        let nx = self.nx;
        let (dx, dy) = self.own;
        for row in (0..n).step_by(nx) {
            for ix in (0..nx).rev() {
                let k = row + ix;
                // The upstream neighbour (already solved): its traction change through C(−1, 0).
                let (ux, uy) = if ix + 1 < nx {
                    self.traction_change(out, k + 1)
                } else {
                    (0.0, 0.0)
                };
                let (cx, cy) = (bxx * ux + bxy * uy, bxy * ux + byy * uy);
                (out[k], out[n + k]) = match self.class[k] {
                    Class::Exterior => (0.0, 0.0),
                    Class::Adhesion => ((r[k] - cx) / dx, (r[n + k] - cy) / dy),
                    Class::Slip => {
                        let d = self.slip_diagonal(k);
                        let rhs = r[k] - (self.tx[k] * cx + self.ty[k] * cy);
                        (if d > 0.0 { rhs / d } else { 0.0 }, 0.0)
                    }
                };
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The line solve inverts the block-lower-bidiagonal part of J exactly: J_trunc, built
    /// here element by element from its definition (own block on the diagonal, the upstream
    /// block to the neighbour at +x, rows and columns transformed by the classes), applied to
    /// a random x and then preconditioned, gives x back; with no upstream block it is the
    /// diagonal scaling.
    #[test]
    fn line_solve_inverts_the_bidiagonal_part() {
        let (nx, ny) = (5, 4);
        let n = nx * ny;
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64) / (1u64 << 53) as f64
        };
        let class: Vec<Class> = (0..n)
            .map(|_| match (3.0 * rnd()) as usize {
                0 => Class::Exterior,
                1 => Class::Adhesion,
                _ => Class::Slip,
            })
            .collect();
        let theta: Vec<f64> = (0..n).map(|_| 6.0 * rnd()).collect();
        let tx: Vec<f64> = theta.iter().map(|t| -t.sin()).collect();
        let ty: Vec<f64> = theta.iter().map(|t| t.cos()).collect();
        let slip_speed: Vec<f64> = (0..n).map(|_| rnd()).collect();
        let bound: Vec<f64> = (0..n).map(|_| 0.5 + rnd()).collect();
        let own = (2.0, 3.0);
        let up = (-2.0, 0.3, -3.0);
        let sys = NewtonSystem {
            class: &class,
            tx: &tx,
            ty: &ty,
            slip_speed: &slip_speed,
            bound: &bound,
            own,
            upstream: Some(up),
            nx,
        };
        let mut x = vec![0.0; 2 * n];
        for k in 0..n {
            match class[k] {
                Class::Exterior => {}
                Class::Adhesion => (x[k], x[n + k]) = (rnd() - 0.5, rnd() - 0.5),
                Class::Slip => x[k] = rnd() - 0.5,
            }
        }
        // y = J_trunc x.
        let mut y = vec![0.0; 2 * n];
        for k in 0..n {
            let (px, py) = sys.traction_change(&x, k);
            let (mut ux, mut uy) = (own.0 * px, own.1 * py);
            if k % nx + 1 < nx {
                let (qx, qy) = sys.traction_change(&x, k + 1);
                ux += up.0 * qx + up.1 * qy;
                uy += up.1 * qx + up.2 * qy;
            }
            (y[k], y[n + k]) = match class[k] {
                Class::Exterior => (0.0, 0.0),
                Class::Adhesion => (ux, uy),
                Class::Slip => (tx[k] * ux + ty[k] * uy + slip_speed[k] * x[k], 0.0),
            };
        }
        let mut z = vec![0.0; 2 * n];
        sys.precondition(&y, &mut z);
        for k in 0..2 * n {
            assert!(
                (z[k] - x[k]).abs() < 1e-12,
                "slot {k}: {} vs {}",
                z[k],
                x[k]
            );
        }
        // Jacobi: the diagonal only.
        let jacobi = NewtonSystem {
            upstream: None,
            ..sys
        };
        jacobi.precondition(&y, &mut z);
        for k in 0..n {
            match class[k] {
                Class::Exterior => assert_eq!((z[k], z[n + k]), (0.0, 0.0)),
                Class::Adhesion => {
                    assert!((z[k] - y[k] / own.0).abs() < 1e-14);
                    assert!((z[n + k] - y[n + k] / own.1).abs() < 1e-14);
                }
                Class::Slip => {
                    let d =
                        slip_speed[k] + bound[k] * (tx[k].powi(2) * own.0 + ty[k].powi(2) * own.1);
                    assert!((z[k] - y[k] / d).abs() < 1e-14);
                }
            }
        }
    }
}

//! Restarted GMRES with right preconditioning (Saad & Schultz, SIAM J. Sci. Stat. Comput. 7
//! (1986) 856; references.md §C3.9), matrix-free: the inner linear solver of the
//! steady-rolling Newton–Krylov iteration.

use crate::linalg::dot;

/// A linear operator J and a preconditioner M ≈ J⁻¹, both applied to whole vectors.
pub(super) trait LinearProblem {
    /// out = J x.
    fn apply(&mut self, x: &[f64], out: &mut [f64]);
    /// out = M r.
    fn precondition(&mut self, r: &[f64], out: &mut [f64]);
}

/// The vectors of one GMRES solve, kept between solves of the same size so that repeated
/// solves (the inner coarse solves of [`super::two_level`]) allocate nothing. The default
/// holds no vectors (a placeholder while the work is lent out; it allocates nothing).
#[derive(Default)]
pub(super) struct GmresWork {
    restart: usize,
    flexible: bool,
    v: Vec<Vec<f64>>,
    /// Flexible GMRES (Saad 1993, references.md §C3.11): the preconditioned basis M_k v_k.
    zs: Vec<Vec<f64>>,
    h: Vec<f64>,
    cs: Vec<f64>,
    sn: Vec<f64>,
    g: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    w: Vec<f64>,
    r: Vec<f64>,
}

impl GmresWork {
    /// Work vectors for systems of `n` unknowns, restarted every `restart` steps; `flexible`
    /// stores the preconditioned basis (a preconditioner that changes between applications,
    /// such as an inner iteration).
    pub(super) fn new(n: usize, restart: usize, flexible: bool) -> Self {
        let m = restart.max(1);
        GmresWork {
            restart: m,
            flexible,
            v: vec![vec![0.0; n]; m + 1],
            zs: if flexible {
                vec![vec![0.0; n]; m]
            } else {
                Vec::new()
            },
            h: vec![0.0; (m + 1) * m],
            cs: vec![0.0; m],
            sn: vec![0.0; m],
            g: vec![0.0; m + 1],
            y: vec![0.0; m],
            z: vec![0.0; n],
            w: vec![0.0; n],
            r: vec![0.0; n],
        }
    }

    /// The number of unknowns these vectors hold.
    pub(super) fn len(&self) -> usize {
        self.z.len()
    }
}

/// Solve J x = b from x = 0 until ‖b − J x‖ ≤ `rtol` ‖b‖ or `max_products` products with
/// J; restart every `restart` steps. Returns the relative residual ‖b − J x‖/‖b‖ (that of the
/// Arnoldi recurrence, checked against a true residual at every restart).
pub(super) fn gmres(
    problem: &mut impl LinearProblem,
    b: &[f64],
    x: &mut [f64],
    rtol: f64,
    restart: usize,
    max_products: usize,
) -> f64 {
    let mut work = GmresWork::new(b.len(), restart, false);
    gmres_with(problem, b, x, rtol, max_products, &mut work)
}

/// [`gmres`] with the vectors of `work` (its restart length; flexible if `work` is).
pub(super) fn gmres_with(
    problem: &mut impl LinearProblem,
    b: &[f64],
    x: &mut [f64],
    rtol: f64,
    max_products: usize,
    work: &mut GmresWork,
) -> f64 {
    let n = b.len();
    assert_eq!(work.len(), n, "GMRES work vectors of the system's size");
    x.fill(0.0);
    let bnorm = dot(b, b).sqrt();
    if bnorm == 0.0 {
        return 0.0;
    }
    let m = work.restart;
    let flexible = work.flexible;
    let GmresWork {
        v,
        zs,
        h,
        cs,
        sn,
        g,
        y,
        z,
        w,
        r,
        ..
    } = work;
    r.copy_from_slice(b);
    let mut products = 0;
    let mut rnorm = bnorm;
    while products < max_products {
        // r = b − J x (x = 0 on the first cycle: r = b).
        if products > 0 {
            problem.apply(x, w);
            products += 1;
            for i in 0..n {
                r[i] = b[i] - w[i];
            }
            rnorm = dot(r, r).sqrt();
        }
        if rnorm <= rtol * bnorm {
            break;
        }
        for i in 0..n {
            v[0][i] = r[i] / rnorm;
        }
        g.fill(0.0);
        g[0] = rnorm;
        let mut k = 0;
        while k < m && products < max_products {
            if flexible {
                problem.precondition(&v[k], &mut zs[k]);
                problem.apply(&zs[k], w);
            } else {
                problem.precondition(&v[k], z);
                problem.apply(z, w);
            }
            products += 1;
            // Modified Gram–Schmidt.
            for j in 0..=k {
                let hj = dot(w, &v[j]);
                h[j * m + k] = hj;
                for (wi, vi) in w.iter_mut().zip(&v[j]) {
                    *wi -= hj * vi;
                }
            }
            let hn = dot(w, w).sqrt();
            h[(k + 1) * m + k] = hn;
            if hn > 0.0 {
                for (vi, wi) in v[k + 1].iter_mut().zip(w.iter()) {
                    *vi = wi / hn;
                }
            }
            // Apply the previous rotations, then a new one that zeroes h[k+1][k].
            for j in 0..k {
                let (a, bb) = (h[j * m + k], h[(j + 1) * m + k]);
                h[j * m + k] = cs[j] * a + sn[j] * bb;
                h[(j + 1) * m + k] = -sn[j] * a + cs[j] * bb;
            }
            let (a, bb) = (h[k * m + k], h[(k + 1) * m + k]);
            let d = a.hypot(bb);
            (cs[k], sn[k]) = if d > 0.0 { (a / d, bb / d) } else { (1.0, 0.0) };
            h[k * m + k] = d;
            h[(k + 1) * m + k] = 0.0;
            g[k + 1] = -sn[k] * g[k];
            g[k] *= cs[k];
            k += 1;
            rnorm = g[k].abs();
            if rnorm <= rtol * bnorm || hn == 0.0 {
                break;
            }
        }
        // y from the triangular system; x += M (V y), or x += Z y when flexible.
        for i in (0..k).rev() {
            let mut s = g[i];
            for j in i + 1..k {
                s -= h[i * m + j] * y[j];
            }
            y[i] = if h[i * m + i] != 0.0 {
                s / h[i * m + i]
            } else {
                0.0
            };
        }
        if flexible {
            for (j, yj) in y[..k].iter().enumerate() {
                for (xi, zi) in x.iter_mut().zip(&zs[j]) {
                    *xi += yj * zi;
                }
            }
        } else {
            w.fill(0.0);
            for (j, yj) in y[..k].iter().enumerate() {
                for (wi, vi) in w.iter_mut().zip(&v[j]) {
                    *wi += yj * vi;
                }
            }
            problem.precondition(w, z);
            for (xi, zi) in x.iter_mut().zip(z.iter()) {
                *xi += zi;
            }
        }
        if rnorm <= rtol * bnorm {
            break;
        }
    }
    rnorm / bnorm
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A non-symmetric tridiagonal test matrix (convection–diffusion-like) with a Jacobi
    /// preconditioner.
    struct Tri {
        n: usize,
    }

    impl LinearProblem for Tri {
        fn apply(&mut self, x: &[f64], out: &mut [f64]) {
            for i in 0..self.n {
                let left = if i > 0 { x[i - 1] } else { 0.0 };
                let right = if i + 1 < self.n { x[i + 1] } else { 0.0 };
                out[i] = 4.0 * x[i] - 1.5 * left - 0.5 * right;
            }
        }
        fn precondition(&mut self, r: &[f64], out: &mut [f64]) {
            for (o, v) in out.iter_mut().zip(r) {
                *o = v / 4.0;
            }
        }
    }

    #[test]
    fn solves_a_nonsymmetric_system_to_the_requested_residual() {
        // Independent check: the true residual ‖b − J x‖ computed after the solve, with and
        // without restarts.
        let n = 200;
        let b: Vec<f64> = (0..n).map(|i| ((i * 7 % 13) as f64) - 6.0).collect();
        for restart in [5, 50] {
            let mut p = Tri { n };
            let mut x = vec![0.0; n];
            let rel = gmres(&mut p, &b, &mut x, 1e-10, restart, 2000);
            let mut jx = vec![0.0; n];
            p.apply(&x, &mut jx);
            let res: f64 = jx
                .iter()
                .zip(&b)
                .map(|(a, c)| (a - c).powi(2))
                .sum::<f64>()
                .sqrt();
            let bn: f64 = b.iter().map(|v| v * v).sum::<f64>().sqrt();
            assert!(res <= 1.01e-10 * bn, "restart {restart}: {res:e}");
            assert!(rel <= 1e-10);
        }
    }

    /// Flexible GMRES (the preconditioned basis stored) with a fixed linear preconditioner is
    /// the same method as right-preconditioned GMRES: the same solution to round-off, the same
    /// residual, from the same reused work vectors twice.
    #[test]
    fn flexible_gmres_equals_gmres_for_a_fixed_preconditioner() {
        let n = 120;
        let b: Vec<f64> = (0..n).map(|i| ((i * 5 % 11) as f64) - 5.0).collect();
        let mut p = Tri { n };
        let mut x = vec![0.0; n];
        let r0 = gmres(&mut p, &b, &mut x, 1e-9, 30, 500);
        let mut work = GmresWork::new(n, 30, true);
        for _ in 0..2 {
            let mut y = vec![0.0; n];
            let r1 = gmres_with(&mut p, &b, &mut y, 1e-9, 500, &mut work);
            assert!((r0 - r1).abs() <= 1e-12, "{r0:e} {r1:e}");
            for (a, c) in x.iter().zip(&y) {
                assert!((a - c).abs() <= 1e-10 * (1.0 + a.abs()), "{a} {c}");
            }
        }
    }
}

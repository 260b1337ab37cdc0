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
    let n = b.len();
    x.fill(0.0);
    let bnorm = dot(b, b).sqrt();
    if bnorm == 0.0 {
        return 0.0;
    }
    let m = restart.max(1);
    let mut v: Vec<Vec<f64>> = vec![vec![0.0; n]; m + 1];
    let mut h = vec![0.0; (m + 1) * m];
    let (mut cs, mut sn, mut g) = (vec![0.0; m], vec![0.0; m], vec![0.0; m + 1]);
    let (mut z, mut w, mut r) = (vec![0.0; n], vec![0.0; n], b.to_vec());
    let mut products = 0;
    let mut rnorm = bnorm;
    while products < max_products {
        // r = b − J x (x = 0 on the first cycle: r = b).
        if products > 0 {
            problem.apply(x, &mut w);
            products += 1;
            for i in 0..n {
                r[i] = b[i] - w[i];
            }
            rnorm = dot(&r, &r).sqrt();
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
            problem.precondition(&v[k], &mut z);
            problem.apply(&z, &mut w);
            products += 1;
            // Modified Gram–Schmidt.
            for j in 0..=k {
                let hj = dot(&w, &v[j]);
                h[j * m + k] = hj;
                for (wi, vi) in w.iter_mut().zip(&v[j]) {
                    *wi -= hj * vi;
                }
            }
            let hn = dot(&w, &w).sqrt();
            h[(k + 1) * m + k] = hn;
            if hn > 0.0 {
                for (vi, wi) in v[k + 1].iter_mut().zip(&w) {
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
        // y from the triangular system, x += M (V y).
        let mut y = vec![0.0; k];
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
        w.fill(0.0);
        for (j, yj) in y.iter().enumerate() {
            for (wi, vi) in w.iter_mut().zip(&v[j]) {
                *wi += yj * vi;
            }
        }
        problem.precondition(&w, &mut z);
        for (xi, zi) in x.iter_mut().zip(&z) {
            *xi += zi;
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
}

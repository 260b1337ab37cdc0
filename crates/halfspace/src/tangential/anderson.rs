//! Anderson acceleration (Walker & Ni, SIAM J. Numer. Anal. 49 (2011) 1715) of the sweep map.

use crate::linalg::{dot, solve_dense};

/// Anderson acceleration (type II, depth m) of the Gauss–Seidel sweep map x ↦ G(x).
#[derive(Debug)]
pub(super) struct Anderson {
    m: usize,
    /// Current iterate x_k (input) and G(x_k) (set by the caller); x_{k+1} on return.
    pub(super) x: Vec<f64>,
    pub(super) gx: Vec<f64>,
    prev_x: Vec<f64>,
    prev_f: Vec<f64>,
    f: Vec<f64>,
    dx: Vec<Vec<f64>>,
    df: Vec<Vec<f64>>,
    count: usize,
    prev_norm: f64,
}

impl Anderson {
    pub(super) fn new(m: usize, len: usize) -> Self {
        Anderson {
            m,
            x: vec![0.0; len],
            gx: vec![0.0; len],
            prev_x: vec![0.0; len],
            prev_f: vec![0.0; len],
            f: vec![0.0; len],
            dx: vec![vec![0.0; len]; m],
            df: vec![vec![0.0; len]; m],
            count: 0,
            prev_norm: f64::INFINITY,
        }
    }

    pub(super) fn step(&mut self) {
        let len = self.x.len();
        for i in 0..len {
            self.f[i] = self.gx[i] - self.x[i];
        }
        let norm: f64 = self.f.iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm > 2.0 * self.prev_norm {
            self.count = 0;
        }
        self.prev_norm = norm;
        if self.count > 0 {
            let slot = (self.count - 1) % self.m;
            for i in 0..len {
                self.dx[slot][i] = self.x[i] - self.prev_x[i];
                self.df[slot][i] = self.f[i] - self.prev_f[i];
            }
        }
        self.prev_x.copy_from_slice(&self.x);
        self.prev_f.copy_from_slice(&self.f);
        let k = self.count.min(self.m);
        self.count += 1;
        if k == 0 {
            self.x.copy_from_slice(&self.gx);
            return;
        }
        // Normal equations (dFᵀdF + εI) γ = dFᵀ f.
        let mut a = vec![0.0; k * k];
        let mut b = vec![0.0; k];
        for p in 0..k {
            for q in 0..k {
                a[p * k + q] = dot(&self.df[p], &self.df[q]);
            }
            b[p] = dot(&self.df[p], &self.f);
        }
        let trace: f64 = (0..k).map(|p| a[p * k + p]).sum();
        for p in 0..k {
            a[p * k + p] += 1e-10 * trace.max(f64::MIN_POSITIVE);
        }
        let Some(gamma) = solve_dense(&mut a, &mut b, k) else {
            self.count = 0;
            self.x.copy_from_slice(&self.gx);
            return;
        };
        for i in 0..len {
            let mut v = self.gx[i];
            for (p, gp) in gamma.iter().enumerate() {
                v -= gp * (self.dx[p][i] + self.df[p][i]);
            }
            self.x[i] = v;
        }
    }
}

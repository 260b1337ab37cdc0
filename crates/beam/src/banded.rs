//! Symmetric positive-definite banded matrices: storage, product and Cholesky factorisation
//! (Golub & Van Loan, *Matrix Computations*, 4th ed., Alg. 4.3.5), O(n b²) work for half-bandwidth b.

use faer::Mat;

use crate::error::BeamError;

/// Lower band of a symmetric matrix: `band[i * (b + 1) + k]` holds A[i, i − b + k].
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SymmetricBand {
    n: usize,
    b: usize,
    band: Vec<f64>,
}

impl SymmetricBand {
    /// The n × n zero matrix with half-bandwidth b.
    pub(crate) fn zeros(n: usize, b: usize) -> Self {
        Self {
            n,
            b,
            band: vec![0.0; n * (b + 1)],
        }
    }

    /// Dimension n.
    pub(crate) fn n(&self) -> usize {
        self.n
    }

    /// A[i, j] += v (and A[j, i]); requires |i − j| ≤ b.
    pub(crate) fn add(&mut self, i: usize, j: usize, v: f64) {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        debug_assert!(i - j <= self.b);
        self.band[i * (self.b + 1) + (j + self.b - i)] += v;
    }

    /// Entry A[i, j] (zero outside the band).
    pub(crate) fn entry(&self, i: usize, j: usize) -> f64 {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        if i - j > self.b { 0.0 } else { self.get(i, j) }
    }

    /// self + σ · other (same dimension and bandwidth).
    pub(crate) fn plus_scaled(&self, other: &Self, sigma: f64) -> Self {
        let band = self
            .band
            .iter()
            .zip(&other.band)
            .map(|(a, b)| a + sigma * b)
            .collect();
        Self {
            n: self.n,
            b: self.b,
            band,
        }
    }

    /// The full dense symmetric matrix.
    pub(crate) fn to_dense(&self) -> Mat<f64> {
        Mat::from_fn(self.n, self.n, |i, j| self.entry(i, j))
    }

    #[inline]
    fn get(&self, i: usize, j: usize) -> f64 {
        // Requires j ≤ i ≤ j + b.
        self.band[i * (self.b + 1) + (j + self.b - i)]
    }

    /// y = A x for every column of `x` into `y`.
    pub(crate) fn mul(&self, x: &Mat<f64>, y: &mut Mat<f64>) {
        for c in 0..x.ncols() {
            for i in 0..self.n {
                let mut s = 0.0;
                for j in i.saturating_sub(self.b)..=i {
                    s += self.get(i, j) * x[(j, c)];
                }
                for j in i + 1..(i + self.b + 1).min(self.n) {
                    s += self.get(j, i) * x[(j, c)];
                }
                y[(i, c)] = s;
            }
        }
    }

    /// In-place Cholesky A = LLᵀ (L stored in the band); error at a non-positive pivot.
    pub(crate) fn cholesky(mut self) -> Result<BandCholesky, BeamError> {
        let w = self.b + 1;
        for i in 0..self.n {
            for j in i.saturating_sub(self.b)..=i {
                let mut s = self.band[i * w + (j + self.b - i)];
                for k in i.saturating_sub(self.b).max(j.saturating_sub(self.b))..j {
                    s -= self.band[i * w + (k + self.b - i)] * self.band[j * w + (k + self.b - j)];
                }
                if i == j {
                    if s <= 0.0 || !s.is_finite() {
                        return Err(BeamError::StiffnessSingular { pivot: i });
                    }
                    self.band[i * w + self.b] = s.sqrt();
                } else {
                    self.band[i * w + (j + self.b - i)] = s / self.band[j * w + self.b];
                }
            }
        }
        Ok(BandCholesky { factor: self })
    }
}

/// Banded Cholesky factor L of A = LLᵀ.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BandCholesky {
    factor: SymmetricBand,
}

impl BandCholesky {
    /// Solve A x = r in place for every column of `r`.
    pub(crate) fn solve_in_place(&self, r: &mut Mat<f64>) {
        let l = &self.factor;
        for c in 0..r.ncols() {
            for i in 0..l.n {
                let mut s = r[(i, c)];
                for k in i.saturating_sub(l.b)..i {
                    s -= l.get(i, k) * r[(k, c)];
                }
                r[(i, c)] = s / l.get(i, i);
            }
            for i in (0..l.n).rev() {
                let mut s = r[(i, c)];
                for k in i + 1..(i + l.b + 1).min(l.n) {
                    s -= l.get(k, i) * r[(k, c)];
                }
                r[(i, c)] = s / l.get(i, i);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Solve a banded SPD system (the 1-D Laplacian plus identity, b = 1, and a b = 3 matrix) and
    /// check the residual A x − r against the dense product: 1e-12 relative (n = 50, well-conditioned).
    #[test]
    fn banded_cholesky_solves() {
        let n = 50;
        for b in [1usize, 3] {
            let a = Mat::from_fn(n, n, |i, j| {
                let d = i.abs_diff(j);
                if d == 0 {
                    4.0 + b as f64
                } else if d <= b {
                    -1.0 / d as f64
                } else {
                    0.0
                }
            });
            let mut band = SymmetricBand::zeros(n, b);
            for i in 0..n {
                for j in i.saturating_sub(b)..=i {
                    band.add(i, j, a[(i, j)]);
                }
            }
            assert_eq!(band.to_dense(), a);
            let r = Mat::from_fn(n, 2, |i, c| ((i + 3 * c) as f64).sin());
            let mut x = r.clone();
            band.clone().cholesky().unwrap().solve_in_place(&mut x);
            let mut ax = Mat::zeros(n, 2);
            band.mul(&x, &mut ax);
            let dense = &a * &x;
            for c in 0..2 {
                for i in 0..n {
                    assert!((ax[(i, c)] - r[(i, c)]).abs() < 1e-12);
                    assert!((dense[(i, c)] - r[(i, c)]).abs() < 1e-12);
                }
            }
        }
        let mut singular = SymmetricBand::zeros(3, 0);
        singular.add(0, 0, 1.0);
        singular.add(1, 1, 1.0);
        assert!(singular.cholesky().is_err());
    }
}

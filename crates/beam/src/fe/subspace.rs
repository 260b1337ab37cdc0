//! Banded subspace iteration with a square-root Rayleigh–Ritz step ([`EigenReduction::BandedSubspace`](super::EigenReduction::BandedSubspace)).

use faer::{Mat, Side};

use super::FeBeam;
use super::eigen::{SvdVectors, square_root_svd_modes};
use crate::banded::SymmetricBand;
use crate::error::BeamError;
use crate::modal::Derivative;

use super::shape::hermite;

impl FeBeam {
    /// G Y for the columns of `y` (element curvature rows and spring rows, see
    /// [`Self::stiffness_square_root`]), without forming G.
    fn apply_square_root(&self, y: &Mat<f64>) -> Mat<f64> {
        let gauss = [0.5 - 0.5 / 3f64.sqrt(), 0.5 + 0.5 / 3f64.sqrt()];
        let n_el = self.mesh.n_elements();
        let mut out = Mat::<f64>::zeros(2 * n_el + self.springs.len(), y.ncols());
        for e in 0..n_el {
            let h = self.mesh.nodes[e + 1] - self.mesh.nodes[e];
            let w = (0.5 * h * self.mesh.element_ei[e]).sqrt();
            for (p, &xi) in gauss.iter().enumerate() {
                let nv = hermite(xi, h, Derivative::Curvature);
                for (a, v) in nv.iter().enumerate() {
                    if let Some(i) = self.free_index[2 * e + a] {
                        for c in 0..y.ncols() {
                            out[(2 * e + p, c)] += w * v * y[(i, c)];
                        }
                    }
                }
            }
        }
        for (r, &(i, k)) in self.springs.iter().enumerate() {
            for c in 0..y.ncols() {
                out[(2 * n_el + r, c)] = k.sqrt() * y[(i, c)];
            }
        }
        out
    }

    /// Subspace iteration (Bathe & Wilson 1972; Bathe, *Finite Element Procedures*, §11.6) with a
    /// banded Cholesky of K + σM: Y = (K + σM)⁻¹ M X, then Rayleigh–Ritz on span(Y) with the
    /// projected stiffness (GY)ᵀ(GY) (no cancellation, K = GᵀG) through the SVD of
    /// (GY) L_r⁻ᵀ, M_r = Yᵀ M Y = L_r L_rᵀ. p = max(2q, q + 8) vectors; once the q Ritz
    /// frequencies change by less than 1e-10 of max(ω_j, ω_q) between iterations (after k
    /// iterations; the frequency error is then ~r²·1e-10 and falls like r^(2k)), runs to 2k
    /// iterations so that the vectors converge too (at most 300 in all).
    pub(super) fn subspace_modes(&self, n_modes: usize) -> Result<(Vec<f64>, Mat<f64>), BeamError> {
        let n = self.n_free_dofs();
        let p = (2 * n_modes).max(n_modes + 8).min(n);
        let factor = self
            .stiffness
            .plus_scaled(&self.mass, self.shift)
            .cholesky()?;
        let mass = &self.mass;
        // Deterministic start: smooth sine patterns over the DOF index plus a small
        // pseudo-random part (LCG) so that no wanted mode is missing from the start space.
        let mut seed: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut x = Mat::from_fn(n, p, |i, c| {
            let noise = next_uniform(&mut seed) - 0.5;
            ((c + 1) as f64 * std::f64::consts::PI * (i as f64 + 0.5) / n as f64).sin()
                + 0.1 * noise
        });
        let mut y = Mat::<f64>::zeros(n, p);
        let mut previous = vec![f64::INFINITY; n_modes];
        // Eigenvalue errors fall like r^(2k) but eigenvector errors only like r^k
        // (r = (ω_j² + σ)/(ω_(p+1)² + σ)): once the frequencies have settled after k iterations,
        // k more iterations bring the vectors to the same accuracy.
        let mut settled_at = None;
        for iteration in 1..=300 {
            mass.mul(&x, &mut y);
            factor.solve_in_place(&mut y);
            m_orthonormalise(&mut y, mass, &mut seed);
            let (omegas, ritz) = self.rayleigh_ritz(&y, mass)?;
            x = ritz;
            // Rounding makes Ritz values jitter by ~1e-15 relative (elastic) and ~1e-11 rad/s
            // absolute (rigid modes): compare against the largest wanted frequency.
            let reference = omegas[n_modes - 1].max(self.shift.sqrt());
            let settled = omegas[..n_modes]
                .iter()
                .zip(&previous)
                .all(|(w, w0)| (w - w0).abs() <= 1e-10 * w.max(reference));
            previous.copy_from_slice(&omegas[..n_modes]);
            if settled && settled_at.is_none() {
                settled_at = Some(iteration);
            }
            if settled_at.is_some_and(|k| iteration >= 2 * k) {
                let phi = Mat::from_fn(n, n_modes, |i, j| x[(i, j)]);
                return Ok((omegas[..n_modes].to_vec(), phi));
            }
        }
        Err(BeamError::EigenNoConvergence { size: n })
    }

    /// Rayleigh–Ritz on span(Y): ascending ω and M-orthonormal Ritz vectors (n × p).
    fn rayleigh_ritz(
        &self,
        y: &Mat<f64>,
        mass: &SymmetricBand,
    ) -> Result<(Vec<f64>, Mat<f64>), BeamError> {
        let (n, p) = (y.nrows(), y.ncols());
        let mut my = Mat::<f64>::zeros(n, p);
        mass.mul(y, &mut my);
        // Column scaling to unit M-norm keeps M_r well conditioned.
        let d: Vec<f64> = (0..p)
            .map(|c| 1.0 / (0..n).map(|i| y[(i, c)] * my[(i, c)]).sum::<f64>().sqrt())
            .collect();
        let mr = Mat::from_fn(p, p, |a, c| {
            d[a] * d[c] * (0..n).map(|i| y[(i, a)] * my[(i, c)]).sum::<f64>()
        });
        let mr = Mat::from_fn(p, p, |a, c| 0.5 * (mr[(a, c)] + mr[(c, a)]));
        let llt = mr
            .llt(Side::Lower)
            .map_err(|_| BeamError::EigenNoConvergence { size: n })?;
        let l = llt.L();
        let gy = self.apply_square_root(y);
        // Hᵀ = L_r⁻¹ (G Y D)ᵀ (p × rows); its left singular vectors are the eigenvectors of
        // L_r⁻¹ K_r L_r⁻ᵀ.
        let (omegas, dz) = square_root_svd_modes(l, &d, &gy, p, SvdVectors::Thin, n)?;
        Ok((omegas, y * &dz))
    }
}

/// Uniform pseudo-random number in [0, 1) from a 64-bit LCG (Knuth's MMIX constants).
fn next_uniform(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6_364_136_223_846_793_005)
        .wrapping_add(1_442_695_040_888_963_407);
    (*seed >> 11) as f64 / (1u64 << 53) as f64
}

/// M-orthonormalise the columns of `y` by classical Gram–Schmidt with one reorthogonalisation
/// (CGS2, Kahan's "twice is enough"; Giraud et al., *Numer. Math.* 101:87–100, 2005); a column that (numerically) lies in the span of the previous ones — inverse iteration
/// makes columns nearly parallel when one mode dominates, e.g. a heavy point mass — is replaced by
/// a pseudo-random vector and orthonormalised again.
fn m_orthonormalise(y: &mut Mat<f64>, mass: &SymmetricBand, seed: &mut u64) {
    let (n, p) = (y.nrows(), y.ncols());
    let mut col = Mat::<f64>::zeros(n, 1);
    let mut mcol = Mat::<f64>::zeros(n, 1);
    let mut coefs = vec![0.0; p];
    let m_norm = |v: &Mat<f64>, mv: &mut Mat<f64>| {
        mass.mul(v, mv);
        (0..n)
            .map(|i| v[(i, 0)] * mv[(i, 0)])
            .sum::<f64>()
            .max(0.0)
            .sqrt()
    };
    for c in 0..p {
        for i in 0..n {
            col[(i, 0)] = y[(i, c)];
        }
        for _attempt in 0..4 {
            let start = m_norm(&col, &mut mcol);
            for _pass in 0..2 {
                mass.mul(&col, &mut mcol);
                for a in 0..c {
                    coefs[a] = (0..n).map(|i| y[(i, a)] * mcol[(i, 0)]).sum();
                }
                for (a, coef) in coefs.iter().enumerate().take(c) {
                    for i in 0..n {
                        col[(i, 0)] -= coef * y[(i, a)];
                    }
                }
            }
            let norm = m_norm(&col, &mut mcol);
            if norm > 1e-8 * start && norm > 0.0 {
                for i in 0..n {
                    y[(i, c)] = col[(i, 0)] / norm;
                }
                break;
            }
            for i in 0..n {
                col[(i, 0)] = next_uniform(seed) - 0.5;
            }
        }
    }
}

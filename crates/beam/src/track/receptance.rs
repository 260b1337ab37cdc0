//! Harmonic response of the track: (K − ω²M + iωC) û = F̂ solved with faer's sparse LU
//! (complex, partial pivoting) at each frequency; the receptance is û(x_r)/F̂ at x_f.

use faer::Mat;
use faer::c64;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};

use crate::error::{BeamError, positive};

use super::model::Track;

/// Receptance (dynamic compliance) of a [`Track`].
#[derive(Debug, Clone)]
pub struct Receptance<'a> {
    track: &'a Track,
    /// Merged pattern: (row, col, m, c, k).
    pattern: Vec<(usize, usize, [f64; 3])>,
}

impl<'a> Receptance<'a> {
    /// Prepare the common sparsity pattern of M, C and K.
    pub fn new(track: &'a Track) -> Self {
        let mut all: Vec<(usize, usize, [f64; 3])> = Vec::new();
        for (w, m) in track.matrices().iter().enumerate() {
            for &(i, j, v) in m.entries() {
                let mut e = [0.0; 3];
                e[w] = v;
                all.push((i, j, e));
            }
        }
        all.sort_by_key(|&(i, j, _)| (j, i));
        let mut pattern: Vec<(usize, usize, [f64; 3])> = Vec::with_capacity(all.len());
        for (i, j, e) in all {
            match pattern.last_mut() {
                Some(last) if last.0 == i && last.1 == j => {
                    for (acc, v) in last.2.iter_mut().zip(e) {
                        *acc += v;
                    }
                }
                _ => pattern.push((i, j, e)),
            }
        }
        Self { track, pattern }
    }

    /// Complex rail displacement at `x_response` per unit harmonic force at `x_force` at
    /// frequency `frequency` \[Hz\] (the receptance α \[m/N\]).
    pub fn rail(&self, x_force: f64, x_response: f64, frequency: f64) -> Result<c64, BeamError> {
        positive("frequency", frequency)?;
        let w = 2.0 * std::f64::consts::PI * frequency;
        let n = self.track.n_dofs();
        let entries: Vec<Triplet<usize, usize, c64>> = self
            .pattern
            .iter()
            .map(|&(i, j, [m, c, k])| Triplet::new(i, j, c64::new(k - w * w * m, w * c)))
            .collect();
        let a = SparseColMat::<usize, c64>::try_new_from_triplets(n, n, &entries).map_err(|e| {
            BeamError::Factorisation {
                matrix: "track dynamic stiffness",
                detail: format!("{e:?}"),
            }
        })?;
        let lu = a.sp_lu().map_err(|e| BeamError::Factorisation {
            matrix: "track dynamic stiffness",
            detail: format!("{e:?}"),
        })?;
        let pf = self.track.rail_point(x_force)?;
        let pr = self.track.rail_point(x_response)?;
        let mut rhs = Mat::<c64>::zeros(n, 1);
        for a in 0..4 {
            rhs[(pf.dofs[a], 0)] += c64::new(pf.weights[a], 0.0);
        }
        lu.solve_in_place(rhs.as_mut());
        let mut out = c64::new(0.0, 0.0);
        for a in 0..4 {
            out += rhs[(pr.dofs[a], 0)] * pr.weights[a];
        }
        Ok(out)
    }
}

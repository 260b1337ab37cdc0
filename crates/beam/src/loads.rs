//! Modal loads and quasi-static modal response.
//!
//! With mass-normalised modes the generalised force of mode j is f_j = ∫₀^L p(x) w_j(x) dx, which
//! for point forces F_k at x_k is Σ_k F_k w_j(x_k) (the modal equation of references.md §D4.4
//! ρ c_j'' = ∫ p w_j dx − EI β_j⁴ c_j). Distributed loads are integrated by a composite
//! Gauss–Legendre or Simpson rule ([`QuadratureRule`]) whose weighted shape values are cached.

use crate::error::{BeamError, finite, inside_span};
use crate::modal::{Derivative, ModalBasis, check_len};
use crate::quadrature::{Quadrature, QuadratureRule};

/// Add Σ_k F_k w_j(x_k) to `out` (length n_modes) for point forces `(x_k, F_k)`, using `scratch`
/// (length n_modes) for the shape values. Allocation-free.
pub fn add_point_forces<B: ModalBasis + ?Sized>(
    basis: &B,
    forces: &[(f64, f64)],
    scratch: &mut [f64],
    out: &mut [f64],
) -> Result<(), BeamError> {
    let n = basis.n_modes();
    check_len("out", out.len(), n)?;
    check_len("scratch", scratch.len(), n)?;
    for &(x, f) in forces {
        inside_span("force position", x, basis.length())?;
        finite("force", f)?;
        basis.eval_all(x, Derivative::Shape, scratch)?;
        for (o, w) in out.iter_mut().zip(scratch.iter()) {
            *o += f * w;
        }
    }
    Ok(())
}

/// Quasi-static modal coordinates q_j = f_j / (m_j ω_j²) (modal mass m_j = 1 after
/// normalisation). Rigid-body modes (ω_j = 0) have no static response and get q_j = 0.
pub fn quasi_static_coordinates<B: ModalBasis + ?Sized>(
    basis: &B,
    modal_forces: &[f64],
    out: &mut [f64],
) -> Result<(), BeamError> {
    let n = basis.n_modes();
    check_len("modal_forces", modal_forces.len(), n)?;
    check_len("out", out.len(), n)?;
    for (j, ((o, f), w)) in out
        .iter_mut()
        .zip(modal_forces)
        .zip(basis.circular_frequencies())
        .enumerate()
    {
        *o = if *w > 0.0 {
            f / (basis.modal_mass(j)? * w * w)
        } else {
            0.0
        };
    }
    Ok(())
}

/// Superpose Σ_j q_j w_j^(d)(x), using `scratch` (length n_modes) for the shape values.
pub fn superpose<B: ModalBasis + ?Sized>(
    basis: &B,
    coordinates: &[f64],
    x: f64,
    d: Derivative,
    scratch: &mut [f64],
) -> Result<f64, BeamError> {
    check_len("coordinates", coordinates.len(), basis.n_modes())?;
    basis.eval_all(x, d, scratch)?;
    Ok(coordinates
        .iter()
        .zip(scratch.iter())
        .map(|(q, w)| q * w)
        .sum())
}

/// Projection of distributed loads p(x) onto the modes by a cached quadrature:
/// f_j = Σ_k ω_k p(x_k) w_j(x_k).
#[derive(Debug, Clone, PartialEq)]
pub struct DistributedLoadProjector {
    nodes: Vec<f64>,
    /// Row k holds ω_k w_j(x_k) for all modes j (node-major).
    weighted_shapes: Vec<f64>,
    n_modes: usize,
}

impl DistributedLoadProjector {
    /// Cache the weighted mode shapes at the nodes of `rule` on [0, L].
    pub fn new<B: ModalBasis + ?Sized>(basis: &B, rule: QuadratureRule) -> Result<Self, BeamError> {
        let q = Quadrature::new(rule, 0.0, basis.length())?;
        let n = basis.n_modes();
        let mut weighted_shapes = vec![0.0; q.nodes().len() * n];
        for (k, (&x, &w)) in q.nodes().iter().zip(q.weights()).enumerate() {
            let row = &mut weighted_shapes[k * n..(k + 1) * n];
            basis.eval_all(x, Derivative::Shape, row)?;
            row.iter_mut().for_each(|v| *v *= w);
        }
        Ok(Self {
            nodes: q.nodes().to_vec(),
            weighted_shapes,
            n_modes: n,
        })
    }

    /// Quadrature nodes (where the load intensity is sampled).
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// f_j = Σ_k ω_k p_k w_j(x_k) for load intensities `p_at_nodes` [N/m] given at [`Self::nodes`].
    pub fn project_values(&self, p_at_nodes: &[f64], out: &mut [f64]) -> Result<(), BeamError> {
        check_len("p_at_nodes", p_at_nodes.len(), self.nodes.len())?;
        check_len("out", out.len(), self.n_modes)?;
        out.fill(0.0);
        for (row, &p) in self
            .weighted_shapes
            .chunks_exact(self.n_modes)
            .zip(p_at_nodes)
        {
            for (o, w) in out.iter_mut().zip(row) {
                *o += p * w;
            }
        }
        Ok(())
    }

    /// f_j = ∫ p(x) w_j(x) dx by the cached rule, for a load intensity function p [N/m].
    pub fn project(&self, p: impl Fn(f64) -> f64, out: &mut [f64]) -> Result<(), BeamError> {
        check_len("out", out.len(), self.n_modes)?;
        out.fill(0.0);
        for (row, &x) in self
            .weighted_shapes
            .chunks_exact(self.n_modes)
            .zip(&self.nodes)
        {
            let px = finite("load intensity", p(x))?;
            for (o, w) in out.iter_mut().zip(row) {
                *o += px * w;
            }
        }
        Ok(())
    }
}

//! The mesh, the Hermite shape functions and the evaluation of FE modes and static deflections
//! between the nodes.

use crate::error::{BeamError, inside_span};
use crate::modal::{Derivative, ModalBasis, check_len, check_mode};

/// Nodes and element properties of a mesh, with Hermite interpolation of nodal DOF vectors.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Mesh {
    pub(super) nodes: Vec<f64>,
    pub(super) element_ei: Vec<f64>,
    pub(super) element_rho_a: Vec<f64>,
}

/// Hermite cubic shape functions (and derivative `d`) at local ξ ∈ [0, 1] of an element of length h,
/// for DOFs (w₁, θ₁, w₂, θ₂).
pub(crate) fn hermite(xi: f64, h: f64, d: Derivative) -> [f64; 4] {
    let (x2, x3) = (xi * xi, xi * xi * xi);
    match d {
        Derivative::Shape => [
            1.0 - 3.0 * x2 + 2.0 * x3,
            h * (xi - 2.0 * x2 + x3),
            3.0 * x2 - 2.0 * x3,
            h * (x3 - x2),
        ],
        Derivative::Slope => [
            (6.0 * x2 - 6.0 * xi) / h,
            1.0 - 4.0 * xi + 3.0 * x2,
            (6.0 * xi - 6.0 * x2) / h,
            3.0 * x2 - 2.0 * xi,
        ],
        Derivative::Curvature => [
            (12.0 * xi - 6.0) / (h * h),
            (6.0 * xi - 4.0) / h,
            (6.0 - 12.0 * xi) / (h * h),
            (6.0 * xi - 2.0) / h,
        ],
        Derivative::Third => [
            12.0 / (h * h * h),
            6.0 / (h * h),
            -12.0 / (h * h * h),
            6.0 / (h * h),
        ],
    }
}

impl Mesh {
    pub(super) fn length(&self) -> f64 {
        self.nodes[self.nodes.len() - 1]
    }

    pub(super) fn n_elements(&self) -> usize {
        self.nodes.len() - 1
    }

    /// Element containing x (the right-hand element at an interior node) and local ξ.
    pub(super) fn locate(&self, x: f64) -> (usize, f64, f64) {
        let e = self
            .nodes
            .partition_point(|&n| n <= x)
            .saturating_sub(1)
            .min(self.n_elements() - 1);
        let h = self.nodes[e + 1] - self.nodes[e];
        (e, ((x - self.nodes[e]) / h).clamp(0.0, 1.0), h)
    }
}

/// Mass-normalised finite-element modes; implements [`ModalBasis`].
#[derive(Debug, Clone, PartialEq)]
pub struct FeModes {
    pub(super) mesh: Mesh,
    /// DOF-major: coefficients[dof * n_modes + j].
    pub(super) coefficients: Vec<f64>,
    pub(super) omegas: Vec<f64>,
}

impl FeModes {
    /// Node positions of the underlying mesh.
    pub fn nodes(&self) -> &[f64] {
        &self.mesh.nodes
    }
}

impl ModalBasis for FeModes {
    fn n_modes(&self) -> usize {
        self.omegas.len()
    }

    fn length(&self) -> f64 {
        self.mesh.length()
    }

    fn circular_frequencies(&self) -> &[f64] {
        &self.omegas
    }

    fn eval_all(&self, x: f64, d: Derivative, out: &mut [f64]) -> Result<(), BeamError> {
        let n = self.omegas.len();
        check_len("out", out.len(), n)?;
        inside_span("x", x, self.mesh.length())?;
        let (e, xi, h) = self.mesh.locate(x);
        let nv = hermite(xi, h, d);
        let c = &self.coefficients[2 * e * n..(2 * e + 4) * n];
        for (j, o) in out.iter_mut().enumerate() {
            *o = nv[0] * c[j] + nv[1] * c[n + j] + nv[2] * c[2 * n + j] + nv[3] * c[3 * n + j];
        }
        Ok(())
    }

    fn mode_value(&self, j: usize, x: f64, d: Derivative) -> Result<f64, BeamError> {
        let n = self.omegas.len();
        check_mode(j, n)?;
        inside_span("x", x, self.mesh.length())?;
        let (e, xi, h) = self.mesh.locate(x);
        let nv = hermite(xi, h, d);
        Ok((0..4)
            .map(|a| nv[a] * self.coefficients[(2 * e + a) * n + j])
            .sum())
    }

    fn bending_stiffness(&self, x: f64) -> Result<f64, BeamError> {
        inside_span("x", x, self.mesh.length())?;
        Ok(self.mesh.element_ei[self.mesh.locate(x).0])
    }
}

/// A static FE solution; evaluate with the Hermite shape functions.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticDeflection {
    pub(super) mesh: Mesh,
    pub(super) dofs: Vec<f64>,
}

impl StaticDeflection {
    /// Derivative `d` of the deflection at x.
    pub fn eval(&self, x: f64, d: Derivative) -> Result<f64, BeamError> {
        inside_span("x", x, self.mesh.length())?;
        let (e, xi, h) = self.mesh.locate(x);
        let nv = hermite(xi, h, d);
        Ok((0..4).map(|a| nv[a] * self.dofs[2 * e + a]).sum())
    }
}

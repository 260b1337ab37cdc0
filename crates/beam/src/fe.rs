//! Finite-element Euler–Bernoulli beam: Hermite cubic elements (2 DOF per node: w, θ = w').
//!
//! Piecewise-constant sections EI(x), ρA(x); pinned or clamped supports anywhere along the span
//! (continuous multi-span bridges); elastic bearings (translational and rotational springs);
//! point masses with optional rotary inertia. Element matrices (Przemieniecki 1968; Cook et al.,
//! *Concepts and Applications of FEA*, §2.5 and §11.3), element length h, DOFs (w₁, θ₁, w₂, θ₂):
//!
//! K_e = EI/h³ [[12, 6h, −12, 6h], [6h, 4h², −6h, 2h²], [−12, −6h, 12, −6h], [6h, 2h², −6h, 4h²]]
//! M_e = ρA h/420 [[156, 22h, 54, −13h], [22h, 4h², 13h, −3h²], [54, 13h, 156, −22h], [−13h, −3h², −22h, 4h²]]
//!
//! (consistent mass). Modes solve K φ = ω² M φ by Cholesky reduction: M = LLᵀ,
//! (L⁻¹ K L⁻ᵀ) y = ω² y (faer's dense symmetric eigen-solver), φ = L⁻ᵀ y, so φᵀ M φ = I
//! (mass-normalised including point masses). Between nodes the shapes are interpolated with the
//! Hermite shape functions and their derivatives. Eigenvalue error is O(h⁴) for smooth modes.

use faer::linalg::solvers::Solve;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, Par, Side};

use crate::error::{BeamError, finite, inside_span, non_negative, positive};
use crate::modal::{Derivative, ModalBasis, check_len, check_mode};

/// A beam segment with constant section properties; segments follow each other from x = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Segment length [m].
    pub length: f64,
    /// Bending stiffness EI [N m²].
    pub bending_stiffness: f64,
    /// Mass per unit length ρA [kg/m].
    pub mass_per_length: f64,
}

/// Kind of a support at a point of the beam.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SupportKind {
    /// w = 0.
    Pinned,
    /// w = 0 and θ = 0.
    Clamped,
    /// Elastic bearing: translational spring k_w [N/m] and rotational spring k_θ [N m/rad].
    Spring {
        /// Translational stiffness [N/m].
        translational: f64,
        /// Rotational stiffness [N m/rad].
        rotational: f64,
    },
}

/// A support at position `x` (a node is placed there).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointSupport {
    /// Position [m].
    pub x: f64,
    /// Support kind.
    pub kind: SupportKind,
}

/// A lumped mass at position `x` (a node is placed there).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointMass {
    /// Position [m].
    pub x: f64,
    /// Mass [kg].
    pub mass: f64,
    /// Rotary inertia [kg m²].
    pub rotary_inertia: f64,
}

/// Nodes and element properties of a mesh, with Hermite interpolation of nodal DOF vectors.
#[derive(Debug, Clone, PartialEq)]
struct Mesh {
    nodes: Vec<f64>,
    element_ei: Vec<f64>,
    element_rho_a: Vec<f64>,
}

/// Hermite cubic shape functions (and derivative `d`) at local ξ ∈ [0, 1] of an element of length h,
/// for DOFs (w₁, θ₁, w₂, θ₂).
fn hermite(xi: f64, h: f64, d: Derivative) -> [f64; 4] {
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
    fn length(&self) -> f64 {
        self.nodes[self.nodes.len() - 1]
    }

    fn n_elements(&self) -> usize {
        self.nodes.len() - 1
    }

    /// Element containing x (the right-hand element at an interior node) and local ξ.
    fn locate(&self, x: f64) -> (usize, f64, f64) {
        let e = self
            .nodes
            .partition_point(|&n| n <= x)
            .saturating_sub(1)
            .min(self.n_elements() - 1);
        let h = self.nodes[e + 1] - self.nodes[e];
        (e, ((x - self.nodes[e]) / h).clamp(0.0, 1.0), h)
    }
}

/// The assembled finite-element beam.
#[derive(Debug, Clone, PartialEq)]
pub struct FeBeam {
    mesh: Mesh,
    /// Global DOF → free DOF index (None if constrained).
    free_index: Vec<Option<usize>>,
    stiffness: Mat<f64>,
    mass: Mat<f64>,
}

/// Sorted, de-duplicated breakpoints (ends, section boundaries, supports, masses).
fn breakpoints(length: f64, sections: &[Section], extra: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut b = vec![0.0, length];
    let mut x = 0.0;
    for s in sections {
        x += s.length;
        b.push(x.min(length));
    }
    b.extend(extra);
    b.sort_by(f64::total_cmp);
    let tol = 1e-12 * length;
    b.dedup_by(|a, prev| (*a - *prev).abs() <= tol);
    b
}

fn validate(
    sections: &[Section],
    supports: &[PointSupport],
    masses: &[PointMass],
    n_elements: usize,
) -> Result<f64, BeamError> {
    if sections.is_empty() {
        return Err(BeamError::InvalidCount {
            name: "sections",
            value: 0,
            reason: "at least one section",
        });
    }
    if n_elements == 0 {
        return Err(BeamError::InvalidCount {
            name: "n_elements",
            value: 0,
            reason: "at least one element",
        });
    }
    let mut length = 0.0;
    for s in sections {
        length += positive("section length", s.length)?;
        positive("bending_stiffness", s.bending_stiffness)?;
        positive("mass_per_length", s.mass_per_length)?;
    }
    for s in supports {
        inside_span("support position", s.x, length)?;
        if let SupportKind::Spring {
            translational,
            rotational,
        } = s.kind
        {
            non_negative("translational spring", translational)?;
            non_negative("rotational spring", rotational)?;
        }
    }
    for m in masses {
        inside_span("point mass position", m.x, length)?;
        non_negative("mass", m.mass)?;
        non_negative("rotary_inertia", m.rotary_inertia)?;
    }
    Ok(length)
}

impl FeBeam {
    /// Mesh with about `n_elements` elements of equal size (a node at every section boundary,
    /// support and point mass), apply supports and assemble K and M on the free DOFs.
    pub fn new(
        sections: &[Section],
        supports: &[PointSupport],
        point_masses: &[PointMass],
        n_elements: usize,
    ) -> Result<Self, BeamError> {
        let length = validate(sections, supports, point_masses, n_elements)?;
        let bps = breakpoints(
            length,
            sections,
            supports
                .iter()
                .map(|s| s.x)
                .chain(point_masses.iter().map(|m| m.x)),
        );
        let h_target = length / n_elements as f64;
        let mut nodes = vec![0.0];
        for w in bps.windows(2) {
            let k = ((w[1] - w[0]) / h_target).round().max(1.0) as usize;
            for i in 1..=k {
                nodes.push(if i == k {
                    w[1]
                } else {
                    w[0] + (w[1] - w[0]) * i as f64 / k as f64
                });
            }
        }
        let mut element_ei = Vec::with_capacity(nodes.len() - 1);
        let mut element_rho_a = Vec::with_capacity(nodes.len() - 1);
        for w in nodes.windows(2) {
            let s = section_at(sections, 0.5 * (w[0] + w[1]));
            element_ei.push(s.bending_stiffness);
            element_rho_a.push(s.mass_per_length);
        }
        let mesh = Mesh {
            nodes,
            element_ei,
            element_rho_a,
        };
        Self::assemble(mesh, supports, point_masses)
    }

    fn node_of(mesh: &Mesh, x: f64) -> usize {
        let (e, xi, _) = mesh.locate(x);
        if xi > 0.5 { e + 1 } else { e }
    }

    fn assemble(
        mesh: Mesh,
        supports: &[PointSupport],
        masses: &[PointMass],
    ) -> Result<Self, BeamError> {
        let n_dof = 2 * mesh.nodes.len();
        let mut constrained = vec![false; n_dof];
        for s in supports {
            let node = Self::node_of(&mesh, s.x);
            match s.kind {
                SupportKind::Pinned => constrained[2 * node] = true,
                SupportKind::Clamped => {
                    constrained[2 * node] = true;
                    constrained[2 * node + 1] = true;
                }
                SupportKind::Spring { .. } => {}
            }
        }
        let mut free_index = vec![None; n_dof];
        let mut n_free = 0;
        for (dof, c) in constrained.iter().enumerate() {
            if !c {
                free_index[dof] = Some(n_free);
                n_free += 1;
            }
        }
        let mut k = Mat::<f64>::zeros(n_free, n_free);
        let mut m = Mat::<f64>::zeros(n_free, n_free);
        for e in 0..mesh.n_elements() {
            let h = mesh.nodes[e + 1] - mesh.nodes[e];
            let (ke, me) = element_matrices(h, mesh.element_ei[e], mesh.element_rho_a[e]);
            let dofs = [2 * e, 2 * e + 1, 2 * e + 2, 2 * e + 3];
            for a in 0..4 {
                let Some(ia) = free_index[dofs[a]] else {
                    continue;
                };
                for b in 0..4 {
                    let Some(ib) = free_index[dofs[b]] else {
                        continue;
                    };
                    k[(ia, ib)] += ke[a][b];
                    m[(ia, ib)] += me[a][b];
                }
            }
        }
        for s in supports {
            if let SupportKind::Spring {
                translational,
                rotational,
            } = s.kind
            {
                let node = Self::node_of(&mesh, s.x);
                if let Some(i) = free_index[2 * node] {
                    k[(i, i)] += translational;
                }
                if let Some(i) = free_index[2 * node + 1] {
                    k[(i, i)] += rotational;
                }
            }
        }
        for pm in masses {
            let node = Self::node_of(&mesh, pm.x);
            if let Some(i) = free_index[2 * node] {
                m[(i, i)] += pm.mass;
            }
            if let Some(i) = free_index[2 * node + 1] {
                m[(i, i)] += pm.rotary_inertia;
            }
        }
        Ok(Self {
            mesh,
            free_index,
            stiffness: k,
            mass: m,
        })
    }

    /// Node positions.
    pub fn nodes(&self) -> &[f64] {
        &self.mesh.nodes
    }

    /// Number of unconstrained DOFs.
    pub fn n_free_dofs(&self) -> usize {
        self.stiffness.nrows()
    }

    /// The lowest `n_modes` modes of K φ = ω² M φ (Cholesky reduction, see module docs).
    pub fn modes(&self, n_modes: usize) -> Result<FeModes, BeamError> {
        let n = self.n_free_dofs();
        if n_modes == 0 || n_modes > n {
            return Err(BeamError::TooManyModes {
                requested: n_modes,
                available: n,
            });
        }
        let llt = self.mass.llt(Side::Lower).map_err(|e| match e {
            faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } => {
                BeamError::MassNotPositiveDefinite { pivot: index }
            }
        })?;
        let l = llt.L();
        // A = L⁻¹ K L⁻ᵀ: X = L⁻¹ K, then A = L⁻¹ Xᵀ (K symmetric).
        let mut x = self.stiffness.clone();
        solve_lower_triangular_in_place(l, x.as_mut(), Par::Seq);
        let mut a = x.transpose().to_owned();
        solve_lower_triangular_in_place(l, a.as_mut(), Par::Seq);
        for i in 0..n {
            for j in 0..i {
                let s = 0.5 * (a[(i, j)] + a[(j, i)]);
                a[(i, j)] = s;
                a[(j, i)] = s;
            }
        }
        // Scale A to unit largest diagonal entry before the eigen-solve (its convergence
        // thresholds are not scale-free in practice), and scale the eigenvalues back.
        let scale = (0..n)
            .map(|i| a[(i, i)].abs())
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        for j in 0..n {
            for i in 0..n {
                a[(i, j)] /= scale;
            }
        }
        let evd = a
            .self_adjoint_eigen(Side::Lower)
            .map_err(|_| BeamError::EigenNoConvergence { size: n })?;
        let eigenvalues: Vec<f64> = (0..n_modes)
            .map(|j| evd.S().column_vector()[j] * scale)
            .collect();
        let mut phi = evd.U().subcols(0, n_modes).to_owned();
        solve_upper_triangular_in_place(l.transpose(), phi.as_mut(), Par::Seq);
        let omegas: Vec<f64> = (0..n_modes)
            .map(|j| eigenvalues[j].max(0.0).sqrt())
            .collect();
        let n_dof = self.free_index.len();
        let mut coefficients = vec![0.0; n_dof * n_modes];
        for (dof, fi) in self.free_index.iter().enumerate() {
            if let Some(i) = fi {
                for j in 0..n_modes {
                    coefficients[dof * n_modes + j] = phi[(*i, j)];
                }
            }
        }
        normalise_signs(&mut coefficients, n_modes);
        Ok(FeModes {
            mesh: self.mesh.clone(),
            coefficients,
            omegas,
        })
    }

    /// Static deflection under point forces (x_k, F_k): K u = f with consistent nodal loads
    /// f = F N(x_k) (exact for Hermite elements), solved by Cholesky. For piecewise-constant EI
    /// the nodal values are exact (the Hermite cubics contain the exact homogeneous solutions).
    pub fn static_deflection(&self, forces: &[(f64, f64)]) -> Result<StaticDeflection, BeamError> {
        let n = self.n_free_dofs();
        let mut f = Mat::<f64>::zeros(n, 1);
        for &(x, force) in forces {
            inside_span("force position", x, self.mesh.length())?;
            finite("force", force)?;
            let (e, xi, h) = self.mesh.locate(x);
            let nvals = hermite(xi, h, Derivative::Shape);
            for (a, nv) in nvals.iter().enumerate() {
                if let Some(i) = self.free_index[2 * e + a] {
                    f[(i, 0)] += force * nv;
                }
            }
        }
        let llt = self.stiffness.llt(Side::Lower).map_err(|e| match e {
            faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } => {
                BeamError::StiffnessSingular { pivot: index }
            }
        })?;
        let u = llt.solve(f.as_ref());
        let mut dofs = vec![0.0; self.free_index.len()];
        for (dof, fi) in self.free_index.iter().enumerate() {
            if let Some(i) = fi {
                dofs[dof] = u[(*i, 0)];
            }
        }
        Ok(StaticDeflection {
            mesh: self.mesh.clone(),
            dofs,
        })
    }
}

/// The section covering x (the last one for x at or beyond the end).
fn section_at(sections: &[Section], x: f64) -> Section {
    let mut end = 0.0;
    for s in sections {
        end += s.length;
        if x < end {
            return *s;
        }
    }
    sections[sections.len() - 1]
}

/// Hermite element stiffness and consistent mass (module docs).
fn element_matrices(h: f64, ei: f64, rho_a: f64) -> ([[f64; 4]; 4], [[f64; 4]; 4]) {
    let k = ei / (h * h * h);
    let h2 = h * h;
    let ke = [
        [12.0 * k, 6.0 * h * k, -12.0 * k, 6.0 * h * k],
        [6.0 * h * k, 4.0 * h2 * k, -6.0 * h * k, 2.0 * h2 * k],
        [-12.0 * k, -6.0 * h * k, 12.0 * k, -6.0 * h * k],
        [6.0 * h * k, 2.0 * h2 * k, -6.0 * h * k, 4.0 * h2 * k],
    ];
    let m = rho_a * h / 420.0;
    let me = [
        [156.0 * m, 22.0 * h * m, 54.0 * m, -13.0 * h * m],
        [22.0 * h * m, 4.0 * h2 * m, 13.0 * h * m, -3.0 * h2 * m],
        [54.0 * m, 13.0 * h * m, 156.0 * m, -22.0 * h * m],
        [-13.0 * h * m, -3.0 * h2 * m, -22.0 * h * m, 4.0 * h2 * m],
    ];
    (ke, me)
}

/// Make each mode's first translational DOF with |w| above 1e-6 of its maximum positive, so that
/// signs are reproducible (analytic clamped shapes start positive too).
fn normalise_signs(coefficients: &mut [f64], n_modes: usize) {
    let n_dof = coefficients.len() / n_modes;
    for j in 0..n_modes {
        let max = (0..n_dof)
            .step_by(2)
            .map(|d| coefficients[d * n_modes + j].abs())
            .fold(0.0, f64::max);
        let first = (0..n_dof)
            .step_by(2)
            .map(|d| coefficients[d * n_modes + j])
            .find(|v| v.abs() > 1e-6 * max)
            .unwrap_or(1.0);
        if first < 0.0 {
            for d in 0..n_dof {
                coefficients[d * n_modes + j] = -coefficients[d * n_modes + j];
            }
        }
    }
}

/// Mass-normalised finite-element modes; implements [`ModalBasis`].
#[derive(Debug, Clone, PartialEq)]
pub struct FeModes {
    mesh: Mesh,
    /// DOF-major: coefficients[dof * n_modes + j].
    coefficients: Vec<f64>,
    omegas: Vec<f64>,
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
    mesh: Mesh,
    dofs: Vec<f64>,
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

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
//! (consistent mass). Modes solve K φ = ω² M φ by a Cholesky reduction to a standard dense
//! symmetric eigenproblem (faer): M = LLᵀ, (L⁻¹ K L⁻ᵀ) y = ω² y, φ = L⁻ᵀ y, also through the SVD
//! of the square root G L⁻ᵀ (K = GᵀG), which keeps the lowest modes accurate on fine meshes; the
//! default is a banded subspace iteration whose Rayleigh–Ritz step uses the same Cholesky /
//! square-root reduction on the subspace (see [`EigenReduction`]); φᵀ M φ = I (mass-normalised
//! including point masses). Between nodes the shapes are interpolated with the
//! Hermite shape functions and their derivatives. Eigenvalue error is O(h⁴) for smooth modes.

use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, Par, Side};

use crate::banded::SymmetricBand;
use crate::error::{
    BENDING_STIFFNESS_RANGE, BeamError, LENGTH_RANGE, MASS_PER_LENGTH_RANGE, MAX_ELEMENTS,
    check_size, finite, in_range, inside_span, non_negative, positive,
};
use crate::modal::{Derivative, ModalBasis, check_len, check_mode};

/// A beam segment with constant section properties; segments follow each other from x = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Segment length \[m\].
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
    /// Position \[m\].
    pub x: f64,
    /// Support kind.
    pub kind: SupportKind,
}

/// A lumped mass at position `x` (a node is placed there).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointMass {
    /// Position \[m\].
    pub x: f64,
    /// Mass \[kg\].
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
    /// Stiffness K on the free DOFs (banded, half-bandwidth 3).
    stiffness: SymmetricBand,
    /// Consistent mass M (plus point masses) on the free DOFs (banded).
    mass: SymmetricBand,
    /// Spectral shift σ of [`EigenReduction::ShiftedStiffness`].
    shift: f64,
    /// Free DOF index and stiffness of every elastic bearing spring.
    springs: Vec<(usize, f64)>,
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
    // The dense eigen-solution holds about six n × n matrices of f64, n = 2 (elements + 1).
    check_size(
        "n_elements",
        n_elements,
        MAX_ELEMENTS,
        "the dense eigen-solution",
        |e| 48.0 * (2.0 * (e as f64 + 1.0)).powi(2),
    )?;
    let mut length = 0.0;
    for s in sections {
        length += in_range(
            "section length",
            positive("section length", s.length)?,
            LENGTH_RANGE,
            "m",
        )?;
        in_range(
            "bending_stiffness",
            positive("bending_stiffness", s.bending_stiffness)?,
            BENDING_STIFFNESS_RANGE,
            "N m^2",
        )?;
        in_range(
            "mass_per_length",
            positive("mass_per_length", s.mass_per_length)?,
            MASS_PER_LENGTH_RANGE,
            "kg/m",
        )?;
    }
    in_range("length", length, LENGTH_RANGE, "m")?;
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
        let ei_min = sections
            .iter()
            .map(|s| s.bending_stiffness)
            .fold(f64::INFINITY, f64::min);
        let total_mass = sections
            .iter()
            .map(|s| s.mass_per_length * s.length)
            .sum::<f64>()
            + point_masses.iter().map(|m| m.mass).sum::<f64>();
        let shift = 1e-2 * ei_min / (total_mass * length.powi(3));
        Self::assemble(mesh, supports, point_masses, shift)
    }

    fn node_of(mesh: &Mesh, x: f64) -> usize {
        let (e, xi, _) = mesh.locate(x);
        if xi > 0.5 { e + 1 } else { e }
    }

    fn assemble(
        mesh: Mesh,
        supports: &[PointSupport],
        masses: &[PointMass],
        shift: f64,
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
        // Free DOFs keep the global order and an element couples 4 consecutive global DOFs,
        // so both matrices have half-bandwidth 3.
        let mut k = SymmetricBand::zeros(n_free, 3);
        let mut m = SymmetricBand::zeros(n_free, 3);
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
                    if ib <= ia {
                        k.add(ia, ib, ke[a][b]);
                        m.add(ia, ib, me[a][b]);
                    }
                }
            }
        }
        let mut springs = Vec::new();
        for s in supports {
            if let SupportKind::Spring {
                translational,
                rotational,
            } = s.kind
            {
                let node = Self::node_of(&mesh, s.x);
                for (dof, stiffness) in [(2 * node, translational), (2 * node + 1, rotational)] {
                    if let Some(i) = free_index[dof] {
                        k.add(i, i, stiffness);
                        if stiffness > 0.0 {
                            springs.push((i, stiffness));
                        }
                    }
                }
            }
        }
        for pm in masses {
            let node = Self::node_of(&mesh, pm.x);
            if let Some(i) = free_index[2 * node] {
                m.add(i, i, pm.mass);
            }
            if let Some(i) = free_index[2 * node + 1] {
                m.add(i, i, pm.rotary_inertia);
            }
        }
        Ok(Self {
            mesh,
            free_index,
            stiffness: k,
            mass: m,
            shift,
            springs,
        })
    }

    /// Node positions.
    pub fn nodes(&self) -> &[f64] {
        &self.mesh.nodes
    }

    /// Number of unconstrained DOFs.
    pub fn n_free_dofs(&self) -> usize {
        self.stiffness.n()
    }

    /// The lowest `n_modes` modes of K φ = ω² M φ with the default
    /// [`EigenReduction::BandedSubspace`].
    pub fn modes(&self, n_modes: usize) -> Result<FeModes, BeamError> {
        self.modes_with(n_modes, EigenReduction::default())
    }

    /// The lowest `n_modes` modes of K φ = ω² M φ by the chosen Cholesky reduction.
    pub fn modes_with(
        &self,
        n_modes: usize,
        reduction: EigenReduction,
    ) -> Result<FeModes, BeamError> {
        let n = self.n_free_dofs();
        if n_modes == 0 || n_modes > n {
            return Err(BeamError::TooManyModes {
                requested: n_modes,
                available: n,
            });
        }
        let (omegas, phi) = match reduction {
            EigenReduction::Mass => {
                let (values, vectors) = reduced_eigen(
                    &self.mass.to_dense(),
                    &self.stiffness.to_dense(),
                    0..n_modes,
                    true,
                )?;
                let omegas = values.iter().map(|l| l.max(0.0).sqrt()).collect::<Vec<_>>();
                // φ = L⁻ᵀ y already satisfies φᵀ M φ = 1.
                (omegas, vectors)
            }
            EigenReduction::StiffnessSquareRoot => self.square_root_modes(n_modes)?,
            EigenReduction::BandedSubspace => self.subspace_modes(n_modes)?,
            EigenReduction::ShiftedStiffness => {
                let sigma = self.shift;
                let shifted = self.stiffness.plus_scaled(&self.mass, sigma).to_dense();
                // Largest μ = 1/(ω² + σ) first.
                let (mu, mut vectors) = reduced_eigen(
                    &shifted,
                    &self.mass.to_dense(),
                    (n - n_modes..n).rev(),
                    false,
                )?;
                let omegas = mu
                    .iter()
                    .map(|m| (1.0 / m - sigma).max(0.0).sqrt())
                    .collect::<Vec<_>>();
                // φᵀ(K + σM)φ = 1 and φᵀMφ = μ: rescale to unit modal mass.
                for (j, m) in mu.iter().enumerate() {
                    let s = 1.0 / m.sqrt();
                    for i in 0..n {
                        vectors[(i, j)] *= s;
                    }
                }
                (omegas, vectors)
            }
        };
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

    /// G with GᵀG = K: per element the rows √(EI h/2) N''(ξ_g) at the two Gauss points
    /// ξ_g = ½ ∓ 1/(2√3) (exact: N''ᵢN''ⱼ is quadratic), plus a row √k per bearing spring.
    fn stiffness_square_root(&self) -> Mat<f64> {
        let n = self.n_free_dofs();
        let gauss = [0.5 - 0.5 / 3f64.sqrt(), 0.5 + 0.5 / 3f64.sqrt()];
        let rows = 2 * self.mesh.n_elements() + self.springs.len();
        let mut g = Mat::<f64>::zeros(rows, n);
        for e in 0..self.mesh.n_elements() {
            let h = self.mesh.nodes[e + 1] - self.mesh.nodes[e];
            let w = (0.5 * h * self.mesh.element_ei[e]).sqrt();
            for (p, &xi) in gauss.iter().enumerate() {
                let nv = hermite(xi, h, Derivative::Curvature);
                for (a, v) in nv.iter().enumerate() {
                    if let Some(i) = self.free_index[2 * e + a] {
                        g[(2 * e + p, i)] = w * v;
                    }
                }
            }
        }
        for (r, &(i, k)) in self.springs.iter().enumerate() {
            g[(2 * self.mesh.n_elements() + r, i)] = k.sqrt();
        }
        g
    }

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
    fn subspace_modes(&self, n_modes: usize) -> Result<(Vec<f64>, Mat<f64>), BeamError> {
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
        let mut ht = Mat::from_fn(p, gy.nrows(), |a, r| d[a] * gy[(r, a)]);
        solve_lower_triangular_in_place(l, ht.as_mut(), Par::Seq);
        let scale = ht.norm_max().max(f64::MIN_POSITIVE);
        let ht = Mat::from_fn(p, ht.ncols(), |a, r| ht[(a, r)] / scale);
        let svd = ht
            .thin_svd()
            .map_err(|_| BeamError::EigenNoConvergence { size: n })?;
        let sv = svd.S().column_vector();
        let u = svd.U();
        let mut omegas = Vec::with_capacity(p);
        let mut z = Mat::<f64>::zeros(p, p);
        for j in 0..p {
            let col = p - 1 - j;
            omegas.push(if col < sv.nrows() {
                sv[col] * scale
            } else {
                0.0
            });
            for a in 0..p {
                z[(a, j)] = u[(a, col)];
            }
        }
        solve_upper_triangular_in_place(l.transpose(), z.as_mut(), Par::Seq);
        let dz = Mat::from_fn(p, p, |a, j| d[a] * z[(a, j)]);
        Ok((omegas, y * &dz))
    }

    /// Modes from the SVD of H = G L⁻ᵀ (M = LLᵀ after Jacobi scaling): L⁻¹KL⁻ᵀ = HᵀH, so its
    /// eigenvalues are the squared singular values and its eigenvectors the right singular
    /// vectors. Working with ω instead of ω² halves the digits lost to the conditioning.
    fn square_root_modes(&self, n_modes: usize) -> Result<(Vec<f64>, Mat<f64>), BeamError> {
        let n = self.n_free_dofs();
        let d: Vec<f64> = (0..n).map(|i| 1.0 / self.mass.entry(i, i).sqrt()).collect();
        let m_scaled = Mat::from_fn(n, n, |i, j| d[i] * self.mass.entry(i, j) * d[j]);
        let llt = m_scaled.llt(Side::Lower).map_err(|e| match e {
            faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } => {
                BeamError::MassNotPositiveDefinite { pivot: index }
            }
        })?;
        let l = llt.L();
        let g = self.stiffness_square_root();
        // Hᵀ = L⁻¹ (G D)ᵀ, n × rows.
        let mut ht = Mat::from_fn(n, g.nrows(), |i, r| d[i] * g[(r, i)]);
        solve_lower_triangular_in_place(l, ht.as_mut(), Par::Seq);
        let scale = ht.norm_max().max(f64::MIN_POSITIVE);
        let ht = Mat::from_fn(n, ht.ncols(), |i, r| ht[(i, r)] / scale);
        let svd = ht
            .svd()
            .map_err(|_| BeamError::EigenNoConvergence { size: n })?;
        let sv = svd.S().column_vector();
        let u = svd.U();
        let mut omegas = Vec::with_capacity(n_modes);
        let mut phi = Mat::<f64>::zeros(n, n_modes);
        for j in 0..n_modes {
            let col = n - 1 - j;
            omegas.push(if col < sv.nrows() {
                sv[col] * scale
            } else {
                0.0
            });
            for i in 0..n {
                phi[(i, j)] = u[(i, col)];
            }
        }
        solve_upper_triangular_in_place(l.transpose(), phi.as_mut(), Par::Seq);
        for (i, di) in d.iter().enumerate() {
            for j in 0..n_modes {
                phi[(i, j)] *= di;
            }
        }
        Ok((omegas, phi))
    }

    /// Static deflection under point forces (x_k, F_k): K u = f with consistent nodal loads
    /// f = F N(x_k) (exact for Hermite elements), solved by banded Cholesky. For piecewise-constant EI
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
        let mut u = f;
        self.stiffness.clone().cholesky()?.solve_in_place(&mut u);
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

/// How the generalised eigenproblem K φ = ω² M φ is reduced to a standard symmetric one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EigenReduction {
    /// M = LLᵀ, eigen-decompose L⁻¹ K L⁻ᵀ (eigenvalues ω²), φ = L⁻ᵀ y. The dense symmetric
    /// solver's absolute error ε‖L⁻¹KL⁻ᵀ‖ ≈ ε ω²_max makes the lowest ω² lose relative accuracy
    /// ε ω²_max/ω₁² ∝ n_el⁴ on fine meshes (ω₁ off by ≈ 3e-5 at 1000 elements, measured).
    Mass,
    /// K + σM = LLᵀ with a small shift σ (1 % of EI_min/(m_total L³), far below ω₁², which
    /// also admits rigid-body modes), eigen-decompose L⁻¹ M L⁻ᵀ (eigenvalues μ = 1/(ω² + σ)); the
    /// lowest modes are now the largest μ. φ = L⁻ᵀ y / √μ. Better than [`Self::Mass`] by one to
    /// two orders on fine meshes, still limited by ε κ(K) (ω₁ off by 1e-5 at 1000 elements).
    ShiftedStiffness,
    /// M = LLᵀ and K = GᵀG (G from the element curvature operators at the Gauss points and the
    /// bearing springs); the singular values of G L⁻ᵀ are ω. Same operator as [`Self::Mass`] but
    /// only √κ of the conditioning enters (ω₁ accurate to ~1e-10 at 1000 elements), at the
    /// price of a dense SVD (about 2.5× the time of the eigen-solve).
    StiffnessSquareRoot,
    /// Subspace iteration with a banded Cholesky of K + σM and a square-root Rayleigh–Ritz step
    /// (no dense n × n factorisation). Most accurate (ω₁ error 3e-13 at 1000 elements, the
    /// Rayleigh quotient error is ε²κ) and fastest for few modes (1000 elements, release build:
    /// 0.14 s for 20 modes).
    #[default]
    BandedSubspace,
}

/// Eigenpairs of L⁻¹ B L⁻ᵀ with A = LLᵀ, for the eigenvalue indices `wanted` (ascending order of
/// the solver), back-transformed φ = L⁻ᵀ y. `a_is_mass` only selects the error variant.
fn reduced_eigen(
    a: &Mat<f64>,
    b: &Mat<f64>,
    wanted: impl Iterator<Item = usize> + Clone,
    a_is_mass: bool,
) -> Result<(Vec<f64>, Mat<f64>), BeamError> {
    let n = a.nrows();
    // Symmetric diagonal (Jacobi) scaling S = diag(1/√A_ii): balances the translational and
    // rotational DOFs (entries ∝ 1/h³ vs 1/h), so the normwise backward errors of the Cholesky
    // factorisation and the eigen-solver do not swamp the small rotational entries.
    let d: Vec<f64> = (0..n)
        .map(|i| 1.0 / a[(i, i)].abs().max(f64::MIN_POSITIVE).sqrt())
        .collect();
    let a = Mat::from_fn(n, n, |i, j| d[i] * a[(i, j)] * d[j]);
    let b = Mat::from_fn(n, n, |i, j| d[i] * b[(i, j)] * d[j]);
    let llt = a.llt(Side::Lower).map_err(|e| match e {
        faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } => {
            if a_is_mass {
                BeamError::MassNotPositiveDefinite { pivot: index }
            } else {
                BeamError::StiffnessSingular { pivot: index }
            }
        }
    })?;
    let l = llt.L();
    // C = L⁻¹ B L⁻ᵀ: X = L⁻¹ B, then C = L⁻¹ Xᵀ (B symmetric).
    let mut x = b.clone();
    solve_lower_triangular_in_place(l, x.as_mut(), Par::Seq);
    let mut c = x.transpose().to_owned();
    solve_lower_triangular_in_place(l, c.as_mut(), Par::Seq);
    // Symmetrise and scale to unit largest diagonal entry: faer's symmetric eigen-solver is not
    // scale-invariant in practice (eigenvectors of a 3.6e6-scaled matrix lost 4 digits, measured).
    let scale = (0..n)
        .map(|i| c[(i, i)].abs())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    for i in 0..n {
        for j in 0..=i {
            let s = 0.5 * (c[(i, j)] + c[(j, i)]) / scale;
            c[(i, j)] = s;
            c[(j, i)] = s;
        }
    }
    let evd = c
        .self_adjoint_eigen(Side::Lower)
        .map_err(|_| BeamError::EigenNoConvergence { size: n })?;
    let values: Vec<f64> = wanted
        .clone()
        .map(|j| evd.S().column_vector()[j] * scale)
        .collect();
    let cols: Vec<usize> = wanted.collect();
    let u = evd.U();
    let mut phi = Mat::from_fn(n, cols.len(), |i, k| u[(i, cols[k])]);
    solve_upper_triangular_in_place(l.transpose(), phi.as_mut(), Par::Seq);
    for (i, di) in d.iter().enumerate() {
        for k in 0..phi.ncols() {
            phi[(i, k)] *= di;
        }
    }
    Ok((values, phi))
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

//! Sections, meshing, validation, assembly of the Hermite element matrices and the static solve.

use faer::Mat;

use super::FeBeam;
use super::shape::{Mesh, StaticDeflection, hermite};
use super::supports::{PointMass, PointSupport, SupportKind};
use crate::banded::SymmetricBand;
use crate::error::{
    BENDING_STIFFNESS_RANGE, BeamError, LENGTH_RANGE, MASS_PER_LENGTH_RANGE, MAX_ELEMENTS,
    check_size, finite, in_range, inside_span, non_negative, positive,
};
use crate::modal::Derivative;

/// A beam segment with constant section properties; segments follow each other from x = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Segment length \[m\].
    pub length: f64,
    /// Bending stiffness EI \[N m²\].
    pub bending_stiffness: f64,
    /// Mass per unit length ρA \[kg/m\].
    pub mass_per_length: f64,
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

//! Wheel–rail contact laws behind one interface ([`ContactLaw`]).
//!
//! A law returns, for a prescribed approach δ [m] (positive when wheel and rail overlap), the
//! normal force F(δ) [N], its tangent k_c = dF/dδ [N/m] and the force carried by each column of
//! its grid (positions ξ_i relative to the wheel, along the track), from which the caller forms
//! the modal loads I_j = Σ_i F_i w_j(x_wheel + ξ_i) (the seed's ∫ p w_j dx, Σ_e p_e ΔA w_j(x_e)).
//!
//! * [`HertzLaw`]: the closed-form elliptic Hertz spring F = C_H δ^{3/2} for δ > 0, else 0
//!   (references.md §C4.1; references.md §D2.3), with the gap curvatures A = 1/(2R_w) along the track
//!   and B = 1/(2R_r) across it; k_c = 1.5 F/δ. A point contact (one column at ξ = 0).
//! * [`BemLaw`]: the half-space solver ([`halfspace::NormalSolver`], NormCG at prescribed
//!   approach, warm-started from the previous call) on an nx × ny grid under the wheel, with the
//!   undeformed gap h(ξ, y) = R_w − √(R_w² − ξ²) (exact wheel circle) + R_r − √(R_r² − y²)
//!   (transverse rail-head circle) + c(ξ), where the column term c(ξ) = [w(x+ξ) − w(x)] −
//!   [r(x+ξ) − r(x)] carries the beam deflection and the irregularity at each grid column
//!   relative to the wheel point. k_c = dF/dδ from the solver's sensitivity solve.
//! * [`RigidLaw`]: no contact spring; the simulation imposes δ = 0 while F > 0 with a Lagrange
//!   multiplier (the wheel follows the rail).

use halfspace::{Grid, Hertz, Material, NormalLoad, NormalSolver, SolverOptions};

use super::VehicleBridgeError;

/// One evaluation of a contact law.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactOutput {
    /// Normal force F \[N\] (≥ 0).
    pub force: f64,
    /// Tangent dF/dδ [N/m] (0 out of contact).
    pub stiffness: f64,
    /// Length of the contact patch along the track \[m\].
    pub patch_length: f64,
    /// Width of the contact patch across the track \[m\].
    pub patch_width: f64,
    /// Peak pressure \[Pa\].
    pub max_pressure: f64,
    /// Iterations of the contact solver (0 for closed forms).
    pub iterations: usize,
}

/// A wheel–rail contact law (module documentation).
pub trait ContactLaw: std::fmt::Debug {
    /// Name used in reports (`rigid`, `hertz`, `bem`).
    fn name(&self) -> &'static str;

    /// `true` for the rigid constraint (no force law).
    fn is_rigid(&self) -> bool {
        false
    }

    /// Column positions ξ_i relative to the wheel \[m\] (one column at 0 for a point contact).
    fn columns(&self) -> &[f64];

    /// The approach δ that carries the force `force` \[N\] on a smooth, undeformed rail.
    fn static_approach(&mut self, force: f64) -> Result<f64, VehicleBridgeError>;

    /// The pressure \[Pa\] of the last evaluation along the track centreline, as (ξ, p) pairs
    /// written into `out` (empty for the rigid constraint).
    fn centreline_pressure(&self, out: &mut Vec<(f64, f64)>) {
        out.clear();
    }

    /// The grid and pressure \[Pa\] of the last evaluation (row-major, x fastest) for laws that
    /// solve the pressure field (`bem`); `None` for the closed forms.
    fn pressure_field(&self) -> Option<(&Grid, &[f64])> {
        None
    }

    /// Evaluates the law at approach `delta` with the column gap terms `column_gap` (see the
    /// module documentation; length = number of columns), writing the force of each column
    /// into `column_force`. With `tangent = false` a law may return the tangent of its previous
    /// evaluation instead of computing a new one (the quasi-Newton iterations of one step reuse
    /// the tangent of the step's first evaluation).
    fn evaluate(
        &mut self,
        delta: f64,
        column_gap: &[f64],
        column_force: &mut [f64],
        tangent: bool,
    ) -> Result<ContactOutput, VehicleBridgeError>;
}

/// Elastic constants and geometry shared by the laws.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactGeometry {
    /// Wheel rolling radius R_w \[m\].
    pub wheel_radius: f64,
    /// Transverse radius of the rail head R_r \[m\].
    pub rail_profile_radius: f64,
    /// Young's modulus of wheel and rail \[Pa\].
    pub youngs_modulus: f64,
    /// Poisson's ratio of wheel and rail.
    pub poisson_ratio: f64,
}

impl ContactGeometry {
    /// Validates the geometry and returns the combined material (references.md §C3.1).
    pub fn material(&self) -> Result<Material, VehicleBridgeError> {
        for (name, v) in [
            ("contact.wheel_radius", self.wheel_radius),
            ("contact.rail_profile_radius", self.rail_profile_radius),
            ("contact.E", self.youngs_modulus),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(VehicleBridgeError::InvalidParameter {
                    name: name.to_string(),
                    value: v,
                    reason: "must be positive and finite".to_string(),
                });
            }
        }
        let nu = self.poisson_ratio;
        if !nu.is_finite() || nu >= 0.5 || nu <= -1.0 {
            return Err(VehicleBridgeError::InvalidParameter {
                name: "contact.nu".to_string(),
                value: nu,
                reason: "must be in (-1, 0.5)".to_string(),
            });
        }
        Material::identical(self.youngs_modulus, nu).map_err(VehicleBridgeError::from)
    }

    /// Gap curvatures (A along the track, B across) [1/m].
    pub fn curvatures(&self) -> (f64, f64) {
        (0.5 / self.wheel_radius, 0.5 / self.rail_profile_radius)
    }
}

/// The closed-form Hertz spring (module documentation).
#[derive(Debug, Clone)]
pub struct HertzLaw {
    /// C_H in F = C_H δ^{3/2} [N/m^{3/2}].
    pub coefficient: f64,
    /// Semi-axes and peak pressure at F = 1 N (they scale as F^{1/3}).
    unit: Hertz,
    columns: [f64; 1],
    last_force: f64,
}

impl HertzLaw {
    /// The Hertz law of the geometry.
    pub fn new(geometry: &ContactGeometry) -> Result<Self, VehicleBridgeError> {
        let material = geometry.material()?;
        let (a, b) = geometry.curvatures();
        let unit = Hertz::elliptic(a, b, material.e_star, 1.0)?;
        Ok(Self {
            coefficient: unit.approach.powf(-1.5),
            unit,
            columns: [0.0],
            last_force: 0.0,
        })
    }

    /// The Hertz solution at force F (semi-axes a along, b across the track; peak pressure).
    pub fn at_force(&self, force: f64) -> (f64, f64, f64) {
        let s = force.max(0.0).cbrt();
        (self.unit.a * s, self.unit.b * s, self.unit.max_pressure * s)
    }
}

impl ContactLaw for HertzLaw {
    fn name(&self) -> &'static str {
        "hertz"
    }

    fn columns(&self) -> &[f64] {
        &self.columns
    }

    fn static_approach(&mut self, force: f64) -> Result<f64, VehicleBridgeError> {
        Ok((force.max(0.0) / self.coefficient).powf(2.0 / 3.0))
    }

    /// Hertz: p(ξ, 0) = p₀ √(1 − ξ²/a²), sampled at 41 points over [−1.25a, 1.25a].
    fn centreline_pressure(&self, out: &mut Vec<(f64, f64)>) {
        out.clear();
        let (a, _, p0) = self.at_force(self.last_force);
        if a > 0.0 {
            for i in 0..=40 {
                let xi = 1.25 * a * (i as f64 / 20.0 - 1.0);
                out.push((xi, p0 * (1.0 - (xi / a).powi(2)).max(0.0).sqrt()));
            }
        }
    }

    fn evaluate(
        &mut self,
        delta: f64,
        _column_gap: &[f64],
        column_force: &mut [f64],
        _tangent: bool,
    ) -> Result<ContactOutput, VehicleBridgeError> {
        if delta <= 0.0 {
            column_force[0] = 0.0;
            self.last_force = 0.0;
            return Ok(ContactOutput::default());
        }
        let root = delta.sqrt();
        let force = self.coefficient * delta * root;
        column_force[0] = force;
        self.last_force = force;
        let (a, b, p0) = self.at_force(force);
        Ok(ContactOutput {
            force,
            stiffness: 1.5 * self.coefficient * root,
            patch_length: 2.0 * a,
            patch_width: 2.0 * b,
            max_pressure: p0,
            iterations: 0,
        })
    }
}

/// The rigid constraint (module documentation).
#[derive(Debug, Clone)]
pub struct RigidLaw {
    columns: [f64; 1],
}

impl Default for RigidLaw {
    fn default() -> Self {
        Self { columns: [0.0] }
    }
}

impl ContactLaw for RigidLaw {
    fn name(&self) -> &'static str {
        "rigid"
    }

    fn is_rigid(&self) -> bool {
        true
    }

    fn columns(&self) -> &[f64] {
        &self.columns
    }

    fn static_approach(&mut self, _force: f64) -> Result<f64, VehicleBridgeError> {
        Ok(0.0)
    }

    /// The rigid contact has no force law: the force is the multiplier held by the
    /// simulation, which never calls this method. It reports the force passed as `delta`.
    fn evaluate(
        &mut self,
        delta: f64,
        _column_gap: &[f64],
        column_force: &mut [f64],
        _tangent: bool,
    ) -> Result<ContactOutput, VehicleBridgeError> {
        column_force[0] = delta.max(0.0);
        Ok(ContactOutput {
            force: delta.max(0.0),
            ..ContactOutput::default()
        })
    }
}

/// The boundary-element contact under the wheel (module documentation).
#[derive(Debug)]
pub struct BemLaw {
    solver: NormalSolver,
    options: SolverOptions,
    grid: Grid,
    /// Gap of the wheel circle and rail head, per element (without the column terms).
    base_gap: Vec<f64>,
    gap: Vec<f64>,
    pressure: Vec<f64>,
    columns: Vec<f64>,
    last_stiffness: f64,
}

impl BemLaw {
    /// A BEM law on an `n × n` grid sized for forces up to `max_force` \[N\]: half-widths of
    /// 1.25 × the Hertz semi-axes at `max_force`; NormCG tolerance `tol`.
    pub fn new(
        geometry: &ContactGeometry,
        n: usize,
        max_force: f64,
        tol: f64,
    ) -> Result<Self, VehicleBridgeError> {
        if !(4..=512).contains(&n) {
            return Err(VehicleBridgeError::InvalidParameter {
                name: "contact.grid".to_string(),
                value: n as f64,
                reason: "must be in 4..=512 elements per direction".to_string(),
            });
        }
        if !(tol.is_finite() && tol > 0.0) {
            return Err(VehicleBridgeError::InvalidParameter {
                name: "contact.bem_tol".to_string(),
                value: tol,
                reason: "must be positive".to_string(),
            });
        }
        let material = geometry.material()?;
        let (ca, cb) = geometry.curvatures();
        let hertz = Hertz::elliptic(ca, cb, material.e_star, max_force.max(1.0))?;
        let (hx, hy) = (1.25 * hertz.a, 1.25 * hertz.b);
        let grid = Grid::centred(n, n, 2.0 * hx / n as f64, 2.0 * hy / n as f64, 0.0, 0.0)?;
        let (rw, rr) = (geometry.wheel_radius, geometry.rail_profile_radius);
        let base_gap =
            grid.sample(|x, y| (rw - (rw * rw - x * x).sqrt()) + (rr - (rr * rr - y * y).sqrt()));
        let columns = (0..n).map(|ix| grid.x(ix)).collect();
        let solver = NormalSolver::new(grid, material)?;
        Ok(Self {
            solver,
            options: SolverOptions {
                tol,
                max_iter: 500,
                // dF/dδ is only the quasi-Newton tangent: 1e-4 relative is far more accurate
                // than the iteration needs (it converges in ~1 iteration per step) and halves
                // the cost of the warm-started sensitivity solve.
                sensitivity_tol: 1e-4,
                ..SolverOptions::default()
            },
            grid,
            gap: base_gap.clone(),
            pressure: vec![0.0; base_gap.len()],
            last_stiffness: 0.0,
            base_gap,
            columns,
        })
    }

    /// The grid (local coordinates: ξ along the track, y across; centred on the wheel).
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The pressure of the last solve \[Pa\], row-major (x fastest).
    pub fn last_pressure(&self) -> &[f64] {
        &self.pressure
    }

    fn solve(&mut self, load: NormalLoad) -> Result<halfspace::NormalSolution, VehicleBridgeError> {
        self.solver
            .solve(&self.gap, load, &self.options)
            .map_err(VehicleBridgeError::from)
    }
}

impl ContactLaw for BemLaw {
    fn name(&self) -> &'static str {
        "bem"
    }

    fn pressure_field(&self) -> Option<(&Grid, &[f64])> {
        Some((&self.grid, &self.pressure))
    }

    fn columns(&self) -> &[f64] {
        &self.columns
    }

    fn centreline_pressure(&self, out: &mut Vec<(f64, f64)>) {
        out.clear();
        let (nx, ny) = (self.grid.nx, self.grid.ny);
        let iy = ny / 2;
        for ix in 0..nx {
            out.push((self.grid.x(ix), self.pressure[iy * nx + ix]));
        }
    }

    fn static_approach(&mut self, force: f64) -> Result<f64, VehicleBridgeError> {
        self.gap.copy_from_slice(&self.base_gap);
        Ok(self.solve(NormalLoad::Force(force))?.approach)
    }

    fn evaluate(
        &mut self,
        delta: f64,
        column_gap: &[f64],
        column_force: &mut [f64],
        tangent: bool,
    ) -> Result<ContactOutput, VehicleBridgeError> {
        let nx = self.grid.nx;
        let mut min_gap = f64::INFINITY;
        for (k, (g, b)) in self.gap.iter_mut().zip(&self.base_gap).enumerate() {
            *g = b + column_gap[k % nx];
            min_gap = min_gap.min(*g);
        }
        column_force.fill(0.0);
        if delta <= min_gap {
            self.pressure.fill(0.0);
            return Ok(ContactOutput::default());
        }
        // The sensitivity solve is skipped when the caller reuses the previous tangent (and
        // there is one).
        self.options.sensitivity = tangent || self.last_stiffness <= 0.0;
        let solution = self.solve(NormalLoad::Approach(delta))?;
        let stiffness = match solution.dfn_dapproach {
            Some(k) if self.options.sensitivity => {
                self.last_stiffness = k;
                k
            }
            _ => self.last_stiffness,
        };
        let area = self.grid.element_area();
        for (k, p) in solution.pressure.iter().enumerate() {
            column_force[k % nx] += p * area;
        }
        let (a, b) = if solution.elements_in_contact > 0 {
            solution.patch_half_widths()
        } else {
            (0.0, 0.0)
        };
        self.pressure.copy_from_slice(&solution.pressure);
        Ok(ContactOutput {
            force: solution.normal_force,
            stiffness,
            patch_length: 2.0 * a,
            patch_width: 2.0 * b,
            max_pressure: solution.max_pressure,
            iterations: solution.iterations,
        })
    }
}

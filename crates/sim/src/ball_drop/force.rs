//! Contact force laws of the ball drop: Hertz's closed form and the boundary-element
//! half-space solver at prescribed approach, with optional linear surface damping.

use halfspace::{GapShape, Hertz, Material, NormalLoad, NormalSolver, SolverOptions, auto_grid};

use super::{BallDropError, BallShape};

/// The Hertz constant `K` of `F = K δ^{3/2}` \[N/m^{3/2}\] for the ball's gap on a flat
/// surface (references.md §D1.4, references.md §C4.1).
///
/// * sphere: `K = (4/3) E* √R` (Johnson 1985 §11.4);
/// * ellipsoid with principal radii of curvature `R_x`, `R_y` at its lowest point: the gap is
///   `h = A x² + B y²` with `A = 1/(2R_x)`, `B = 1/(2R_y)`; Hertz's elliptic solution gives
///   the approach `δ₁` under a unit force, and since `F ∝ δ^{3/2}`, `K = δ₁^{−3/2}`.
pub fn hertz_constant(shape: &BallShape, material: &Material) -> Result<f64, BallDropError> {
    match *shape {
        BallShape::Sphere { radius } => Ok(4.0 / 3.0 * material.e_star * radius.sqrt()),
        BallShape::Ellipsoid { radius_x, radius_y } => {
            let unit = Hertz::elliptic(0.5 / radius_x, 0.5 / radius_y, material.e_star, 1.0)
                .map_err(|source| BallDropError::Material {
                    key: "[ball] radius_x/radius_y",
                    source,
                })?;
            Ok(unit.approach.powf(-1.5))
        }
    }
}

/// Result of one elastic force evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticForce {
    /// Elastic contact force `F_el(δ)` \[N\].
    pub force: f64,
    /// Contact stiffness `dF_el/dδ` \[N/m\] (only when requested from the BEM model).
    pub stiffness: Option<f64>,
    /// Stored elastic energy `W(δ) = ∫₀^δ F_el dδ'` \[J\].
    pub energy: f64,
}

/// The elastic force law F_el(δ).
#[derive(Debug)]
enum Law {
    /// `F = K δ^{3/2}`, `W = (2/5) K δ^{5/2}`.
    Hertz { k: f64 },
    /// The half-space solver (boxed: it owns FFT plans and work vectors).
    Bem(Box<Bem>),
}

/// Boundary-element force law: `NormalSolver::solve(gap, Approach(δ))`, warm-started.
#[derive(Debug)]
struct Bem {
    solver: NormalSolver,
    gap: Vec<f64>,
    area: f64,
    force_only: SolverOptions,
    with_stiffness: SolverOptions,
    last: Option<(f64, ElasticForce)>,
    solves: usize,
}

/// A contact force model: an elastic law plus linear surface damping `c δ'`.
///
/// Total force (compression positive, acting upward on the ball):
/// `F = max(0, F_el(δ) + c δ')` while `δ > 0`, and `F = 0` otherwise. The clamp keeps the
/// damped force from pulling the ball (a surface cannot hold it).
#[derive(Debug)]
pub struct ContactForce {
    law: Law,
    damping: f64,
}

impl ContactForce {
    /// Hertz's law `F_el = K δ^{3/2}` with the constant of [`hertz_constant`].
    pub fn hertz(k: f64, damping: f64) -> Self {
        Self {
            law: Law::Hertz { k },
            damping,
        }
    }

    /// The half-space solver on an automatic `elements × elements` grid sized for the Hertz
    /// patch at `max_approach` (with the margin [`halfspace::AUTO_GRID_MARGIN`]); the gap is
    /// the exact sphere `h = R − √(R² − r²)` or, for an ellipsoid, its quadratic
    /// `A x² + B y²`. NormCG tolerance `tol`.
    pub fn bem(
        shape: &BallShape,
        material: Material,
        max_approach: f64,
        elements: usize,
        tol: f64,
        damping: f64,
    ) -> Result<Self, BallDropError> {
        let gap_shape = match *shape {
            BallShape::Sphere { radius } => GapShape::Sphere { radius },
            BallShape::Ellipsoid { radius_x, radius_y } => GapShape::Quadratic {
                a: 0.5 / radius_x,
                b: 0.5 / radius_y,
            },
        };
        let bad = |source| BallDropError::Material {
            key: "[contact] elements",
            source,
        };
        let grid = auto_grid(
            &gap_shape,
            &material,
            NormalLoad::Approach(max_approach),
            elements,
        )
        .map_err(bad)?;
        let gap = gap_shape.sample(&grid).map_err(bad)?;
        let solver = NormalSolver::new(grid, material).map_err(bad)?;
        let force_only = SolverOptions {
            tol,
            max_iter: 500,
            sensitivity: false,
            ..SolverOptions::default()
        };
        let with_stiffness = SolverOptions {
            sensitivity: true,
            sensitivity_tol: tol.min(1e-10),
            ..force_only
        };
        Ok(Self {
            law: Law::Bem(Box::new(Bem {
                solver,
                gap,
                area: grid.element_area(),
                force_only,
                with_stiffness,
                last: None,
                solves: 0,
            })),
            damping,
        })
    }

    /// Linear damping coefficient `c` \[N·s/m\].
    pub fn damping(&self) -> f64 {
        self.damping
    }

    /// Number of half-space solves so far (0 for Hertz).
    pub fn solves(&self) -> usize {
        match &self.law {
            Law::Hertz { .. } => 0,
            Law::Bem(b) => b.solves,
        }
    }

    /// The grid (nx, ny, dx, dy) of the BEM model, `None` for Hertz.
    pub fn grid(&self) -> Option<(usize, usize, f64, f64)> {
        match &self.law {
            Law::Hertz { .. } => None,
            Law::Bem(b) => {
                let g = b.solver.grid();
                Some((g.nx, g.ny, g.dx, g.dy))
            }
        }
    }

    /// Elastic force, energy and (if `stiffness`) the tangent `dF_el/dδ` at approach δ \[m\].
    ///
    /// BEM: the stored energy is Clapeyron's `W = ½ ΔA Σ pᵢ uᵢ` of the discrete solution,
    /// which equals `∫ F dδ` exactly for the discrete frictionless problem (by the envelope
    /// theorem on `min_{p ≥ 0} ½ pᵀA p − Σ pᵢ(δ − hᵢ)`, `d(½ΔA pᵀA p)/dδ = ΔA Σ pᵢ = F`).
    pub fn elastic(&mut self, delta: f64, stiffness: bool) -> Result<ElasticForce, BallDropError> {
        if delta <= 0.0 {
            return Ok(ElasticForce {
                force: 0.0,
                stiffness: Some(0.0),
                energy: 0.0,
            });
        }
        match &mut self.law {
            Law::Hertz { k } => {
                let s = delta.sqrt();
                Ok(ElasticForce {
                    force: *k * delta * s,
                    stiffness: Some(1.5 * *k * s),
                    energy: 0.4 * *k * delta * delta * s,
                })
            }
            Law::Bem(b) => b.evaluate(delta, stiffness),
        }
    }

    /// Total force `F = max(0, F_el(δ) + c δ')` for `δ > 0`, else 0, together with `F_el`.
    pub fn total(&mut self, delta: f64, delta_rate: f64) -> Result<(f64, f64), BallDropError> {
        if delta <= 0.0 {
            return Ok((0.0, 0.0));
        }
        let el = self.elastic(delta, false)?.force;
        Ok(((el + self.damping * delta_rate).max(0.0), el))
    }
}

impl Bem {
    fn evaluate(&mut self, delta: f64, stiffness: bool) -> Result<ElasticForce, BallDropError> {
        if let Some((d, cached)) = self.last
            && d == delta
            && (!stiffness || cached.stiffness.is_some())
        {
            return Ok(cached);
        }
        let options = if stiffness {
            &self.with_stiffness
        } else {
            &self.force_only
        };
        let sol = self
            .solver
            .solve(&self.gap, NormalLoad::Approach(delta), options)
            .map_err(|source| BallDropError::ContactSolve {
                approach: delta,
                source,
            })?;
        self.solves += 1;
        let work: f64 = sol
            .pressure
            .iter()
            .zip(&sol.displacement)
            .map(|(p, u)| p * u)
            .sum();
        let result = ElasticForce {
            force: sol.normal_force,
            stiffness: if stiffness { sol.dfn_dapproach } else { None },
            energy: 0.5 * self.area * work,
        };
        self.last = Some((delta, result));
        Ok(result)
    }
}

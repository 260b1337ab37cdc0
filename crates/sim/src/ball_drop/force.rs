//! Contact force laws of the ball drop: Hertz's closed form and the boundary-element
//! half-space solver at prescribed approach ([`halfspace::law`]), with optional linear
//! surface damping ([`Damped`]).

use halfspace::law::{
    BemLaw, BemOptions, ContactLaw, Damped, DampingModel, HertzPoint, LawOutput, TangentPolicy,
};
use halfspace::{ContactError, GapShape, Material, NormalLoad, SolverOptions};

use super::{BallDropError, BallShape};

/// Hertz's law of the ball's gap on a flat surface (references.md §D1.4, references.md §C4.1).
fn hertz_point(shape: &BallShape, material: &Material) -> Result<HertzPoint, BallDropError> {
    match *shape {
        BallShape::Sphere { radius } => {
            HertzPoint::sphere(radius, material).map_err(|source| BallDropError::Material {
                key: "[ball] radius",
                source,
            })
        }
        BallShape::Ellipsoid { radius_x, radius_y } => {
            HertzPoint::elliptic(0.5 / radius_x, 0.5 / radius_y, material).map_err(|source| {
                BallDropError::Material {
                    key: "[ball] radius_x/radius_y",
                    source,
                }
            })
        }
    }
}

/// The Hertz constant `K` of `F = K δ^{3/2}` \[N/m^{3/2}\] for the ball's gap on a flat
/// surface (references.md §D1.4, references.md §C4.1; [`HertzPoint`]).
///
/// * sphere: `K = (4/3) E* √R` (Johnson 1985 §11.4);
/// * ellipsoid with principal radii of curvature `R_x`, `R_y` at its lowest point: the gap is
///   `h = A x² + B y²` with `A = 1/(2R_x)`, `B = 1/(2R_y)`; Hertz's elliptic solution gives
///   the approach `δ₁` under a unit force, and since `F ∝ δ^{3/2}`, `K = δ₁^{−3/2}`.
pub fn hertz_constant(shape: &BallShape, material: &Material) -> Result<f64, BallDropError> {
    Ok(hertz_point(shape, material)?.coefficient())
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

impl From<LawOutput> for ElasticForce {
    fn from(out: LawOutput) -> Self {
        Self {
            force: out.force,
            stiffness: out.tangent_fresh.then_some(out.stiffness),
            energy: out.energy,
        }
    }
}

/// The damped elastic law.
#[derive(Debug)]
enum Law {
    /// `F = K δ^{3/2}`, `W = (2/5) K δ^{5/2}`.
    Hertz(Damped<HertzPoint>),
    /// The half-space solver (boxed: it owns FFT plans and work vectors).
    Bem(Box<Damped<BemLaw>>),
}

/// A contact force model: an elastic law plus linear surface damping `c δ'`.
///
/// Total force (compression positive, acting upward on the ball):
/// `F = max(0, F_el(δ) + c δ')` while `δ > 0`, and `F = 0` otherwise. The clamp keeps the
/// damped force from pulling the ball (a surface cannot hold it).
#[derive(Debug)]
pub struct ContactForce {
    law: Law,
}

fn damped<L: ContactLaw>(law: L, damping: f64) -> Result<Damped<L>, BallDropError> {
    Damped::new(law, DampingModel::Linear { c: damping }).map_err(|source| {
        BallDropError::Material {
            key: "[contact] damping",
            source,
        }
    })
}

impl ContactForce {
    /// Hertz's law `F_el = K δ^{3/2}` of the ball's shape ([`hertz_constant`]).
    pub fn hertz(
        shape: &BallShape,
        material: &Material,
        damping: f64,
    ) -> Result<Self, BallDropError> {
        Ok(Self {
            law: Law::Hertz(damped(hertz_point(shape, material)?, damping)?),
        })
    }

    /// The half-space solver on an automatic `elements × elements` grid sized for the Hertz
    /// patch at `max_approach` (with the margin [`halfspace::AUTO_GRID_MARGIN`]); the gap is
    /// the exact sphere `h = R − √(R² − r²)` or, for an ellipsoid, its quadratic
    /// `A x² + B y²`. NormCG tolerance `tol`; the tangent (tolerance min(tol, 1e-10)) only
    /// when asked; repeated evaluations at the same δ are memoized.
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
        let options = BemOptions {
            solver: SolverOptions {
                tol,
                max_iter: 500,
                sensitivity: false,
                sensitivity_tol: tol.min(1e-10),
                ..SolverOptions::default()
            },
            tangent: TangentPolicy::Requested,
            memoize: true,
            skip_separated: false,
            reuse_tol: 0.0,
        };
        let law = BemLaw::from_shape(
            &gap_shape,
            material,
            NormalLoad::Approach(max_approach),
            elements,
            options,
        )
        .map_err(|source| BallDropError::Material {
            key: "[contact] elements",
            source,
        })?;
        Ok(Self {
            law: Law::Bem(Box::new(damped(law, damping)?)),
        })
    }

    fn law_mut(&mut self) -> &mut dyn ContactLaw {
        match &mut self.law {
            Law::Hertz(law) => law,
            Law::Bem(law) => law.as_mut(),
        }
    }

    /// Linear damping coefficient `c` \[N·s/m\].
    pub fn damping(&self) -> f64 {
        match &self.law {
            Law::Hertz(law) => law.damping(),
            Law::Bem(law) => law.damping(),
        }
    }

    /// Number of half-space solves so far (0 for Hertz).
    pub fn solves(&self) -> usize {
        match &self.law {
            Law::Hertz(_) => 0,
            Law::Bem(law) => law.inner().solves(),
        }
    }

    /// The grid (nx, ny, dx, dy) of the BEM model, `None` for Hertz.
    pub fn grid(&self) -> Option<(usize, usize, f64, f64)> {
        match &self.law {
            Law::Hertz(_) => None,
            Law::Bem(law) => {
                let g = law.inner().grid();
                Some((g.nx, g.ny, g.dx, g.dy))
            }
        }
    }

    /// Elastic force, energy and (if `stiffness`) the tangent `dF_el/dδ` at approach δ \[m\].
    ///
    /// BEM: the stored energy is Clapeyron's `W = ½ ΔA Σ pᵢ uᵢ` of the discrete solution,
    /// which equals `∫ F dδ` exactly for the discrete frictionless problem ([`BemLaw`]).
    pub fn elastic(&mut self, delta: f64, stiffness: bool) -> Result<ElasticForce, BallDropError> {
        if delta <= 0.0 {
            return Ok(ElasticForce {
                force: 0.0,
                stiffness: Some(0.0),
                energy: 0.0,
            });
        }
        let out = self
            .law_mut()
            .evaluate(delta, &[], &mut [], stiffness)
            .map_err(solve_error(delta))?;
        Ok(out.into())
    }

    /// Total force `F = max(0, F_el(δ) + c δ')` for `δ > 0`, else 0, together with `F_el`.
    pub fn total(&mut self, delta: f64, delta_rate: f64) -> Result<(f64, f64), BallDropError> {
        if delta <= 0.0 {
            return Ok((0.0, 0.0));
        }
        let (force, elastic) = self
            .law_mut()
            .total_force(delta, delta_rate)
            .map_err(solve_error(delta))?;
        Ok((force, elastic.force))
    }
}

/// A contact-law error inside the time integration, at approach `approach` \[m\].
fn solve_error(approach: f64) -> impl Fn(ContactError) -> BallDropError {
    move |source| BallDropError::ContactSolve { approach, source }
}

//! Hertz's elliptic point contact as a force law (references.md §C4.1).

use super::{ContactLaw, LawOutput, semi_ellipse_profile, single_column_approach};
use crate::error::{ContactError, positive};
use crate::hertz::Hertz;
use crate::material::Material;

/// Hertz point contact F = C δ^{3/2} for δ > 0, else 0 (references.md §C4.1):
/// k = dF/dδ = 1.5 C δ^{1/2} = 1.5 F/δ, W = ∫₀^δ F = 0.4 C δ^{5/2} = 0.4 F δ.
/// The patch semi-axes and the peak pressure scale as F^{1/3} from the unit-force solution.
#[derive(Debug, Clone)]
pub struct HertzPoint {
    coefficient: f64,
    /// Semi-axes and peak pressure at F = 1 N.
    unit: Hertz,
    /// C^{1/3}: the F^{1/3} scale of the patch is C^{1/3} δ^{1/2} (no cube root per evaluation).
    coefficient_cbrt: f64,
    columns: [f64; 1],
    last_force: f64,
}

impl HertzPoint {
    /// The elliptic contact of the gap h = A x² + B y² (curvatures A, B \[1/m\], e.g. from
    /// [`crate::curvatures_from_radii`]): C = δ₁^{−3/2} with δ₁ the approach under 1 N.
    pub fn elliptic(a_curv: f64, b_curv: f64, material: &Material) -> Result<Self, ContactError> {
        let unit = Hertz::elliptic(a_curv, b_curv, material.e_star, 1.0)?;
        Ok(Self::with_unit(unit.approach.powf(-1.5), unit))
    }

    /// A sphere of combined radius R \[m\] on a plane: C = (4/3) E* √R (Johnson 1985 §4.2).
    pub fn sphere(radius: f64, material: &Material) -> Result<Self, ContactError> {
        let unit = Hertz::sphere(radius, material.e_star, 1.0)?;
        positive("E*", material.e_star)?;
        Ok(Self::with_unit(
            4.0 / 3.0 * material.e_star * radius.sqrt(),
            unit,
        ))
    }

    fn with_unit(coefficient: f64, unit: Hertz) -> Self {
        Self {
            coefficient,
            coefficient_cbrt: coefficient.cbrt(),
            unit,
            columns: [0.0],
            last_force: 0.0,
        }
    }

    /// C in F = C δ^{3/2} \[N/m^{3/2}\].
    pub fn coefficient(&self) -> f64 {
        self.coefficient
    }

    /// Semi-axes a (along x), b (across) \[m\] and peak pressure \[Pa\] at force F \[N\].
    pub fn at_force(&self, force: f64) -> (f64, f64, f64) {
        let s = force.max(0.0).cbrt();
        (self.unit.a * s, self.unit.b * s, self.unit.max_pressure * s)
    }
}

impl ContactLaw for HertzPoint {
    fn name(&self) -> &'static str {
        "hertz"
    }

    fn columns(&self) -> &[f64] {
        &self.columns
    }

    /// A point contact: a column correction c₀ shifts the approach to δ − c₀.
    fn evaluate(
        &mut self,
        delta: f64,
        column_gap: &[f64],
        column_force: &mut [f64],
        _tangent: bool,
    ) -> Result<LawOutput, ContactError> {
        let delta = single_column_approach(delta, column_gap, column_force)?;
        if delta <= 0.0 {
            column_force.fill(0.0);
            self.last_force = 0.0;
            return Ok(LawOutput {
                tangent_fresh: true,
                ..LawOutput::default()
            });
        }
        let root = delta.sqrt();
        let force = self.coefficient * delta * root;
        column_force.fill(force);
        self.last_force = force;
        // at_force(F) with F^{1/3} = C^{1/3} δ^{1/2} (equal to round-off).
        let s = self.coefficient_cbrt * root;
        let (a, b, p0) = (self.unit.a * s, self.unit.b * s, self.unit.max_pressure * s);
        Ok(LawOutput {
            force,
            stiffness: 1.5 * self.coefficient * root,
            tangent_fresh: true,
            energy: 0.4 * self.coefficient * delta * delta * root,
            patch_length: 2.0 * a,
            patch_width: 2.0 * b,
            max_pressure: p0,
            iterations: 0,
        })
    }

    fn static_approach(&mut self, force: f64) -> Result<f64, ContactError> {
        crate::error::finite("force", force)?;
        Ok((force.max(0.0) / self.coefficient).powf(2.0 / 3.0))
    }

    /// p(ξ, 0) = p₀ √(1 − ξ²/a²) of the last evaluation, 41 points over \[−1.25a, 1.25a\].
    fn centreline_pressure(&self, out: &mut Vec<(f64, f64)>) {
        let (a, _, p0) = self.at_force(self.last_force);
        semi_ellipse_profile(a, p0, out);
    }
}

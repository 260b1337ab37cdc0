//! Hertz's line contact of a cylinder on a half-space as a force law (references.md §C4.1).

use super::{ContactLaw, LawOutput, semi_ellipse_profile, single_column_approach};
use crate::error::{ContactError, finite, positive};
use crate::material::Material;

/// Hertz line contact of a cylinder (combined radius R, length L) on an elastic half-space,
/// per unit length F' = F/L (Johnson 1985 §4.3; references.md §C4.1):
///
/// ```text
/// a² = 4 R F'/(π E*),   p₀ = 2F'/(π a),   p(x) = p₀ √(1 − x²/a²).
/// ```
///
/// **Approach.** In two dimensions the displacement of a loaded half-plane grows like ln r,
/// so an approach is only defined relative to a reference point at a depth d below the
/// surface (on the axis of the load). Integrating the plane-strain strain
/// ε_z = ((1 − ν²) σ_z − ν(1 + ν) σ_x)/E over the axis stresses of the Hertz pressure
/// (Johnson 1985 §4.3: σ_z = −p₀ a/√(a² + z²), σ_x = −p₀ ((a² + 2z²)/(a √(a² + z²)) − 2z/a))
/// from the surface to z = d gives, with s = d/a and κ = ν/(1 − ν),
///
/// ```text
/// δ(F') = (2F'/(π E*)) · [ asinh s − κ s (√(1 + s²) − s) ]
///       → (F'/(π E*)) · [ 2 ln(2d/a) − ν/(1 − ν) ]        for d ≫ a,
/// ```
///
/// the classical logarithmic law of line contact. It holds exactly for a rigid cylinder on
/// one elastic body and for two bodies of equal ν with the reference point at depth d in each;
/// with the combined E* and ν of [`Material`] it is used for any pair. The law is valid for
/// a ≤ d (δ(F') is increasing there; beyond, the reference point would lie inside the
/// contact zone): larger approaches are rejected with an error naming `approach`.
///
/// F'(δ) is found by safeguarded Newton iteration; k = dF/dδ = L/(dδ/dF') with
/// dδ/dF' = (2/(π E*)) [g(s) − s g'(s)/2], g(s) = asinh s − κ s/(√(1 + s²) + s); the energy
/// W = ∫₀^δ F dδ' = L (F' δ − ∫₀^{F'} δ(f) df) in closed form (tests/hertz_line.rs checks
/// both against finite differences and Simpson quadrature, the approach against Flamant's
/// displacement field integrated over the Hertz pressure).
#[derive(Debug, Clone)]
pub struct HertzLine {
    radius: f64,
    length: f64,
    depth: f64,
    e_star: f64,
    /// κ = ν/(1 − ν) of the combined material.
    kappa: f64,
    columns: [f64; 1],
    last_force_per_length: f64,
}

impl HertzLine {
    /// A cylinder of combined radius `radius` R \[m\] and contact length `length` L \[m\]
    /// on a half-space, the approach measured to a point at depth `depth` d \[m\] below the
    /// surface (all three positive and finite).
    pub fn new(
        radius: f64,
        length: f64,
        depth: f64,
        material: &Material,
    ) -> Result<Self, ContactError> {
        positive("radius", radius)?;
        positive("length", length)?;
        positive("depth", depth)?;
        positive("E*", material.e_star)?;
        Ok(Self {
            radius,
            length,
            depth,
            e_star: material.e_star,
            kappa: material.nu / (1.0 - material.nu),
            columns: [0.0],
            last_force_per_length: 0.0,
        })
    }

    /// Half-width a = √(4 R F'/(π E*)) \[m\] at force per length F' \[N/m\].
    pub fn half_width(&self, force_per_length: f64) -> f64 {
        (4.0 * self.radius * force_per_length.max(0.0) / (std::f64::consts::PI * self.e_star))
            .sqrt()
    }

    /// Peak pressure p₀ = 2F'/(π a) \[Pa\] at force per length F' \[N/m\].
    pub fn max_pressure(&self, force_per_length: f64) -> f64 {
        let a = self.half_width(force_per_length);
        if a > 0.0 {
            2.0 * force_per_length / (std::f64::consts::PI * a)
        } else {
            0.0
        }
    }

    /// The largest force per length of the law's range, where a = d \[N/m\].
    pub fn max_force_per_length(&self) -> f64 {
        std::f64::consts::PI * self.e_star * self.depth * self.depth / (4.0 * self.radius)
    }

    /// 2/(π E*) \[m²/N\].
    fn compliance(&self) -> f64 {
        2.0 / (std::f64::consts::PI * self.e_star)
    }

    /// s = d/a and q = √(1 + s²) at F' > 0.
    fn depth_ratio(&self, force_per_length: f64) -> (f64, f64) {
        let s = self.depth / self.half_width(force_per_length);
        (s, s.hypot(1.0))
    }

    /// δ(F') \[m\] (type documentation), without the range check.
    fn approach_unchecked(&self, fpl: f64) -> f64 {
        if fpl <= 0.0 {
            return 0.0;
        }
        let (s, q) = self.depth_ratio(fpl);
        self.compliance() * fpl * (s.asinh() - self.kappa * s / (q + s))
    }

    /// dδ/dF' \[m²/N\] at F' > 0.
    fn approach_rate(&self, fpl: f64) -> f64 {
        let (s, q) = self.depth_ratio(fpl);
        let g = s.asinh() - self.kappa * s / (q + s);
        // g'(s) = 1/q − κ/(q (q + s)²), written without cancellation.
        let dg = 1.0 / q - self.kappa / (q * (q + s) * (q + s));
        self.compliance() * (g - 0.5 * s * dg)
    }

    /// ∫₀^{F'} δ(f) df \[N\] in closed form: with w = √(1 + (a/d)²),
    /// (2/(π E*)) F'² [ ½ (asinh s + (w + 2)/(3 (w + 1)²)) − κ (2w + 1)/(3 (w + 1)²) ].
    fn complementary_energy(&self, fpl: f64) -> f64 {
        if fpl <= 0.0 {
            return 0.0;
        }
        let (s, _) = self.depth_ratio(fpl);
        let w = (1.0 / s).hypot(1.0);
        let w1 = 3.0 * (w + 1.0) * (w + 1.0);
        self.compliance()
            * fpl
            * fpl
            * (0.5 * (s.asinh() + (w + 2.0) / w1) - self.kappa * (2.0 * w + 1.0) / w1)
    }

    /// The approach δ \[m\] at force per length F' \[N/m\] (≥ 0, with a ≤ d).
    pub fn approach(&self, force_per_length: f64) -> Result<f64, ContactError> {
        finite("force per length", force_per_length)?;
        if force_per_length > self.max_force_per_length() {
            return Err(ContactError::InvalidParameter {
                name: "force per length",
                value: force_per_length,
                reason: "the contact half-width a would exceed the reference depth d \
                         (the line law needs a ≤ d: F' ≤ π E* d²/(4R))",
            });
        }
        Ok(self.approach_unchecked(force_per_length))
    }

    /// The force per length F'(δ) \[N/m\] (0 for δ ≤ 0); an error for an approach beyond
    /// the law's range a ≤ d.
    pub fn force_per_length(&self, delta: f64) -> Result<f64, ContactError> {
        finite("approach", delta)?;
        if delta <= 0.0 {
            return Ok(0.0);
        }
        let f_max = self.max_force_per_length();
        if delta > self.approach_unchecked(f_max) {
            return Err(ContactError::InvalidParameter {
                name: "approach",
                value: delta,
                reason: "the contact half-width a would exceed the reference depth d \
                         (the line law needs a ≤ d: δ ≤ δ(F' = π E* d²/(4R)))",
            });
        }
        // δ(F') is increasing on [0, f_max]: Newton's method kept inside the bracket
        // [lo, hi] by bisection.
        let (mut lo, mut hi) = (0.0, f_max);
        let mut f = f_max.min(delta / self.compliance());
        for _ in 0..200 {
            let r = self.approach_unchecked(f) - delta;
            if r > 0.0 {
                hi = f;
            } else {
                lo = f;
            }
            let mut next = f - r / self.approach_rate(f);
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            let done = (next - f).abs() <= 1e-15 * f;
            f = next;
            if done || hi - lo <= 1e-15 * hi {
                break;
            }
        }
        Ok(f)
    }
}

impl ContactLaw for HertzLine {
    fn name(&self) -> &'static str {
        "hertz-line"
    }

    fn columns(&self) -> &[f64] {
        &self.columns
    }

    /// One column (the contact line): a column correction c₀ shifts the approach to δ − c₀.
    fn evaluate(
        &mut self,
        delta: f64,
        column_gap: &[f64],
        column_force: &mut [f64],
        _tangent: bool,
    ) -> Result<LawOutput, ContactError> {
        let delta = single_column_approach(delta, column_gap, column_force)?;
        let fpl = self.force_per_length(delta)?;
        self.last_force_per_length = fpl;
        let force = fpl * self.length;
        column_force.fill(force);
        if fpl <= 0.0 {
            return Ok(LawOutput {
                tangent_fresh: true,
                patch_width: self.length,
                ..LawOutput::default()
            });
        }
        Ok(LawOutput {
            force,
            stiffness: self.length / self.approach_rate(fpl),
            tangent_fresh: true,
            energy: self.length * (fpl * delta - self.complementary_energy(fpl)),
            patch_length: 2.0 * self.half_width(fpl),
            patch_width: self.length,
            max_pressure: self.max_pressure(fpl),
            iterations: 0,
        })
    }

    fn static_approach(&mut self, force: f64) -> Result<f64, ContactError> {
        finite("force", force)?;
        self.approach(force.max(0.0) / self.length)
    }

    /// p(ξ) = p₀ √(1 − ξ²/a²) of the last evaluation, 41 points over \[−1.25a, 1.25a\].
    fn centreline_pressure(&self, out: &mut Vec<(f64, f64)>) {
        let fpl = self.last_force_per_length;
        semi_ellipse_profile(self.half_width(fpl), self.max_pressure(fpl), out);
    }
}

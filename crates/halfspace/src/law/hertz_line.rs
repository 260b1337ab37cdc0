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
/// W = ∫₀^δ F dδ' = L (F' δ − ∫₀^{F'} δ(f) df) in closed form (module tests check both
/// against finite differences and Simpson quadrature, the approach against Flamant's
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

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// CONTACT's Carter 2-D case (references.md §C4.1): R = 500 mm, G = 82 000 N/mm²,
    /// ν = 0.28, a = 1 mm → F' = 178.90 N/mm, p₀ = 113.88 N/mm² (quoted to 5 digits: 1e-4).
    #[test]
    fn carter_case_half_width_and_peak_pressure() {
        let m = Material::from_combined(82e9, 0.28).unwrap();
        let law = HertzLine::new(0.5, 0.01, 0.02, &m).unwrap();
        let fpl = 178.90e3;
        assert_relative_eq!(law.half_width(fpl), 1e-3, max_relative = 1e-4);
        assert_relative_eq!(law.max_pressure(fpl), 113.88e6, max_relative = 1e-4);
    }

    /// Gauss–Legendre nodes and weights on [−1, 1] by Newton on P_n (independent of the law).
    fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
        (1..=n)
            .map(|i| {
                let mut x = (std::f64::consts::PI * (i as f64 - 0.25) / (n as f64 + 0.5)).cos();
                let mut dp = 0.0;
                for _ in 0..100 {
                    let (mut p0, mut p1) = (1.0, x);
                    for k in 2..=n {
                        let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                        p0 = p1;
                        p1 = p2;
                    }
                    dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                    let step = p1 / dp;
                    x -= step;
                    if step.abs() < 1e-16 {
                        break;
                    }
                }
                (x, 2.0 / ((1.0 - x * x) * dp * dp))
            })
            .collect()
    }

    /// The approach from Flamant's line-load solution (plane strain, z into the solid; the
    /// displacement field follows from integrating its strains, Johnson 1985 §2.2):
    /// u_z(x, z) = −(2P(1 − ν²)/(π E)) ln r − (P(1 + ν)/(π E)) x²/r² + C.
    /// The compression between the surface point under the centre and the point at depth d
    /// below it, from a line load P at distance x, is with E* = E/(1 − ν²)
    /// u_z(x, 0) − u_z(x, d) = (P/(π E*)) [ln(1 + d²/x²) − (1/(1 − ν)) d²/(x² + d²)],
    /// integrated over the Hertz pressure with x = a sin t (p dx = p₀ a cos²t dt) by
    /// Gauss–Legendre on panels graded geometrically towards the log singularity at t = 0.
    fn flamant_approach(fpl: f64, a: f64, d: f64, nu: f64, e_star: f64) -> f64 {
        let p0 = 2.0 * fpl / (std::f64::consts::PI * a);
        let rule = gauss_legendre(20);
        let kernel = |x: f64| ((d * d) / (x * x)).ln_1p() - d * d / ((1.0 - nu) * (x * x + d * d));
        let mut total = 0.0;
        let mut hi = 0.5 * std::f64::consts::PI;
        for _ in 0..60 {
            let lo = 0.25 * hi;
            let (mid, half) = (0.5 * (hi + lo), 0.5 * (hi - lo));
            for &(u, w) in &rule {
                let t = mid + half * u;
                total += w * half * t.cos().powi(2) * kernel(a * t.sin());
            }
            hi = lo;
        }
        // Both halves x < 0 and x > 0.
        2.0 * p0 * a * total / (std::f64::consts::PI * e_star)
    }

    #[test]
    fn approach_matches_flamant_integration() {
        // Rigid cylinder on steel: the law is exact there. Depths from 1.5 a to 300 a.
        let m = Material::combine(
            crate::material::Body::Rigid,
            crate::material::Body::elastic(210e9, 0.3).unwrap(),
        )
        .unwrap();
        assert!(
            HertzLine::new(0.05, 0.02, 0.0, &m).is_err(),
            "zero depth is rejected"
        );
        let fpl = 2e5;
        let a = HertzLine::new(0.05, 0.02, 1.0, &m).unwrap().half_width(fpl);
        for depth in [1.5 * a, 10.0 * a, 300.0 * a] {
            let law = HertzLine::new(0.05, 0.02, depth, &m).unwrap();
            let numeric = flamant_approach(fpl, a, depth, m.nu, m.e_star);
            let closed = law.approach(fpl).unwrap();
            println!(
                "d/a = {:.1}: closed {closed:e}, Flamant {numeric:e}",
                depth / a
            );
            // Quadrature error ~1e-15 (60 graded panels × 20 points); measured 4e-15.
            assert_relative_eq!(closed, numeric, max_relative = 1e-12);
            // The asymptote (F'/(π E*))(2 ln(2d/a) − ν/(1 − ν)) to O((a/d)²).
            let asym = fpl / (std::f64::consts::PI * m.e_star)
                * (2.0 * (2.0 * depth / a).ln() - m.nu / (1.0 - m.nu));
            assert!(((closed - asym) / closed).abs() < 2.0 * (a / depth).powi(2));
        }
    }

    #[test]
    fn force_tangent_and_energy() {
        let m = Material::identical(210e9, 0.3).unwrap();
        let (length, depth) = (0.02, 0.01);
        let mut law = HertzLine::new(0.05, length, depth, &m).unwrap();
        let delta_max = law.approach(law.max_force_per_length()).unwrap();
        for frac in [1e-4, 0.01, 0.3, 0.9] {
            let delta = frac * delta_max;
            let out = law.evaluate(delta, &[], &mut [], true).unwrap();
            // Inversion: δ(F'(δ)) = δ to round-off.
            assert_relative_eq!(
                law.approach(out.force / length).unwrap(),
                delta,
                max_relative = 1e-13
            );
            assert_relative_eq!(
                law.static_approach(out.force).unwrap(),
                delta,
                max_relative = 1e-13
            );
            // Tangent against a central difference (truncation O(h²) ~ 1e-12, round-off
            // 1e-16/1e-6 ~ 1e-10; measured ≤ 1e-10): 1e-8.
            let h = 1e-6 * delta;
            let fp = law.evaluate(delta + h, &[], &mut [], false).unwrap().force;
            let fm = law.evaluate(delta - h, &[], &mut [], false).unwrap().force;
            assert_relative_eq!(out.stiffness, (fp - fm) / (2.0 * h), max_relative = 1e-8);
            // Energy against composite Simpson over [0, δ] (F ~ δ/ln(1/δ) near 0: the
            // error at 4000 intervals is ~2e-10, measured).
            let n = 4000;
            let step = delta / n as f64;
            let mut w = law.evaluate(delta, &[], &mut [], false).unwrap().force;
            for i in 1..n {
                let f = law
                    .evaluate(i as f64 * step, &[], &mut [], false)
                    .unwrap()
                    .force;
                w += f * if i % 2 == 1 { 4.0 } else { 2.0 };
            }
            w *= step / 3.0;
            let fd = (fp - fm) / (2.0 * h);
            println!(
                "δ/δmax = {frac}: k {:e} vs FD {fd:e}; W {:e} vs Simpson {w:e}",
                out.stiffness, out.energy
            );
            assert_relative_eq!(out.energy, w, max_relative = 1e-8);
            assert_relative_eq!(out.patch_length, 2.0 * law.half_width(out.force / length));
            assert_eq!(out.patch_width, length);
        }
        // Beyond the range a ≤ d, and bad inputs: errors naming the key.
        let err = law
            .evaluate(1.01 * delta_max, &[], &mut [], true)
            .unwrap_err();
        assert!(err.to_string().contains("approach"), "{err}");
        assert!(law.evaluate(f64::NAN, &[], &mut [], true).is_err());
        let out = law.evaluate(-1e-6, &[], &mut [], true).unwrap();
        assert_eq!((out.force, out.stiffness, out.energy), (0.0, 0.0, 0.0));
        for (r, l, d) in [(0.0, 1.0, 1.0), (1.0, -1.0, 1.0), (1.0, 1.0, f64::INFINITY)] {
            assert!(HertzLine::new(r, l, d, &m).is_err());
        }
    }
}

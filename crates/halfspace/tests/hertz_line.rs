//! `halfspace::law::HertzLine` (references.md §C4.1) against CONTACT's Carter 2-D case, an
//! independent numerical integration of Flamant's line-load solution, finite differences and
//! Simpson quadrature.

mod support;

use approx::assert_relative_eq;
use halfspace::law::{ContactLaw, HertzLine};
use halfspace::{Body, Material};
use support::gauss_legendre;

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
    let m = Material::combine(Body::Rigid, Body::elastic(210e9, 0.3).unwrap()).unwrap();
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

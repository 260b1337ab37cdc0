//! Tests of the contact laws against closed forms and quadratures.

use super::*;
use crate::gap::GapShape;
use crate::hertz::Hertz;
use crate::material::Material;
use crate::normcg::NormalLoad;
use approx::assert_relative_eq;

fn steel() -> Material {
    Material::identical(210e9, 0.3).unwrap()
}

/// Composite Simpson rule of `f` over [0, b] with `n` (even) intervals.
fn simpson(mut f: impl FnMut(f64) -> f64, b: f64, n: usize) -> f64 {
    let h = b / n as f64;
    let mut s = f(0.0) + f(b);
    for i in 1..n {
        s += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * h / 3.0
}

#[test]
fn hertz_sphere_matches_closed_forms() {
    let m = steel();
    let r = 0.01;
    let mut law = HertzPoint::sphere(r, &m).unwrap();
    let c = 4.0 / 3.0 * m.e_star * r.sqrt();
    assert_eq!(law.coefficient(), c);
    for delta in [1e-7, 3e-6, 2e-5] {
        let out = law.evaluate(delta, &[], &mut [], true).unwrap();
        let f = c * delta.powf(1.5);
        assert_relative_eq!(out.force, f, max_relative = 1e-14);
        assert_relative_eq!(out.stiffness, 1.5 * f / delta, max_relative = 1e-14);
        assert_relative_eq!(out.energy, 0.4 * f * delta, max_relative = 1e-14);
        // Patch and peak pressure: Hertz's sphere at this force.
        let h = Hertz::sphere(r, m.e_star, f).unwrap();
        assert_relative_eq!(out.patch_length, 2.0 * h.a, max_relative = 1e-12);
        assert_relative_eq!(out.max_pressure, h.max_pressure, max_relative = 1e-12);
        // Energy = ∫F dδ by Simpson (F ∝ δ^{3/2}: error O(h^{2.5}) near 0, 1e-6 at 2000).
        let w = simpson(|d| c * d.powf(1.5), delta, 2000);
        assert_relative_eq!(out.energy, w, max_relative = 1e-6);
        assert_relative_eq!(law.static_approach(f).unwrap(), delta, max_relative = 1e-12);
    }
    let out = law.evaluate(-1e-6, &[], &mut [], true).unwrap();
    assert_eq!((out.force, out.stiffness, out.energy), (0.0, 0.0, 0.0));
    assert!(law.evaluate(f64::NAN, &[], &mut [], true).is_err());
}

#[test]
fn hertz_elliptic_coefficient_and_column_shift() {
    // The wheel-rail ellipse: R_w = 0.46 m along, R_r = 0.3 m across.
    let m = steel();
    let (a, b) = (0.5 / 0.46, 0.5 / 0.3);
    let mut law = HertzPoint::elliptic(a, b, &m).unwrap();
    // Independent path: Hertz's elliptic solution at a force gives the approach.
    let h = Hertz::elliptic(a, b, m.e_star, 100e3).unwrap();
    let mut column = [0.0];
    let out = law.evaluate(h.approach, &[], &mut column, true).unwrap();
    assert_relative_eq!(out.force, 100e3, max_relative = 1e-12);
    assert_eq!(column[0], out.force);
    assert_relative_eq!(out.stiffness, h.stiffness, max_relative = 1e-12);
    assert_relative_eq!(out.patch_length, 2.0 * h.a, max_relative = 1e-12);
    assert_relative_eq!(out.patch_width, 2.0 * h.b, max_relative = 1e-12);
    // A column correction c₀ is a shift of the approach.
    let shifted = law
        .evaluate(h.approach + 1e-6, &[1e-6], &mut [], false)
        .unwrap();
    assert_relative_eq!(shifted.force, out.force, max_relative = 1e-9);
    assert!(matches!(
        law.evaluate(1e-5, &[0.0, 0.0], &mut [], false),
        Err(ContactError::SizeMismatch { .. })
    ));
}

/// Relative BEM errors in F and dF/dδ against Hertz for the quadratic gap of a sphere
/// (R = 10 mm, steel) at δ = 10 µm on the automatic n × n grid (its half-width is 1.25 × the
/// Hertz radius, so the contact edge sits on element boundaries for n = 20, 40, 80).
fn bem_sphere_error(n: usize) -> (f64, f64) {
    let m = steel();
    let r = 0.01;
    let delta = 1e-5;
    let shape = GapShape::Quadratic {
        a: 0.5 / r,
        b: 0.5 / r,
    };
    let mut law = BemLaw::from_shape(
        &shape,
        m,
        NormalLoad::Approach(delta),
        n,
        BemOptions::default(),
    )
    .unwrap();
    let out = law.evaluate(delta, &[], &mut [], true).unwrap();
    let f = Hertz::sphere_force(r, m.e_star, delta);
    (out.force / f - 1.0, out.stiffness / (1.5 * f / delta) - 1.0)
}

#[test]
fn bem_converges_to_hertz_at_the_observed_order() {
    // Measured: F error 1.59e-3 (20²), 3.43e-4 (40²), 7.29e-5 (80²): second order in the
    // element size. The tangent's error is not monotone (elements entering the contact set
    // along its perimeter): 1.5e-3, −2.8e-3, 1.7e-3.
    let (e20, k20) = bem_sphere_error(20);
    let (e40, k40) = bem_sphere_error(40);
    let order = (e20.abs() / e40.abs()).log2();
    eprintln!("F error 20: {e20:e}, 40: {e40:e}, order {order:.2}; k error {k20:e}, {k40:e}");
    assert!((1.7..2.7).contains(&order), "observed order {order}");
    assert!(e40.abs() < 5e-4, "{e40}");
    assert!(k20.abs() < 5e-3 && k40.abs() < 5e-3, "{k20} {k40}");
}

#[test]
fn bem_energy_is_the_integral_of_the_force() {
    let m = steel();
    let r = 0.01;
    let dmax = 1e-5;
    let shape = GapShape::Sphere { radius: r };
    let mut law = BemLaw::from_shape(
        &shape,
        m,
        NormalLoad::Approach(dmax),
        24,
        BemOptions::default(),
    )
    .unwrap();
    let w = law.evaluate(dmax, &[], &mut [], false).unwrap().energy;
    // ∫₀^δ F dδ' by Simpson on the BEM force itself. The discrete F(δ) has kinks where
    // elements enter contact, so Simpson is not of fourth order here; measured relative
    // errors 5.4e-7 (200 intervals) and 3.1e-7 (400). Tolerance 2e-6.
    let mut q = |n| {
        simpson(
            |d| law.evaluate(d, &[], &mut [], false).unwrap().force,
            dmax,
            n,
        )
    };
    let (w200, w400) = (q(200), q(400));
    eprintln!("W = {w:e}, quadrature 200: {w200:e}, 400: {w400:e}");
    assert!((w400 / w - 1.0).abs() <= (w200 / w - 1.0).abs() + 1e-6);
    assert_relative_eq!(w400, w, max_relative = 2e-6);
    // And close to Hertz's 0.4 F δ (discretisation error of 24² elements).
    let f = Hertz::sphere_force(r, m.e_star, dmax);
    assert_relative_eq!(w, 0.4 * f * dmax, max_relative = 0.05);
}

#[test]
fn bem_tangent_matches_finite_difference_and_columns_shift() {
    let m = steel();
    let mut law = BemLaw::wheel_on_rail(0.46, 0.3, m, 24, 100e3, BemOptions::default()).unwrap();
    let h = Hertz::elliptic(0.5 / 0.46, 0.5 / 0.3, m.e_star, 80e3).unwrap();
    let d = h.approach;
    let nx = law.columns().len();
    let mut cols = vec![0.0; nx];
    let out = law.evaluate(d, &[], &mut cols, true).unwrap();
    assert!(out.tangent_fresh);
    // Columns carry the whole force.
    assert_relative_eq!(cols.iter().sum::<f64>(), out.force, max_relative = 1e-12);
    // Discretisation error of 24² elements against Hertz.
    assert_relative_eq!(out.force, 80e3, max_relative = 0.03);
    let eps = 1e-3 * d;
    let fp = law.evaluate(d + eps, &[], &mut [], false).unwrap().force;
    let fm = law.evaluate(d - eps, &[], &mut [], false).unwrap().force;
    // Central difference of the piecewise-smooth discrete F(δ): agreement to a few 1e-3.
    assert_relative_eq!(out.stiffness, (fp - fm) / (2.0 * eps), max_relative = 5e-3);
    // A uniform column correction c is a shift of the approach (solver tolerance).
    let c = vec![2e-6; nx];
    let shifted = law.evaluate(d + 2e-6, &c, &mut [], false).unwrap();
    assert_relative_eq!(shifted.force, out.force, max_relative = 1e-6);
    // Separated: no solve, zero force.
    let solves = law.solves();
    let off = law.evaluate(-1e-6, &[], &mut cols, false).unwrap();
    assert_eq!(off.force, 0.0);
    assert!(cols.iter().all(|f| *f == 0.0));
    assert_eq!(law.solves(), solves);
    // The static approach inverts the force.
    let d80 = law.static_approach(80e3).unwrap();
    let f = law.evaluate(d80, &[], &mut [], false).unwrap().force;
    assert_relative_eq!(f, 80e3, max_relative = 1e-6);
}

#[test]
fn bem_tangent_policies_and_memo() {
    let m = steel();
    let shape = GapShape::Sphere { radius: 0.01 };
    let make = |tangent, memoize| {
        BemLaw::from_shape(
            &shape,
            m,
            NormalLoad::Approach(1e-5),
            16,
            BemOptions {
                tangent,
                memoize,
                ..BemOptions::default()
            },
        )
        .unwrap()
    };
    let mut lazy = make(TangentPolicy::Requested, true);
    let out = lazy.evaluate(5e-6, &[], &mut [], false).unwrap();
    assert!(!out.tangent_fresh && out.stiffness == 0.0);
    let again = lazy.evaluate(5e-6, &[], &mut [], false).unwrap();
    assert_eq!(lazy.solves(), 1, "memoized");
    assert_eq!(again, out);
    let with_k = lazy.evaluate(5e-6, &[], &mut [], true).unwrap();
    assert!(with_k.tangent_fresh && with_k.stiffness > 0.0);
    assert_eq!(lazy.solves(), 2, "a tangent was missing");
    let mut eager = make(TangentPolicy::RequestedOrMissing, false);
    let first = eager.evaluate(5e-6, &[], &mut [], false).unwrap();
    assert!(first.tangent_fresh && first.stiffness > 0.0);
    let second = eager.evaluate(6e-6, &[], &mut [], false).unwrap();
    assert!(!second.tangent_fresh);
    assert_eq!(second.stiffness, first.stiffness);
    eager.evaluate(6e-6, &[], &mut [], false).unwrap();
    assert_eq!(eager.solves(), 3, "not memoized");
}

#[test]
fn damped_law_follows_its_formula() {
    let m = steel();
    let c = 50.0;
    let mut law = Damped::new(
        HertzPoint::sphere(0.01, &m).unwrap(),
        DampingModel::Linear { c },
    )
    .unwrap();
    let k = law.inner().coefficient();
    for (delta, rate) in [(1e-6, 0.3), (1e-6, -0.3), (4e-6, -1e3), (-1e-6, 1.0)] {
        let (f, el) = law.total_force(delta, rate).unwrap();
        let f_el = if delta > 0.0 {
            k * delta.powf(1.5)
        } else {
            0.0
        };
        let expected = if delta > 0.0 {
            (f_el + c * rate).max(0.0)
        } else {
            0.0
        };
        assert_relative_eq!(el.force, f_el, max_relative = 1e-14);
        assert_relative_eq!(f, expected, max_relative = 1e-14);
    }
    // A strongly receding contact is clamped at zero force (never pulls).
    assert_eq!(law.total_force(1e-6, -1e3).unwrap().0, 0.0);
    // The elastic evaluation is the wrapped law's.
    let e = law.evaluate(1e-6, &[], &mut [], true).unwrap();
    assert_relative_eq!(e.force, k * 1e-9, max_relative = 1e-12);
    assert!(
        Damped::new(
            HertzPoint::sphere(0.01, &m).unwrap(),
            DampingModel::Linear { c: -1.0 }
        )
        .is_err()
    );
    // An undamped law's total force is its elastic force.
    let mut plain = HertzPoint::sphere(0.01, &m).unwrap();
    assert_eq!(plain.total_force(1e-6, 5.0).unwrap().0, e.force);
}

#[test]
fn rigid_constraint_complementarity_and_model_dispatch() {
    let mut rigid = RigidConstraint::new(false);
    assert!(!rigid.check_approach(-1e-6));
    assert!(rigid.check_approach(0.0));
    assert_eq!(rigid.accept_multiplier(12.5), 12.5);
    assert!(rigid.is_active());
    // A tensile multiplier releases the contact: F = 0.
    assert_eq!(rigid.accept_multiplier(-3.0), 0.0);
    assert!(!rigid.is_active());
    let mut models = [
        ContactModel::Rigid(rigid),
        ContactModel::Law(Box::new(HertzPoint::sphere(0.01, &steel()).unwrap())),
    ];
    assert_eq!(models[0].name(), "rigid");
    assert!(models[0].law_mut().is_none());
    assert_eq!(models[1].name(), "hertz");
    let f = models[1]
        .law_mut()
        .unwrap()
        .evaluate(1e-6, &[], &mut [], false)
        .unwrap()
        .force;
    assert!(f > 0.0);
}

/// A wheel on a rail (R_w = 0.46 m, R_r = 0.3 m, 20 × 20 grid, NormCG tol 1e-12) with reuse
/// (references.md §C8.4) against full solves.
fn wheel_law(reuse_tol: f64) -> BemLaw {
    BemLaw::wheel_on_rail(
        0.46,
        0.3,
        steel(),
        20,
        150e3,
        BemOptions {
            solver: crate::SolverOptions {
                tol: 1e-12,
                sensitivity_tol: 1e-10,
                max_iter: 1000,
                ..crate::SolverOptions::default()
            },
            tangent: TangentPolicy::RequestedOrMissing,
            memoize: false,
            skip_separated: true,
            reuse_tol,
        },
    )
    .unwrap()
}

/// On a frozen contact set the reused evaluation is the exact solution: a change of the
/// approach by 1e-4 relative (the contact set does not change) gives the force, the column
/// forces, the energy and dF/dδ of a full solve to 1e-7 relative (the CG tolerance 1e-5 of the
/// responses times the 1e-4 change, 1e-9, and the solver tolerances); the stiffness is the
/// sensitivity solve's to 1e-6.
#[test]
fn bem_reuse_is_exact_on_a_frozen_set() {
    let (mut exact, mut reused) = (wheel_law(0.0), wheel_law(1e-3));
    let delta = 6e-5;
    let ncol = exact.columns().len();
    let (mut fe, mut fr) = (vec![0.0; ncol], vec![0.0; ncol]);
    let a = exact.evaluate(delta, &[], &mut fe, true).unwrap();
    let b = reused.evaluate(delta, &[], &mut fr, true).unwrap();
    assert_eq!(a.force, b.force, "the first evaluation solves");
    assert_relative_eq!(a.stiffness, b.stiffness, max_relative = 1e-6);
    let d2 = delta * (1.0 + 1e-4);
    let a = exact.evaluate(d2, &[], &mut fe, true).unwrap();
    let b = reused.evaluate(d2, &[], &mut fr, true).unwrap();
    let stats = reused.reuse_stats().unwrap();
    assert_eq!((stats.full_solves, stats.reused), (1, 1), "{stats:?}");
    assert_relative_eq!(a.force, b.force, max_relative = 1e-7);
    assert_relative_eq!(a.energy, b.energy, max_relative = 1e-7);
    assert_relative_eq!(a.stiffness, b.stiffness, max_relative = 1e-6);
    for (x, y) in fe.iter().zip(&fr) {
        assert!((x - y).abs() <= 1e-7 * a.force, "{x} vs {y}");
    }
}

/// A sequence of 60 evaluations whose approach oscillates by ±8 % and whose column corrections
/// carry a tilt (slope up to 2e-3) and a curvature (up to 5e-3 1/m) changing every evaluation,
/// as between time steps: with reuse_tol = 1e-4 every reused force is within its estimate
/// (plus 1e-9 relative for the solver tolerances) of the full solve's, and at least a third of
/// the evaluations reuse (measured: 28 of 60; the approach changes by up to 1.6 % per step).
/// The other evaluations after the first are solved by the dense factor's active-set updates
/// (references.md §C8.4): within 1e-9 of NormCG.
#[test]
fn bem_reuse_estimate_bounds_the_error() {
    let (mut exact, mut reused) = (wheel_law(0.0), wheel_law(1e-4));
    let xi: Vec<f64> = exact.columns().to_vec();
    let ncol = xi.len();
    let (mut fe, mut fr) = (vec![0.0; ncol], vec![0.0; ncol]);
    let mut reuses = 0;
    for step in 0..60 {
        let t = step as f64 / 60.0;
        let delta = 6e-5 * (1.0 + 0.08 * (12.0 * t).sin());
        let slope = 2e-3 * (5.0 * t).sin();
        let curvature = 5e-3 * (7.0 * t).cos();
        let gap: Vec<f64> = xi
            .iter()
            .map(|&x| slope * x + 0.5 * curvature * x * x)
            .collect();
        let a = exact.evaluate(delta, &gap, &mut fe, true).unwrap();
        let b = reused.evaluate(delta, &gap, &mut fr, true).unwrap();
        let stats = reused.reuse_stats().unwrap();
        let error = (a.force - b.force).abs() / a.force;
        assert!(
            error <= stats.last_estimate * 1.001 + 1e-9,
            "step {step}: error {error:e}, estimate {:e}",
            stats.last_estimate
        );
        if stats.last_estimate > 0.0 {
            reuses += 1;
        }
    }
    let stats = reused.reuse_stats().unwrap();
    assert_eq!(stats.reused, reuses);
    assert!(stats.reused >= 20, "{stats:?}");
    // The set changes were solved by the factor's active-set updates (estimate 0: within
    // 1e-9 of NormCG at tolerance 1e-12), NormCG only at the first evaluation.
    assert_eq!(stats.full_solves, 1, "{stats:?}");
    assert_eq!(stats.factor_solves + stats.reused + 1, 60, "{stats:?}");
}

//! Moving force on a simply supported beam: the modal simulation against Frýba's closed-form
//! series and the undamped reference table of references.md §D1.1, the crawling-speed static limit,
//! and axle trains against the superposed closed form.

use std::f64::consts::PI;

use beam::closed_form::{SsMovingForce, speed_for_parameter, ss_midspan_static_deflection};
use beam::{
    AnalyticBeam, Axle, ModalBasis, ModalDamping, MovingLoadSettings, MovingLoads, Support,
    UniformBeam, simulate_moving_loads,
};

/// Frýba's example (references.md §D1.3): L = 25 m, EI = 2.87e9·2.90 N m², ρA = 2303 kg/m, F = 56.4 kN.
fn fryba() -> UniformBeam {
    UniformBeam::new(25.0, 2.87e9 * 2.90, 2303.0).unwrap()
}
const FORCE: f64 = 56.4e3;

fn period_1(beam: &UniformBeam) -> f64 {
    let b = AnalyticBeam::new(Support::SimplySupported, *beam, 1).unwrap();
    2.0 * PI / b.circular_frequencies()[0]
}

/// Maximum of the series midspan deflection / δ_st on a grid of `samples` points in [t0, t1].
fn series_max(
    case: &SsMovingForce,
    beam: &UniformBeam,
    t0: f64,
    t1: f64,
    samples: usize,
    terms: usize,
) -> f64 {
    let d_st = ss_midspan_static_deflection(FORCE, beam.length, beam.bending_stiffness);
    (0..=samples)
        .map(|i| t0 + (t1 - t0) * i as f64 / samples as f64)
        .map(|t| case.deflection(0.5 * beam.length, t, terms).unwrap().abs())
        .fold(0.0, f64::max)
        / d_st
}

/// The closed-form series reproduces the undamped table (150 terms, time resolution T₁/6000 as in
/// the table's footnote) to 1e-4: the table is rounded to 4 decimals (5e-5) and the grid maximum
/// is within (2π/6000)²/8 ≈ 1e-7 of the true maximum.
#[test]
fn closed_form_series_reproduces_the_table() {
    let beam = fryba();
    let t1 = period_1(&beam);
    for (alpha, passage, free) in [
        (0.5, 1.7054, Some(1.3101)),
        (0.618, 1.7317, None),
        (1.0, 1.5481, Some(1.5481)),
    ] {
        let c = speed_for_parameter(&beam, alpha).unwrap();
        let case = SsMovingForce::new(beam, FORCE, c).unwrap();
        assert!((case.speed_parameter() - alpha).abs() < 1e-12);
        let exit = case.exit_time();
        let samples = (exit / t1 * 6000.0) as usize;
        let max = series_max(&case, &beam, 0.0, exit, samples, 150);
        eprintln!("series alpha={alpha}: passage max {max:.6} (table {passage})");
        assert!(
            (max - passage).abs() < 1e-4,
            "alpha {alpha}: {max} vs {passage}"
        );
        if let Some(free) = free {
            // ω_j = j² ω₁, so the free vibration is T₁-periodic: one period holds its maximum.
            let fmax = series_max(&case, &beam, exit, exit + t1, 6000, 150);
            eprintln!("series alpha={alpha}: free max {fmax:.6} (table {free})");
            assert!(
                (fmax - free).abs() < 1e-4,
                "alpha {alpha}: free {fmax} vs {free}"
            );
        }
    }
    // α = 1: the maximum is reached at t = L/c and equals 48/π³ (references.md §D1.1); with the
    // resonance-safe form the single-mode value at exit is (96/π⁴)·π/2 exactly: check the series
    // at L/c against 48/π³ to the truncation of the other modes (< 1e-4).
    let c = speed_for_parameter(&beam, 1.0).unwrap();
    let case = SsMovingForce::new(beam, FORCE, c).unwrap();
    let d_st = ss_midspan_static_deflection(FORCE, beam.length, beam.bending_stiffness);
    let at_exit = case.deflection(12.5, case.exit_time(), 150).unwrap() / d_st;
    assert!((at_exit - 48.0 / PI.powi(3)).abs() < 1e-4, "{at_exit}");
}

/// Run the modal simulation with `modes` SS modes at speed parameter α, Δt = T₁/6000.
fn simulate(
    alpha: f64,
    modes: usize,
    free_periods: f64,
) -> (beam::MovingLoadResponse, SsMovingForce, f64) {
    let beam = fryba();
    let t1 = period_1(&beam);
    let basis = AnalyticBeam::new(Support::SimplySupported, beam, modes).unwrap();
    let c = speed_for_parameter(&beam, alpha).unwrap();
    let loads = MovingLoads::single(FORCE, c).unwrap();
    let settings = MovingLoadSettings::new(t1 / 6000.0, free_periods * t1);
    let r = simulate_moving_loads(
        &basis,
        &ModalDamping::Undamped,
        &loads,
        &settings,
        &[0.5 * beam.length],
    )
    .unwrap();
    (r, SsMovingForce::new(beam, FORCE, c).unwrap(), t1)
}

/// Modal simulation (40 modes, exact piecewise-linear modal steps, Δt = T₁/6000) against the
/// table to 1e-4 (table rounding 5e-5; truncation after 40 modes ≈ 3e-6 δ_st; sampling 1e-7),
/// and pointwise against the 40-term series to 1e-6 δ_st (the only discretisation error is the
/// linear interpolation of the modal forces, O((jΩΔt)²) for the highest modes).
#[test]
fn modal_simulation_reproduces_the_table_and_the_series() {
    let beam = fryba();
    let d_st = ss_midspan_static_deflection(FORCE, beam.length, beam.bending_stiffness);
    for (alpha, passage, free) in [
        (0.5, 1.7054, Some(1.3101)),
        (0.618, 1.7317, None),
        (1.0, 1.5481, None),
    ] {
        let (r, case, t1) = simulate(alpha, 40, 1.0);
        let max = r.max_abs_deflection_between(0, 0.0, r.exit_time).unwrap() / d_st;
        eprintln!("modal alpha={alpha}: passage max {max:.6} (table {passage})");
        assert!(
            (max - passage).abs() < 1e-4,
            "alpha {alpha}: {max} vs {passage}"
        );
        if let Some(free) = free {
            let fmax = r
                .max_abs_deflection_between(0, r.exit_time, r.exit_time + t1)
                .unwrap()
                / d_st;
            eprintln!("modal alpha={alpha}: free max {fmax:.6} (table {free})");
            assert!(
                (fmax - free).abs() < 1e-4,
                "alpha {alpha}: free {fmax} vs {free}"
            );
        }
        let mut worst: f64 = 0.0;
        for (i, &t) in r.times.iter().enumerate().step_by(37) {
            let exact = case.deflection(0.5 * beam.length, t, 40).unwrap();
            worst = worst.max((r.deflection[i] - exact).abs() / d_st);
        }
        eprintln!("modal alpha={alpha}: max |modal - series| / d_st = {worst:e}");
        assert!(
            worst < 1e-6,
            "alpha {alpha}: deviation from series {worst:e}"
        );
    }
}

/// Crawling speed (α = 1e-3): the dynamic maximum tends to δ_st = FL³/(48EI) with a dynamic excess
/// ≈ α (references.md §D1.1 table: 1.0482 at α = 0.05), so tolerance 2e-3; the quasi-static maximum
/// from 50 modes differs from δ_st by the modal truncation Σ_(j>50) 96/(π⁴j⁴) ≈ 3e-6 (tolerance
/// 1e-5); the midspan bending moment tends to FL/4, converging like 1/j² (truncation
/// (8/π²)Σ_(j>50, odd) 1/j² ≈ 8e-3, tolerance 1.5e-2).
#[test]
fn crawling_speed_gives_the_static_values() {
    let beam = fryba();
    let t1 = period_1(&beam);
    let basis = AnalyticBeam::new(Support::SimplySupported, beam, 50).unwrap();
    let c = speed_for_parameter(&beam, 1e-3).unwrap();
    let loads = MovingLoads::single(FORCE, c).unwrap();
    let settings = MovingLoadSettings::new(t1 / 40.0, 0.0);
    let r =
        simulate_moving_loads(&basis, &ModalDamping::Undamped, &loads, &settings, &[12.5]).unwrap();
    let d_st = ss_midspan_static_deflection(FORCE, beam.length, beam.bending_stiffness);
    let dyn_ratio = r.max_abs_deflection(0).unwrap() / d_st;
    let static_ratio = r.max_abs_quasi_static(0).unwrap() / d_st;
    let moment_ratio = r.max_abs_bending_moment(0).unwrap() / (FORCE * beam.length / 4.0);
    eprintln!(
        "crawl: dyn/d_st {dyn_ratio:.6}, quasi-static/d_st {static_ratio:.8}, M/(FL/4) {moment_ratio:.5}"
    );
    assert!((dyn_ratio - 1.0).abs() < 2e-3);
    assert!((static_ratio - 1.0).abs() < 1e-5);
    assert!((moment_ratio - 1.0).abs() < 1.5e-2);
}

/// The amplification factor against the same-basis static maximum reproduces the table at α = 0.5
/// (the quasi-static maximum of 40 modes equals δ_st to ≈ 3e-6, so the same 1e-4 tolerance).
#[test]
fn dynamic_amplification_factor() {
    let (r, _, _) = simulate(0.5, 40, 0.0);
    let daf = r.dynamic_amplification(0).unwrap();
    eprintln!("DAF alpha=0.5: {daf:.6}");
    assert!((daf - 1.7054).abs() < 1e-4, "{daf}");
}

/// A train of three axles (offsets 0, 7.5, 18 m; forces 1, 0.6, 1.4 F) at α = 0.3 against the
/// superposed closed-form series Σ_k w(t − d_k/c) (zero before an axle enters, free vibration
/// after it leaves): 1e-6 of δ_st as in the single-force comparison.
#[test]
fn axle_train_matches_superposed_series() {
    let beam = fryba();
    let t1 = period_1(&beam);
    let c = speed_for_parameter(&beam, 0.3).unwrap();
    let axles = vec![
        Axle {
            offset: 0.0,
            force: FORCE,
        },
        Axle {
            offset: 7.5,
            force: 0.6 * FORCE,
        },
        Axle {
            offset: 18.0,
            force: 1.4 * FORCE,
        },
    ];
    let loads = MovingLoads::train(axles.clone(), c).unwrap();
    let basis = AnalyticBeam::new(Support::SimplySupported, beam, 30).unwrap();
    let settings = MovingLoadSettings {
        output_every: 10,
        ..MovingLoadSettings::new(t1 / 6000.0, 0.5 * t1)
    };
    let points = [6.25, 12.5];
    let r =
        simulate_moving_loads(&basis, &ModalDamping::Undamped, &loads, &settings, &points).unwrap();
    assert!((r.exit_time - (25.0 + 18.0) / c).abs() < 1e-12);
    let d_st = ss_midspan_static_deflection(FORCE, beam.length, beam.bending_stiffness);
    let mut worst: f64 = 0.0;
    for (i, &t) in r.times.iter().enumerate().step_by(13) {
        for (p, &x) in points.iter().enumerate() {
            let mut exact = 0.0;
            for a in &axles {
                let t_local = t - a.offset / c;
                if t_local >= 0.0 {
                    exact += SsMovingForce::new(beam, a.force, c)
                        .unwrap()
                        .deflection(x, t_local, 30)
                        .unwrap();
                }
            }
            worst = worst.max((r.deflection[i * 2 + p] - exact).abs() / d_st);
        }
    }
    eprintln!("train: max |modal - superposed series| / d_st = {worst:e}");
    assert!(worst < 1e-6, "{worst:e}");
}

/// The recorded acceleration (q̈ from the modal equations) against a central difference of the
/// recorded velocity: O(Δt²) agreement, tolerance 2e-3 of max|ẅ| for Δt = T₁/6000 with 10 modes
/// (highest mode period T₁/100, i.e. 60 steps per period: (2π/60)²/6 ≈ 2e-3 of that mode's part,
/// which is small in the total); damped (ζ = 2 %) to exercise the damping term.
#[test]
fn acceleration_is_consistent_with_velocity() {
    let beam = fryba();
    let t1 = period_1(&beam);
    let basis = AnalyticBeam::new(Support::SimplySupported, beam, 10).unwrap();
    let c = speed_for_parameter(&beam, 0.4).unwrap();
    let loads = MovingLoads::single(FORCE, c).unwrap();
    let settings = MovingLoadSettings::new(t1 / 6000.0, 0.3 * t1);
    let r = simulate_moving_loads(
        &basis,
        &ModalDamping::Uniform(0.02),
        &loads,
        &settings,
        &[10.0],
    )
    .unwrap();
    let dt = t1 / 6000.0;
    let amax = r.max_abs_acceleration(0).unwrap();
    let mut worst: f64 = 0.0;
    for i in 1..r.times.len() - 1 {
        let fd = (r.velocity[i + 1] - r.velocity[i - 1]) / (2.0 * dt);
        worst = worst.max((fd - r.acceleration[i]).abs());
    }
    eprintln!("acceleration vs d(velocity)/dt: {:e} of max", worst / amax);
    assert!(worst < 2e-3 * amax, "{worst} vs {amax}");
}

#[test]
fn invalid_moving_loads_are_rejected() {
    assert!(MovingLoads::single(FORCE, 0.0).is_err());
    assert!(MovingLoads::single(f64::NAN, 10.0).is_err());
    assert!(
        MovingLoads::train(
            vec![Axle {
                offset: -1.0,
                force: 1.0
            }],
            10.0
        )
        .is_err()
    );
    assert!(MovingLoads::train(vec![], 10.0).is_err());
    let basis = AnalyticBeam::new(Support::SimplySupported, fryba(), 3).unwrap();
    let loads = MovingLoads::single(FORCE, 20.0).unwrap();
    let bad_dt = MovingLoadSettings::new(-1.0, 0.0);
    assert!(
        simulate_moving_loads(&basis, &ModalDamping::Undamped, &loads, &bad_dt, &[1.0]).is_err()
    );
    let ok = MovingLoadSettings::new(1e-3, 0.0);
    assert!(simulate_moving_loads(&basis, &ModalDamping::Undamped, &loads, &ok, &[30.0]).is_err());
    assert!(
        simulate_moving_loads(&basis, &ModalDamping::Uniform(-0.1), &loads, &ok, &[1.0]).is_err()
    );
}

/// A time step that would need more than `MAX_STEPS` steps is rejected, not allocated.
#[test]
fn absurd_time_step_is_rejected() {
    let basis = AnalyticBeam::new(Support::SimplySupported, fryba(), 2).unwrap();
    let loads = MovingLoads::single(FORCE, 20.0).unwrap();
    let settings = MovingLoadSettings::new(1e-300, 0.0);
    assert!(
        simulate_moving_loads(&basis, &ModalDamping::Undamped, &loads, &settings, &[1.0]).is_err()
    );
}

/// Yang–Yau–Hsu cancellation (references.md §D1.1): for equally spaced axles (spacing d) at the
/// mode-1 resonance speed v = f₁ d, the free vibration left by each axle vanishes when
/// L/d = k + ½. A 10-axle train at resonance: with L/d = 1.5 the residual free vibration of
/// the midspan must be below 5 % of that with L/d = 2 (where each axle leaves ≈ 0.52 δ_st, table
/// at α = 0.25, and the residuals add up; with cancellation only the higher modes remain,
/// ≈ 0.3 % of δ_st per axle for mode 3). At L/d = 2 (α = d/(2L) = 0.25) all modes are
/// commensurate with the axle period (ω_j = j²ω₁), so the residuals of the 10 axles add in phase:
/// 10 × 0.5237 δ_st (table), tolerance 2e-3 (table rounding ×10 plus 5-mode truncation).
#[test]
fn resonant_train_cancellation() {
    let beam = fryba();
    let basis = AnalyticBeam::new(Support::SimplySupported, beam, 5).unwrap();
    let f1 = basis.circular_frequencies()[0] / (2.0 * PI);
    let t1 = 1.0 / f1;
    let residual = |l_over_d: f64| {
        let d = beam.length / l_over_d;
        let axles = (0..10)
            .map(|k| Axle {
                offset: k as f64 * d,
                force: FORCE,
            })
            .collect();
        let loads = MovingLoads::train(axles, f1 * d).unwrap();
        let settings = MovingLoadSettings::new(t1 / 2000.0, 2.0 * t1);
        let r = simulate_moving_loads(&basis, &ModalDamping::Undamped, &loads, &settings, &[12.5])
            .unwrap();
        r.max_abs_deflection_between(0, r.exit_time, r.exit_time + 2.0 * t1)
            .unwrap()
    };
    let (cancelled, resonant) = (residual(1.5), residual(2.0));
    let d_st = ss_midspan_static_deflection(FORCE, beam.length, beam.bending_stiffness);
    eprintln!(
        "train: residual/d_st L/d=1.5 {:.4}, L/d=2 {:.4}",
        cancelled / d_st,
        resonant / d_st
    );
    assert!(cancelled < 0.05 * resonant);
    assert!(
        (resonant / d_st - 10.0 * 0.5237).abs() < 2e-3,
        "{}",
        resonant / d_st
    );
}

/// An observer that stops the run after step 137 (of a run recorded every 10th step): the
/// response ends at t = 137 Δt with `completed = false`, the stop step is recorded although
/// 137 is not a multiple of 10, and every recorded sample equals the uninterrupted run's
/// sample at the same time (stopping changes no number), for the exact modal step and for
/// Newmark.
#[test]
fn observer_stops_the_run_after_a_step() {
    use std::ops::ControlFlow;
    let beam = fryba();
    let basis = AnalyticBeam::new(Support::SimplySupported, beam, 8).unwrap();
    let loads = MovingLoads::single(FORCE, 30.0).unwrap();
    for integrator in [
        beam::ModalIntegrator::ExactPiecewiseLinear,
        beam::ModalIntegrator::Structural(integrate::StructuralMethod::average_acceleration()),
    ] {
        let settings = MovingLoadSettings {
            output_every: 10,
            integrator,
            ..MovingLoadSettings::new(1e-3, 0.5)
        };
        let full = simulate_moving_loads(
            &basis,
            &ModalDamping::Undamped,
            &loads,
            &settings,
            &[12.5, 5.0],
        )
        .unwrap();
        assert!(full.completed);
        let mut calls = 0;
        let part = beam::simulate_moving_loads_observed(
            &basis,
            &ModalDamping::Undamped,
            &loads,
            &settings,
            &[12.5, 5.0],
            &mut |p| {
                calls += 1;
                assert_eq!(p.step, calls);
                if p.step == 137 {
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(())
                }
            },
        )
        .unwrap();
        assert!(!part.completed);
        assert_eq!(calls, 137);
        // Samples at steps 0, 10, …, 130 and the stop step 137.
        assert_eq!(part.times.len(), 15);
        let t_end = *part.times.last().unwrap();
        assert!((t_end - 0.137).abs() < 1e-12, "{t_end}");
        for (i, t) in part.times[..14].iter().enumerate() {
            assert_eq!(*t, full.times[i]);
            for p in 0..2 {
                assert_eq!(part.deflection[2 * i + p], full.deflection[2 * i + p]);
                assert_eq!(
                    part.bending_moment[2 * i + p],
                    full.bending_moment[2 * i + p]
                );
            }
        }
        assert!(part.deflection[28].abs() > 0.0);
    }
}

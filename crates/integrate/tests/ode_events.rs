//! Events and contact: free-fall impact time, the Hertz impact of a steel ball on a steel
//! half-space (references.md §D1.4, closed form computed here from the formulas) and a
//! multi-bounce drop that an adaptive implicit method must not step over.

use integrate::ode::{Direction, Event, Method, OdeOptions, OdeSystem, Output, solve};

const G: f64 = 9.81;

/// Free fall `z' = v, v' = −g`.
struct FreeFall;

impl OdeSystem for FreeFall {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = y[1];
        dydt[1] = -G;
    }
}

/// Rigid steel ball (R = 10 mm, ρ = 7850 kg/m³) on a steel half-space (E = 210 GPa, ν = 0.3):
/// state (z, v) with z the gap below the ball (negative = approach δ = −z), Hertz force
/// `F = (4/3) E* √R δ^{3/2}` (Johnson 1985 §11.4), optional gravity.
struct HertzBall {
    mass: f64,
    stiffness: f64,
    gravity: f64,
}

impl HertzBall {
    const RADIUS: f64 = 0.01;

    fn steel(gravity: f64) -> Self {
        let (e, nu, rho) = (210e9, 0.3, 7850.0);
        let e_star = e / (1.0 - nu * nu);
        let mass = 4.0 / 3.0 * std::f64::consts::PI * Self::RADIUS.powi(3) * rho;
        Self {
            mass,
            stiffness: 4.0 / 3.0 * e_star * Self::RADIUS.sqrt(),
            gravity,
        }
    }

    fn force(&self, z: f64) -> f64 {
        if z < 0.0 {
            self.stiffness * (-z).powf(1.5)
        } else {
            0.0
        }
    }

    /// Closed form (references.md §D1.4): δ* = (15 m v²/(16 E* √R))^{2/5}, F* = (4/3)E*√R δ*^{3/2},
    /// t_c = 2.9432 δ*/v.
    fn closed_form(&self, v: f64) -> (f64, f64, f64) {
        // (4/3) E* √R = stiffness, so 16 E* √R / 15 = (4/5) stiffness.
        let delta = (self.mass * v * v / (0.8 * self.stiffness)).powf(0.4);
        (delta, self.stiffness * delta.powf(1.5), 2.9432 * delta / v)
    }
}

impl OdeSystem for HertzBall {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = y[1];
        dydt[1] = self.force(y[0]) / self.mass - self.gravity;
    }
}

/// The impact time of a free fall from h is √(2h/g): located by a terminal falling event on
/// z = 0 to 1e-10 (the solution is a parabola, which every method used here integrates
/// exactly up to round-off; the root finder stops at a 4ε bracket).
#[test]
fn free_fall_impact_time_to_1e_10() {
    let h = 1.0;
    let exact = (2.0 * h / G).sqrt();
    let cases = [
        (Method::Dopri5, OdeOptions::adaptive(1e-8, 1e-10)),
        (Method::Radau5, OdeOptions::adaptive(1e-8, 1e-10)),
        (Method::Rk4, OdeOptions::fixed(0.01)),
        (Method::Adams, OdeOptions::fixed(0.01)),
    ];
    for (method, opts) in cases {
        let mut stepper = method.build(2, &opts).unwrap();
        let mut events = [Event::new(|_t, y: &[f64]| y[0])
            .direction(Direction::Falling)
            .terminal()];
        let sol = solve(
            stepper.as_mut(),
            &mut FreeFall,
            (0.0, &[h, 0.0]),
            10.0,
            &mut events,
            &Output::Final,
        )
        .unwrap();
        assert!(sol.terminated);
        let t_hit = sol.events[0].t;
        eprintln!(
            "{}: impact at {t_hit:.15}, error {:.2e}",
            method.name(),
            (t_hit - exact).abs()
        );
        assert!(
            (t_hit - exact).abs() < 1e-10,
            "{}: {t_hit} vs {exact}",
            method.name()
        );
        assert_eq!(*sol.t.last().unwrap(), t_hit);
        // The state at the event is the impact state: z = 0, v = −g t.
        assert!(sol.events[0].y[0].abs() < 1e-10 && (sol.events[0].y[1] + G * exact).abs() < 1e-9);
    }
}

/// Hertz impact at V = 1 m/s from a gap of 0.1 mm, gravity off (the closed form has none):
/// contact start and end events, maximum approach at v = 0, peak force and contact duration
/// within 0.1 % of the closed form (references.md §R5.1; the constant 2.9432 has 5 digits), and
/// the rebound speed equal to the impact speed within 1e-4 (elastic: energy conserved).
#[test]
fn hertz_impact_matches_closed_form_for_dopri5_radau5_bdf() {
    let v0 = 1.0;
    let gap = 1e-4;
    let ball = HertzBall::steel(0.0);
    let (delta_star, force_star, t_contact) = ball.closed_form(v0);
    eprintln!(
        "closed form: δ* = {delta_star:.6e} m, F* = {force_star:.3} N, t_c = {t_contact:.6e} s"
    );
    // Sanity against the rounded published numbers (17.795 µm, 2309.8 N, 52.37 µs).
    assert!(
        (delta_star / 17.795e-6 - 1.0).abs() < 1e-3 && (force_star / 2309.8 - 1.0).abs() < 1e-3
    );
    assert!((t_contact / 52.37e-6 - 1.0).abs() < 1e-3);
    for method in [Method::Dopri5, Method::Radau5, Method::Bdf] {
        let mut ball = HertzBall::steel(0.0);
        let opts = OdeOptions {
            rtol: 1e-10,
            atol: 1e-15,
            ..OdeOptions::default()
        };
        let mut stepper = method.build(2, &opts).unwrap();
        let mut events = [
            Event::new(|_t, y: &[f64]| y[0])
                .direction(Direction::Falling)
                .guard(t_contact / 50.0)
                .unwrap(),
            Event::new(|_t, y: &[f64]| y[1]).direction(Direction::Rising),
            Event::new(|_t, y: &[f64]| y[0])
                .direction(Direction::Rising)
                .terminal(),
        ];
        let sol = solve(
            stepper.as_mut(),
            &mut ball,
            (0.0, &[gap, -v0]),
            1.0,
            &mut events,
            &Output::Final,
        )
        .unwrap();
        assert!(sol.terminated, "{}: contact did not end", method.name());
        let find = |i: usize| {
            sol.events
                .iter()
                .find(|e| e.index == i)
                .unwrap_or_else(|| panic!("event {i}"))
        };
        let (start, max_approach, end) = (find(0), find(1), find(2));
        let delta = -max_approach.y[0];
        let force = ball.force(max_approach.y[0]);
        let duration = end.t - start.t;
        let rebound = end.y[1];
        eprintln!(
            "{}: start {:.3e} (exact {gap:e}), δ* {:.3e} (rel {:.1e}), F* {:.2} (rel {:.1e}), t_c rel {:.1e}, rebound {rebound:.10} | {:?}, guard retries {}",
            method.name(),
            start.t,
            delta,
            delta / delta_star - 1.0,
            force,
            force / force_star - 1.0,
            duration / t_contact - 1.0,
            sol.stats,
            sol.guard_retries
        );
        assert!(
            (start.t - gap / v0).abs() < 1e-12,
            "free flight to contact is linear"
        );
        assert!((delta / delta_star - 1.0).abs() < 1e-3);
        assert!((force / force_star - 1.0).abs() < 1e-3);
        assert!((duration / t_contact - 1.0).abs() < 1e-3);
        assert!(
            (rebound - v0).abs() < 1e-4,
            "{}: rebound {rebound}",
            method.name()
        );
    }
}

/// Counts bounces of a drop from 0.1 m over 1 s with gravity; returns the rebound speeds at
/// the contact-end events and the impact speeds at the contact-start events.
fn drop_bounces(method: Method, rtol: f64, guard: Option<f64>) -> (Vec<f64>, Vec<f64>) {
    let mut ball = HertzBall::steel(G);
    let opts = OdeOptions {
        rtol,
        atol: rtol * 1e-6,
        ..OdeOptions::default()
    };
    let mut stepper = method.build(2, &opts).unwrap();
    let start = Event::new(|_t, y: &[f64]| y[0]).direction(Direction::Falling);
    let start = match guard {
        Some(h) => start.guard(h).unwrap(),
        None => start,
    };
    let mut events = [
        start,
        Event::new(|_t, y: &[f64]| y[0]).direction(Direction::Rising),
    ];
    let sol = solve(
        stepper.as_mut(),
        &mut ball,
        (0.0, &[0.1, 0.0]),
        1.0,
        &mut events,
        &Output::Final,
    )
    .unwrap();
    let speeds = |i: usize| {
        sol.events
            .iter()
            .filter(|e| e.index == i)
            .map(|e| e.y[1].abs())
            .collect::<Vec<_>>()
    };
    eprintln!(
        "{} rtol {rtol:e} guard {guard:?}: {:?}, retries {}",
        method.name(),
        sol.stats,
        sol.guard_retries
    );
    (speeds(0), speeds(1))
}

/// Drop from 0.1 m for 1 s: impacts at t_k = t_f (1 + 2k) + k t_c with t_f = √(2h/g) =
/// 0.1428 s, i.e. 4 impacts (0.143, 0.428, 0.714, 0.9996 s, the last contact ending 50 µs
/// before 1 s). Radau5 at rtol 1e-6 with the contact guard (h_c = t_c/50) must see all four
/// bounces, each rebounding with the impact speed √(2gh) = 1.4007 m/s within 1 % (Radau5 is
/// slightly dissipative; 1 % bounds the energy loss over 4 contacts at this tolerance).
#[test]
fn radau5_does_not_skip_bounces_of_a_drop() {
    let ball = HertzBall::steel(G);
    let v_impact = (2.0 * G * 0.1f64).sqrt();
    let (_, _, t_contact) = ball.closed_form(v_impact);
    let (impacts, rebounds) = drop_bounces(Method::Radau5, 1e-6, Some(t_contact / 50.0));
    eprintln!("impacts {impacts:?}\nrebounds {rebounds:?}");
    assert_eq!(impacts.len(), 4, "impacts {impacts:?}");
    assert_eq!(rebounds.len(), 4, "rebounds {rebounds:?}");
    for (vi, vr) in impacts.iter().zip(&rebounds) {
        assert!((vi / v_impact - 1.0).abs() < 1e-2, "impact speed {vi}");
        assert!((vr / v_impact - 1.0).abs() < 1e-2, "rebound speed {vr}");
    }
}

/// The guard at loose tolerances: with it, Radau5 and DOPRI5 see all four bounces at
/// rtol 1e-2 … 1e-5 with speeds within 1 % of √(2gh) (each run undoes one entering step per
/// bounce). Without it, Radau5 at rtol 1e-2 steps over a bounce (measured: 3 impacts), which
/// is the failure the guard exists for (cf. scipy's Radau on the ball drop).
#[test]
fn contact_guard_keeps_every_bounce_at_loose_tolerances() {
    let v_impact = (2.0 * G * 0.1f64).sqrt();
    let (_, _, t_contact) = HertzBall::steel(G).closed_form(v_impact);
    for method in [Method::Radau5, Method::Dopri5] {
        for rtol in [1e-2, 1e-3, 1e-4, 1e-5] {
            let (impacts, rebounds) = drop_bounces(method, rtol, Some(t_contact / 50.0));
            assert_eq!(
                (impacts.len(), rebounds.len()),
                (4, 4),
                "{} rtol {rtol}",
                method.name()
            );
            for v in impacts.iter().chain(&rebounds) {
                assert!(
                    (v / v_impact - 1.0).abs() < 1e-2,
                    "{} rtol {rtol}: speed {v}",
                    method.name()
                );
            }
        }
    }
    let (impacts, _) = drop_bounces(Method::Radau5, 1e-2, None);
    assert!(
        impacts.len() < 4,
        "unguarded Radau5 at rtol 1e-2 now sees every bounce: {impacts:?}"
    );
}

/// Harmonic oscillator `q' = p, p' = −q` from (1, 0): q = cos t crosses zero falling at
/// π/2 + 2kπ and rising at 3π/2 + 2kπ. Several crossings per run, directions filtered, times
/// located on Radau5's and DOPRI5's dense output to 1e-8 (rtol 1e-10; the dense output is
/// accurate to about the tolerance, the root finder to round-off).
#[test]
fn oscillator_zero_crossings_by_direction() {
    struct Oscillator;
    impl OdeSystem for Oscillator {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dydt: &mut [f64]) {
            dydt[0] = y[1];
            dydt[1] = -y[0];
        }
    }
    use std::f64::consts::PI;
    for method in [Method::Radau5, Method::Dopri5, Method::Bdf] {
        let mut stepper = method
            .build(2, &OdeOptions::adaptive(1e-10, 1e-12))
            .unwrap();
        let mut events = [
            Event::new(|_t, y: &[f64]| y[0]).direction(Direction::Falling),
            Event::new(|_t, y: &[f64]| y[0]).direction(Direction::Rising),
            Event::new(|_t, y: &[f64]| y[1]),
        ];
        let sol = solve(
            stepper.as_mut(),
            &mut Oscillator,
            (0.0, &[1.0, 0.0]),
            20.0,
            &mut events,
            &Output::Final,
        )
        .unwrap();
        let times = |i: usize| {
            sol.events
                .iter()
                .filter(|e| e.index == i)
                .map(|e| e.t)
                .collect::<Vec<_>>()
        };
        let falling: Vec<f64> = (0..4)
            .map(|k| PI / 2.0 + 2.0 * PI * k as f64)
            .filter(|&t| t < 20.0)
            .collect();
        let rising: Vec<f64> = (0..4)
            .map(|k| 1.5 * PI + 2.0 * PI * k as f64)
            .filter(|&t| t < 20.0)
            .collect();
        // p = −sin t is zero at kπ, both directions (t = 0 itself is the start, not a crossing).
        let both: Vec<f64> = (1..7)
            .map(|k| PI * k as f64)
            .filter(|&t| t < 20.0)
            .collect();
        let tol = if method == Method::Bdf { 1e-7 } else { 1e-8 };
        for (i, expected) in [(0, falling), (1, rising), (2, both)] {
            let found = times(i);
            assert_eq!(
                found.len(),
                expected.len(),
                "{} event {i}: {found:?}",
                method.name()
            );
            for (a, b) in found.iter().zip(&expected) {
                assert!(
                    (a - b).abs() < tol,
                    "{} event {i}: {a} vs {b}",
                    method.name()
                );
            }
        }
        assert!(
            sol.events.windows(2).all(|w| w[0].t <= w[1].t),
            "events in time order"
        );
    }
}

/// An outer loop with a terminal event and a state change between steps: a ball dropped from
/// h bounces with restitution e (v ← −e v at z = 0, restart with `set_state` via `solve`).
/// Impact times t₁ = √(2h/g), t_{k+1} = t_k + 2 e^k v₁/g with v₁ = √(2gh); located to 1e-10
/// (free flight is a parabola, integrated exactly).
#[test]
fn bouncing_ball_with_restitution_via_restarts() {
    let (h, e): (f64, f64) = (1.0, 0.8);
    let v1 = (2.0 * G * h).sqrt();
    let mut expected = vec![(2.0 * h / G).sqrt()];
    for k in 1..5 {
        let last = *expected.last().unwrap();
        expected.push(last + 2.0 * e.powi(k) * v1 / G);
    }
    let mut stepper = Method::Dopri5
        .build(2, &OdeOptions::adaptive(1e-10, 1e-12))
        .unwrap();
    let (mut t, mut y) = (0.0, vec![h, 0.0]);
    for (k, t_expected) in expected.iter().enumerate() {
        let mut events = [Event::new(|_t, y: &[f64]| y[0])
            .direction(Direction::Falling)
            .terminal()];
        let sol = solve(
            stepper.as_mut(),
            &mut FreeFall,
            (t, &y),
            100.0,
            &mut events,
            &Output::Final,
        )
        .unwrap();
        assert!(sol.terminated);
        let hit = &sol.events[0];
        assert!(
            (hit.t - t_expected).abs() < 1e-10,
            "bounce {k}: {} vs {t_expected}",
            hit.t
        );
        t = hit.t;
        y = vec![0.0, -e * hit.y[1]];
        // The restart at z = 0 moving up is not a crossing: a falling crossing needs g > 0
        // before it.
        assert!(y[1] > 0.0);
    }
}

/// An observer that breaks once t ≥ 0.305 stops the free fall at the first accepted step past
/// it (fixed step 0.01 s: t = 0.31 s up to round-off), with the state of the exact parabola
/// z = h − g t²/2, v = −g t (which RK4 integrates exactly) and `stopped` set; the observer is
/// called once per step.
#[test]
fn observer_stops_the_run_at_the_next_step() {
    use std::ops::ControlFlow;
    let h = 1.0;
    let mut stepper = Method::Rk4.build(2, &OdeOptions::fixed(0.01)).unwrap();
    let mut calls = 0;
    for output in [Output::Final, Output::Steps] {
        calls = 0;
        let sol = integrate::ode::solve_observed(
            stepper.as_mut(),
            &mut FreeFall,
            (0.0, &[h, 0.0]),
            10.0,
            &mut [],
            &output,
            &mut |t, _y| {
                calls += 1;
                if t >= 0.305 {
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(())
                }
            },
        )
        .unwrap();
        assert!(sol.stopped && !sol.terminated);
        let (t, y) = (*sol.t.last().unwrap(), sol.y.last().unwrap());
        assert!((t - 0.31).abs() < 1e-12, "{t}");
        assert!((y[0] - (h - 0.5 * G * t * t)).abs() < 1e-12, "{y:?}");
        assert!((y[1] + G * t).abs() < 1e-12, "{y:?}");
        assert_eq!(sol.stats.steps, 31);
    }
    assert_eq!(calls, 31);
    // Without a break the run reaches t_end and is not marked stopped.
    let sol = solve(
        stepper.as_mut(),
        &mut FreeFall,
        (0.0, &[h, 0.0]),
        0.1,
        &mut [],
        &Output::Final,
    )
    .unwrap();
    assert!(!sol.stopped && (sol.t[0] - 0.1).abs() < 1e-12);
}

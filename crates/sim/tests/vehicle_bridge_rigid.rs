//! Rigid wheel–rail contact with every integrator, including the trapezoidal rule
//! (Newmark β = ¼, γ = ½, no numerical damping): the moving mass against an independent
//! glued-mass modal integration, the quarter car against a tight generalized-α run, and loss
//! of contact / re-contact against free flight (issue #9 item 2).

use beam::{AnalyticBeam, Derivative, ModalBasis, ModalDamping, Support, UniformBeam};
use integrate::structural::StructuralMethod;
use sim::vehicle_bridge::{
    ContactGeometry, ContactModel, CouplingSpec, GRAVITY, Integrator, Irregularity, Scenario,
    Simulation, WheelSpec,
};

/// The Biggs / Yang–Yau bridge (references.md §D1.3): EI = 8.323e9 N m², ρA = 2303 kg/m.
const EI: f64 = 8.323e9;
const RHO_A: f64 = 2303.0;

fn basis(length: f64, modes: usize) -> AnalyticBeam {
    AnalyticBeam::new(
        Support::SimplySupported,
        UniformBeam::new(length, EI, RHO_A).unwrap(),
        modes,
    )
    .unwrap()
}

fn scenario(
    length: f64,
    modes: usize,
    wheel: WheelSpec,
    speed: f64,
    method: StructuralMethod,
    dt: f64,
) -> Scenario {
    Scenario {
        moving_forces: Vec::new(),
        bridge: Box::new(basis(length, modes)),
        damping: ModalDamping::Undamped,
        wheels: vec![wheel],
        speed,
        contact: ContactModel::Rigid,
        geometry: ContactGeometry {
            wheel_radius: 0.46,
            rail_profile_radius: 0.3,
            youngs_modulus: 210e9,
            poisson_ratio: 0.3,
        },
        irregularity: Irregularity::None,
        integrator: Integrator::Structural(method),
        dt,
        duration: None,
        coupling: CouplingSpec::default(),
        gravity: GRAVITY,
        output_point: 0.5 * length,
    }
}

/// The quarter car of issue #9: 600 kg wheel, 5750 kg body on 1595 kN/m and 20 kN s/m.
fn quarter_car() -> WheelSpec {
    WheelSpec {
        position: 0.0,
        wheel_mass: 600.0,
        body_mass: 5750.0,
        suspension_stiffness: 1595e3,
        suspension_damping: 2e4,
        static_load: 0.0,
    }
}

/// One run: (t, midspan deflection, contact force, wheel displacement) per step, and the
/// loss-of-contact events.
struct History {
    t: Vec<f64>,
    w_mid: Vec<f64>,
    force: Vec<f64>,
    z_wheel: Vec<f64>,
    losses: usize,
}

fn run(sc: Scenario) -> History {
    let mut sim = Simulation::new(sc).unwrap();
    let mut h = History {
        t: vec![sim.t()],
        w_mid: vec![sim.output_point_response().0],
        force: vec![sim.wheels()[0].contact.force],
        z_wheel: vec![sim.wheels()[0].wheel_displacement],
        losses: 0,
    };
    sim.run(|s| {
        h.t.push(s.t());
        h.w_mid.push(s.output_point_response().0);
        h.force.push(s.wheels()[0].contact.force);
        h.z_wheel.push(s.wheels()[0].wheel_displacement);
    })
    .unwrap();
    h.losses = sim.loss_of_contact_events();
    h
}

/// Largest second difference max |F_{n+1} − 2F_n + F_{n−1}| (the 2Δt ringing indicator).
fn ringing(f: &[f64]) -> f64 {
    f.windows(3)
        .map(|w| (w[2] - 2.0 * w[1] + w[0]).abs())
        .fold(0.0, f64::max)
}

/// The integrators of the step interface: the trapezoidal rule, HHT-α, generalized-α and
/// backward Euler.
fn integrators() -> Vec<(&'static str, StructuralMethod)> {
    vec![
        ("trapezoidal", StructuralMethod::average_acceleration()),
        ("hht(-0.1)", StructuralMethod::hht(-0.1).unwrap()),
        (
            "generalized_alpha(0.8)",
            StructuralMethod::generalized_alpha(0.8).unwrap(),
        ),
        ("backward_euler", StructuralMethod::BackwardEuler),
    ]
}

/// The glued-mass modal equations of a rigid moving mass m on a smooth rail
/// (references.md §D1.2), independent of the simulation: with φ, φ', φ'' the mode shapes,
/// slopes and curvatures at x = c t (zero off the span),
/// `(I + m φφᵀ) q̈ + 2c m φφ'ᵀ q̇ + c² m φφ''ᵀ q + Ω² q = m g φ`,
/// solved for q̈ by Gaussian elimination of the dense m × m matrix; returns (q̈, z̈_w) with
/// the wheel's acceleration z̈_w = φ·q̈ + 2c φ'·q̇ + c² φ''·q.
fn glued_mass_acceleration(
    b: &AnalyticBeam,
    mass: f64,
    c: f64,
    t: f64,
    q: &[f64],
    v: &[f64],
) -> (Vec<f64>, f64) {
    let n = q.len();
    let x = c * t;
    let (mut phi, mut d1, mut d2) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    if (0.0..=b.length()).contains(&x) {
        b.eval_all(x, Derivative::Shape, &mut phi).unwrap();
        b.eval_all(x, Derivative::Slope, &mut d1).unwrap();
        b.eval_all(x, Derivative::Curvature, &mut d2).unwrap();
    }
    let om = b.circular_frequencies();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let conv = 2.0 * c * dot(&d1, v) + c * c * dot(&d2, q);
    // Dense [A | f], A = I + m φφᵀ, f = m g φ − m φ conv − Ω² q.
    let mut a = vec![0.0; n * (n + 1)];
    for i in 0..n {
        for j in 0..n {
            a[i * (n + 1) + j] = mass * phi[i] * phi[j] + if i == j { 1.0 } else { 0.0 };
        }
        a[i * (n + 1) + n] = mass * GRAVITY * phi[i] - mass * phi[i] * conv - om[i] * om[i] * q[i];
    }
    for col in 0..n {
        let p = (col..n)
            .max_by(|&r, &s| {
                a[r * (n + 1) + col]
                    .abs()
                    .total_cmp(&a[s * (n + 1) + col].abs())
            })
            .unwrap();
        for k in 0..=n {
            a.swap(col * (n + 1) + k, p * (n + 1) + k);
        }
        for r in 0..n {
            if r != col {
                let f = a[r * (n + 1) + col] / a[col * (n + 1) + col];
                for k in col..=n {
                    a[r * (n + 1) + k] -= f * a[col * (n + 1) + k];
                }
            }
        }
    }
    let acc: Vec<f64> = (0..n)
        .map(|i| a[i * (n + 1) + n] / a[i * (n + 1) + i])
        .collect();
    let zdd = dot(&phi, &acc) + conv;
    (acc, zdd)
}

/// Issue #9's heavy moving mass: a rigid wheel of 28 787.5 kg (no body) on the 25 m bridge
/// (12 modes, undamped) at 119.45 m/s, against the glued-mass modal equations integrated by
/// classical RK4 at h = 1.25e-6 s (ω₁₂h < 6e-3: error ≈ 1e-10 of the response). The glued mass
/// would need a pull from t ≈ 0.1965 s on (its force F_ref = m(g − z̈_w) turns negative near
/// the far support): the unilateral rigid contact must release the wheel there, within 5 steps
/// of the zero crossing, and the comparison covers the time before. At Δt = 2e-5 s the
/// former displacement-level multiplier was 3.8e-2 off with the trapezoidal rule; now every
/// second-order integrator must be within 1e-3 of the peak midspan deflection and 1e-2 of the
/// static load mg in the contact force (the force, an acceleration, carries the phase error
/// of the highest mode, ω₁₂Δt = 0.09, which the trapezoidal rule does not damp), backward
/// Euler (first order) within 2e-2 and 1e-1. The trapezoidal rule must converge at second
/// order: halving Δt divides both errors by at least 3.
#[test]
fn heavy_moving_mass_matches_the_glued_mass_equations() {
    let (length, modes, mass, c) = (25.0, 12, 28_787.5, 119.45);
    let b = basis(length, modes);
    let t_end = length / c;
    let h = 1.25e-6;
    let mut mid = vec![0.0; modes];
    b.eval_all(0.5 * length, Derivative::Shape, &mut mid)
        .unwrap();
    let steps = (t_end / h - 1e-9).ceil() as usize;
    // Reference (w_mid, F) at t_i = i h.
    let mut reference = vec![(0.0, mass * GRAVITY)];
    let (mut q, mut v) = (vec![0.0; modes], vec![0.0; modes]);
    let deriv = |t: f64, q: &[f64], v: &[f64]| glued_mass_acceleration(&b, mass, c, t, q, v).0;
    let axpy = |x: &[f64], k: &[f64], s: f64| -> Vec<f64> {
        x.iter().zip(k).map(|(a, b)| a + s * b).collect()
    };
    for i in 0..steps {
        let t = i as f64 * h;
        let (k1q, k1v) = (v.clone(), deriv(t, &q, &v));
        let (q2, v2) = (axpy(&q, &k1q, 0.5 * h), axpy(&v, &k1v, 0.5 * h));
        let (k2q, k2v) = (v2.clone(), deriv(t + 0.5 * h, &q2, &v2));
        let (q3, v3) = (axpy(&q, &k2q, 0.5 * h), axpy(&v, &k2v, 0.5 * h));
        let (k3q, k3v) = (v3.clone(), deriv(t + 0.5 * h, &q3, &v3));
        let (q4, v4) = (axpy(&q, &k3q, h), axpy(&v, &k3v, h));
        let (k4q, k4v) = (v4.clone(), deriv(t + h, &q4, &v4));
        for j in 0..modes {
            q[j] += h / 6.0 * (k1q[j] + 2.0 * k2q[j] + 2.0 * k3q[j] + k4q[j]);
            v[j] += h / 6.0 * (k1v[j] + 2.0 * k2v[j] + 2.0 * k3v[j] + k4v[j]);
        }
        let zdd = glued_mass_acceleration(&b, mass, c, (i + 1) as f64 * h, &q, &v).1;
        let w: f64 = q.iter().zip(&mid).map(|(a, b)| a * b).sum();
        reference.push((w, mass * (GRAVITY - zdd)));
    }
    let pull = reference.iter().position(|r| r.1 < 0.0).unwrap();
    let t_pull = pull as f64 * h;
    let peak = reference[..pull]
        .iter()
        .fold(0.0f64, |m, r| m.max(r.0.abs()));
    let load = mass * GRAVITY;
    let errors = |method: StructuralMethod, dt: f64| {
        let wheel = WheelSpec {
            position: 0.0,
            wheel_mass: mass,
            ..WheelSpec::default()
        };
        let hist = run(scenario(length, modes, wheel, c, method, dt));
        let ratio = (dt / h).round() as usize;
        let (mut e_w, mut e_f) = (0.0f64, 0.0f64);
        for n in 0..hist.t.len() {
            let i = n * ratio;
            if i >= pull {
                break;
            }
            assert!((hist.t[n] - i as f64 * h).abs() < 1e-9);
            e_w = e_w.max((hist.w_mid[n] - reference[i].0).abs());
            e_f = e_f.max((hist.force[n] - reference[i].1).abs());
        }
        let release = hist.force.iter().position(|&f| f == 0.0).map(|n| hist.t[n]);
        (e_w / peak, e_f / load, hist.losses, release)
    };
    let dt = 2e-5;
    for (name, method) in integrators() {
        let (e_w, e_f, losses, release) = errors(method, dt);
        println!(
            "{name}: peak {peak:.4e} m; max error before the pull (t < {t_pull:.5} s): deflection {e_w:.2e} (of peak), force {e_f:.2e} (of mg); losses {losses}, released at {release:?}"
        );
        let (tol_w, tol_f) = if name == "backward_euler" {
            (2e-2, 1e-1)
        } else {
            (1e-3, 1e-2)
        };
        assert!(e_w < tol_w && e_f < tol_f, "{name}: {e_w:e} {e_f:e}");
        assert_eq!(losses, 1, "{name}");
        let release = release.unwrap();
        // The force crosses zero at a slope of about 4e7 N/s: a force error e_f m g moves the
        // release by e_f m g / 4e7 N/s (≈ 2.5 steps at e_f = 7e-3), hence 5 steps.
        assert!((release - t_pull).abs() <= 5.0 * dt, "{name}: {release}");
    }
    let (e_w1, e_f1, _, _) = errors(StructuralMethod::average_acceleration(), dt);
    let (e_w2, e_f2, _, _) = errors(StructuralMethod::average_acceleration(), 0.5 * dt);
    println!(
        "trapezoidal at Δt/2: deflection {e_w2:.2e}, force {e_f2:.2e}; ratios {:.2}, {:.2}",
        e_w1 / e_w2,
        e_f1 / e_f2
    );
    assert!(e_w1 / e_w2 > 3.0 && e_f1 / e_f2 > 3.0);
}

/// Issue #9's quarter car with the trapezoidal rule at Δt = 1 ms (25 m bridge, 12 modes,
/// 30 m/s): no loss of contact, the contact force within 1 % of the static load of a tight
/// generalized-α run (ρ∞ = 0.9, Δt = 1e-5 s, every 100th step), and no 2Δt ringing: the
/// largest second difference |F_{n+1} − 2F_n + F_{n−1}| stays below 5e-3 of the static load
/// W and below 1.5× that of the reference sampled at the same 1 ms (the bridge's higher modes
/// give the true force a second difference of that order; the former displacement-level
/// multiplier had 2.6e4 N = 0.42 W on the 25 m bridge, force 55.0–68.3 kN).
#[test]
fn quarter_car_with_the_trapezoidal_rule_is_smooth() {
    for length in [25.0, 50.0] {
        let quarter_car_run = |method, dt| {
            let mut sc = scenario(length, 12, quarter_car(), 30.0, method, dt);
            // Up to 0.5 m before the far support: the wheel that reaches the support meets the
            // kink of the deflected span (a velocity jump that may throw the wheel off for a moment: docs/vehicle_bridge.md).
            sc.duration = Some((length - 0.5) / 30.0);
            run(sc)
        };
        let coarse = quarter_car_run(StructuralMethod::average_acceleration(), 1e-3);
        let fine = quarter_car_run(StructuralMethod::generalized_alpha(0.9).unwrap(), 1e-5);
        let load = (600.0 + 5750.0) * GRAVITY;
        let mut err = 0.0f64;
        let mut sampled = Vec::new();
        for (n, &f) in coarse.force.iter().enumerate() {
            let i = 100 * n;
            if i >= fine.t.len() || (fine.t[i] - coarse.t[n]).abs() > 1e-9 {
                break;
            }
            err = err.max((f - fine.force[i]).abs());
            sampled.push(fine.force[i]);
        }
        let (fmin, fmax) = coarse
            .force
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &f| (a.min(f), b.max(f)));
        println!(
            "L = {length}: losses {} (reference {}), F in [{fmin:.4e}, {fmax:.4e}] N, max |F − F_ref| = {err:.3e} N ({:.2e} W), ringing {:.3e} N (reference sampled alike {:.3e} N)",
            coarse.losses,
            fine.losses,
            err / load,
            ringing(&coarse.force),
            ringing(&sampled)
        );
        assert_eq!(coarse.losses, 0);
        assert_eq!(fine.losses, 0);
        assert!(err < 1e-2 * load, "{err}");
        let (ring, ring_ref) = (ringing(&coarse.force), ringing(&sampled));
        assert!(
            ring < 5e-3 * load && ring < 1.5 * ring_ref,
            "{ring} vs {ring_ref}"
        );
    }
}

/// Loss of contact and re-contact: a 2000 kg rigid wheel (no body, no extra load) at 30 m/s
/// over a 5 mm deep, 2 m long cosine dip on the bridge (12 modes, undamped, Δt = 1e-4 s). At
/// the dip's start the rail falls away with c² r'' = ½ d (2π/ℓ)² c² = 22 m/s² > g, so the
/// wheel leaves it. With every integrator: at least one loss event; during the first flight
/// the contact force is exactly zero and the wheel is ballistic,
/// z_w(t) = z₀ + ż₀ (t − t₀) + ½ g (t − t₀)² from its state at the last step on the rail, to
/// within g T_flight Δt + 1e-3 of the flight's largest gap (the release lies somewhere in
/// that step; measured 1.5e-5 m of a 1.16e-3 m gap, 0.0306 s flight, all four integrators);
/// the flight times agree between the integrators within 3 steps (measured 306, 306, 306 and
/// 303 steps), and the wheel ends on the rail. The landing is a plastic impact; the bridge's
/// higher modes, excited by it, then make the wheel hop several times more (tens of
/// micro-flights with gaps of ~1e-8 m with the undamped modes; backward Euler damps them and
/// reports 3 events): the repeated impacts of a mass on an elastic beam.
#[test]
fn loss_of_contact_and_landing_with_every_integrator() {
    let dip = Irregularity::Dip {
        position: 10.0,
        length: 2.0,
        depth: 5e-3,
    };
    let dt = 1e-4;
    let mut flights = Vec::new();
    for (name, method) in integrators() {
        let wheel = WheelSpec {
            position: 0.0,
            wheel_mass: 2000.0,
            ..WheelSpec::default()
        };
        let mut sc = scenario(25.0, 12, wheel, 30.0, method, dt);
        sc.irregularity = dip.clone();
        let mut sim = Simulation::new(sc).unwrap();
        let iw = 12;
        // (t, z_w, ż_w, F, gap)
        let mut hist = vec![(
            sim.t(),
            sim.state()[iw],
            sim.velocity()[iw],
            sim.wheels()[0].contact.force,
            sim.wheels()[0].approach,
        )];
        sim.run(|s| {
            hist.push((
                s.t(),
                s.state()[iw],
                s.velocity()[iw],
                s.wheels()[0].contact.force,
                s.wheels()[0].approach,
            ))
        })
        .unwrap();
        let losses = sim.loss_of_contact_events();
        // The flight: the steps with a negative approach (wheel above the rail).
        let first = hist.iter().position(|h| h.4 < -1e-12).expect("no flight");
        // First flight's start: the step before the wheel is seen above the rail.
        let last = first + hist[first..].iter().position(|h| h.4 >= -1e-12).unwrap();
        let (t0, z0, v0, _, _) = hist[first - 1];
        let mut max_gap = 0.0f64;
        let mut dev = 0.0f64;
        for h in &hist[first..last] {
            let tau = h.0 - t0;
            dev = dev.max((h.1 - (z0 + v0 * tau + 0.5 * GRAVITY * tau * tau)).abs());
            max_gap = max_gap.max(-h.4);
            assert_eq!(h.3, 0.0, "{name}: force in flight");
        }
        let flight = hist[last].0 - t0;
        println!(
            "{name}: losses {losses}, flight {:.4} s ({} steps) from x = {:.3} m, largest gap {:.3e} m, deviation from ballistic {:.2e} m ({:.2e} of the gap); final force {:.4e} N",
            flight,
            last - first + 1,
            30.0 * t0,
            max_gap,
            dev,
            dev / max_gap,
            hist.last().unwrap().3
        );
        assert!(losses >= 1, "{name}");
        // The release lies somewhere in the step before the first gap: starting the parabola
        // up to Δt early shifts it by at most g T_flight Δt.
        let tol = GRAVITY * flight * dt + 1e-3 * max_gap;
        assert!(dev < tol, "{name}: {dev} vs {tol}");
        assert!(hist.last().unwrap().3 > 0.0, "{name}: not back on the rail");
        flights.push(flight);
    }
    let spread = flights
        .iter()
        .fold(0.0f64, |m, &f| m.max((f - flights[0]).abs()));
    assert!(spread <= 3.0 * dt + 1e-12, "flight times {flights:?}");
}

/// The rail terms of the constraint (c² r'', c r') against an independent solution: a quarter
/// car on the rigid approach track (no bridge under it) over a 1 mm deep, 1 m long cosine dip
/// at 30 m/s. On a rigid track the wheel follows the rail exactly, z_w = −r(ct), so the body is
/// a base-excited oscillator, integrated here by RK4 (h = 1e-5 s) with the analytic r, r', r'',
/// and the contact force is F = m_w (g − z̈_w) + k_s (z_b − z_w) + c_s (ż_b − ż_w). The force
/// jumps by m_w c² r''(0) = 10.7 kN at each end of the dip (the dip is C¹ only). The
/// simulation's force at Δt = 1e-4 s (the default step) must agree within 1e-3 of the static
/// load W with every integrator, and within 1e-4 W away from the jumps (10 steps after each);
/// measured 1.9e-4 / 2.4e-7 (trapezoidal), 2.1e-4 / 2.1e-7 (HHT), 2.0e-4 / 2.4e-5
/// (generalized-α), 4.8e-4 / 2.3e-5 (backward Euler). The constraint of the α-schemes is
/// α-weighted like their balance (module `rigid`): with the acceleration imposed at t_{n+1}
/// alone, generalized-α's multiplier overshot each jump by (α_f − α_m)/(1 − α_f) = 20 %
/// (2.1 kN) and decayed like ρ∞ⁿ.
#[test]
fn rail_irregularity_on_a_rigid_track_matches_the_base_excited_body() {
    let (m_w, m_b, k_s, c_s) = (600.0, 5750.0, 1595e3, 2e4);
    // (The dip's ends, where r'' jumps, fall between the simulation's steps.)
    let (speed, x0, dip_at, len, depth) = (30.0, -10.0, -6.9805, 1.0, 1e-3);
    let k = std::f64::consts::TAU / len;
    // r, r', r'' of the dip at x.
    let rail = |x: f64| -> (f64, f64, f64) {
        let s = x - dip_at;
        if (0.0..=len).contains(&s) {
            let (sn, cs) = (k * s).sin_cos();
            (
                -0.5 * depth * (1.0 - cs),
                -0.5 * depth * k * sn,
                -0.5 * depth * k * k * cs,
            )
        } else {
            (0.0, 0.0, 0.0)
        }
    };
    let duration: f64 = 0.25;
    // Body ODE y = (z_b, ż_b): m_b z̈_b = m_b g − k_s (z_b − z_w) − c_s (ż_b − ż_w).
    let body = |t: f64, y: [f64; 2]| -> [f64; 2] {
        let (r, r1, _) = rail(x0 + speed * t);
        let (zw, vw) = (-r, -speed * r1);
        [
            y[1],
            GRAVITY - (k_s * (y[0] - zw) + c_s * (y[1] - vw)) / m_b,
        ]
    };
    let force = |t: f64, y: [f64; 2]| -> f64 {
        let (r, r1, r2) = rail(x0 + speed * t);
        let (zw, vw, aw) = (-r, -speed * r1, -speed * speed * r2);
        m_w * (GRAVITY - aw) + k_s * (y[0] - zw) + c_s * (y[1] - vw)
    };
    let h = 1e-5;
    let mut y = [m_b * GRAVITY / k_s, 0.0];
    let mut reference = vec![force(0.0, y)];
    let steps = (duration / h).round() as usize;
    for i in 0..steps {
        let t = i as f64 * h;
        let add = |y: [f64; 2], k: [f64; 2], s: f64| [y[0] + s * k[0], y[1] + s * k[1]];
        let k1 = body(t, y);
        let k2 = body(t + 0.5 * h, add(y, k1, 0.5 * h));
        let k3 = body(t + 0.5 * h, add(y, k2, 0.5 * h));
        let k4 = body(t + h, add(y, k3, h));
        for j in 0..2 {
            y[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
        }
        reference.push(force((i + 1) as f64 * h, y));
    }
    let load = (m_w + m_b) * GRAVITY;
    let dt = 1e-4;
    for (name, method) in integrators() {
        let wheel = WheelSpec {
            position: x0,
            ..quarter_car()
        };
        let mut sc = scenario(25.0, 12, wheel, speed, method, dt);
        sc.irregularity = Irregularity::Dip {
            position: dip_at,
            length: len,
            depth,
        };
        sc.duration = Some(duration);
        let hist = run(sc);
        // Largest error everywhere, and away from the two jumps of r'' (10 steps after each).
        let (mut err, mut err_smooth) = (0.0f64, 0.0f64);
        let jumps = [dip_at, dip_at + len].map(|x| (x - x0) / speed);
        for (n, &f) in hist.force.iter().enumerate() {
            let i = (hist.t[n] / h).round() as usize;
            let e = (f - reference[i]).abs();
            err = err.max(e);
            if jumps
                .iter()
                .all(|&tj| !(tj..tj + 10.0 * dt).contains(&hist.t[n]))
            {
                err_smooth = err_smooth.max(e);
            }
        }
        let (fmin, fmax) = hist
            .force
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &f| (a.min(f), b.max(f)));
        println!(
            "{name}: F in [{fmin:.4e}, {fmax:.4e}] N, max |F − F_ref| = {err:.3e} N ({:.2e} W), {err_smooth:.3e} N ({:.2e} W) away from the jumps, losses {}",
            err / load,
            err_smooth / load,
            hist.losses
        );
        assert!(err < 1e-3 * load, "{name}: {err}");
        assert!(err_smooth < 1e-4 * load, "{name}: {err_smooth}");
        assert_eq!(hist.losses, 0, "{name}");
    }
}

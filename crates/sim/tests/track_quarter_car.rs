//! A quarter car over Frýba's 25 m bridge with the real track (rail on pads, sleepers and
//! ballast, continued on the embankments; `beam::track`, references.md §D5) against today's
//! model (rail = beam, rigid track off the span; `sim::vehicle_bridge`).
//!
//! The track runs are made by a small monolithic coupling written here (the test's own
//! reference, independent of `sim::vehicle_bridge`): Newmark's average-acceleration rule for the
//! track + bridge (`beam::track::TrackNewmark`, the step matrix factorised once) and for the
//! 2-DOF vehicle; the Hertz force F = C_H max(δ, 0)^{3/2}, δ = z_w − u_rail(x_w), solved exactly
//! each step from the linear responses u = u₀ + F A⁻¹b (b the Hermite load vector of the wheel
//! on the rail, references.md §D4.2: the one-wheel Sherman–Morrison step) in the split form of
//! `TrackNewmark::predict_forward`/`forward_point`/`backward`, so each step costs one forward
//! and one backward sweep of the factor, a short sparse forward sweep and a scalar equation.

use beam::track::{
    RailSection, SpringDamper, SupportStack, Track, TrackLayout, TrackNewmark, TrackSupports,
};
use beam::{AnalyticBeam, Derivative, ModalBasis, ModalDamping, Support, UniformBeam};
use integrate::structural::StructuralMethod;
use sim::config::vehicle_bridge::DEFAULT_GEOMETRY;
use sim::vehicle_bridge::{
    ContactModel, CouplingSpec, GRAVITY, Integrator, Irregularity, Scenario, Simulation, WheelSpec,
};

const L: f64 = 25.0;
const EI: f64 = 2.87e9 * 2.90;
const RHO_A: f64 = 2303.0;
const MODES: usize = 10;
const SPEED: f64 = 27.78;
const DT: f64 = 1e-4;
const M_W: f64 = 600.0;
const M_B: f64 = 5750.0;
const K_S: f64 = 1595e3;
const C_S: f64 = 0.0;

/// The bridge modes with the bridge's own mass per length `rho_a`.
fn basis(rho_a: f64) -> AnalyticBeam {
    AnalyticBeam::new(
        Support::SimplySupported,
        UniformBeam::new(L, EI, rho_a).unwrap(),
        MODES,
    )
    .unwrap()
}

fn damping() -> ModalDamping {
    ModalDamping::Uniform(0.02)
}

/// Today's model: peak midspan deflection while the wheel crosses the span from x = 0.
fn today() -> f64 {
    today_with(StructuralMethod::average_acceleration())
}

/// [`today`] with the structural method `method`.
fn today_with(method: StructuralMethod) -> f64 {
    let wheel = WheelSpec {
        position: 0.0,
        wheel_mass: M_W,
        body_mass: M_B,
        suspension_stiffness: K_S,
        suspension_damping: C_S,
        static_load: 0.0,
    };
    let sc = Scenario {
        moving_forces: Vec::new(),
        bridge: Box::new(basis(RHO_A)),
        damping: damping(),
        wheels: vec![wheel],
        speed: SPEED,
        contact: ContactModel::Hertz,
        geometry: DEFAULT_GEOMETRY,
        irregularity: Irregularity::None,
        integrator: Integrator::Structural(method),
        dt: DT,
        duration: Some(L / SPEED),
        coupling: CouplingSpec {
            tol: 1e-10,
            ..CouplingSpec::default()
        },
        gravity: GRAVITY,
        output_point: 0.5 * L,
    };
    let mut sim = Simulation::new(sc).unwrap();
    let mut peak = 0.0f64;
    sim.run(|s| peak = peak.max(s.deflection_at(0.5 * L).unwrap()))
        .unwrap();
    peak
}

/// The quarter car on `track` at `speed`, starting at x = `x0` in static equilibrium, for
/// `steps` steps of [`DT`]; after each step `observe(x_wheel, track state, contact force)`.
fn run_quarter_car(
    track: &Track,
    x0: f64,
    speed: f64,
    steps: usize,
    mut observe: impl FnMut(f64, &[f64], f64),
) {
    let c_h = DEFAULT_GEOMETRY.hertz().unwrap().coefficient();
    let weight = (M_W + M_B) * GRAVITY;
    let n = track.n_dofs();
    // Static start: the wheel load on the rail at x0.
    let mut load = vec![0.0; n];
    track.add_point_force(x0, weight, &mut load).unwrap();
    let mut nm = TrackNewmark::new(track, DT, &load).unwrap();
    let delta_static = (weight / c_h).powf(2.0 / 3.0);
    let mut zw = delta_static + track.rail_displacement(x0, nm.displacement()).unwrap();
    let mut zb = zw + M_B * GRAVITY / K_S;
    let (mut vw, mut vb, mut aw, mut ab) = (0.0, 0.0, 0.0, 0.0);
    // Vehicle step matrix (Newmark β = ¼, γ = ½).
    let (a0, a1) = (4.0 / (DT * DT), 2.0 / DT);
    let a_v = [
        [M_W * a0 + C_S * a1 + K_S, -(C_S * a1 + K_S)],
        [-(C_S * a1 + K_S), M_B * a0 + C_S * a1 + K_S],
    ];
    let det = a_v[0][0] * a_v[1][1] - a_v[0][1] * a_v[1][0];
    let inv = [
        [a_v[1][1] / det, -a_v[0][1] / det],
        [-a_v[1][0] / det, a_v[0][0] / det],
    ];
    let zero = vec![0.0; n];
    let (mut u0, mut g) = (vec![0.0; n], vec![0.0; n]);
    let mut force = weight;
    for _ in 0..steps {
        let x = x0 + speed * (nm.time() + DT);
        let p = track.rail_point(x).unwrap();
        // One solve per step: z = L⁻¹P r, y = L⁻¹P b (sparse), then one backward sweep.
        nm.predict_forward(&zero, &mut u0).unwrap();
        nm.forward_point(&p, &mut g).unwrap();
        let rail0: f64 = g.iter().zip(&u0).map(|(a, b)| a * b).sum();
        let c_rail: f64 = g.iter().map(|a| a * a).sum();
        // Vehicle predictor (no contact force): gravity + the Newmark history terms.
        let hist = |m: f64, z: f64, v: f64, a: f64| m * (a0 * z + 4.0 / DT * v + a);
        let r = [
            M_W * GRAVITY + hist(M_W, zw, vw, aw),
            M_B * GRAVITY + hist(M_B, zb, vb, ab),
        ];
        let zw0 = inv[0][0] * r[0] + inv[0][1] * r[1];
        let zb0 = inv[1][0] * r[0] + inv[1][1] * r[1];
        // δ(F) = δ0 − c F.
        let delta0 = zw0 - rail0;
        let c = inv[0][0] + c_rail;
        force = if delta0 <= 0.0 {
            0.0
        } else {
            // F = C_H (δ0 − cF)^{3/2}: h(F) increasing on [0, δ0/c]; Newton from the last
            // force, bracketed.
            let (mut lo, mut hi) = (0.0, delta0 / c);
            let mut f = force.clamp(lo, hi);
            for _ in 0..100 {
                let d = (delta0 - c * f).max(0.0);
                let h = f - c_h * d.powf(1.5);
                if h > 0.0 {
                    hi = f
                } else {
                    lo = f
                }
                let dh = 1.0 + 1.5 * c_h * c * d.sqrt();
                let mut next = f - h / dh;
                if !(lo..=hi).contains(&next) {
                    next = 0.5 * (lo + hi);
                }
                if (next - f).abs() <= 1e-12 * weight {
                    f = next;
                    break;
                }
                f = next;
            }
            f
        };
        for i in 0..n {
            u0[i] += force * g[i];
        }
        nm.backward(&mut u0).unwrap();
        nm.advance_to(&u0).unwrap();
        let zw1 = zw0 - force * inv[0][0];
        let zb1 = zb0 - force * inv[1][0];
        let aw1 = a0 * (zw1 - zw) - 4.0 / DT * vw - aw;
        let ab1 = a0 * (zb1 - zb) - 4.0 / DT * vb - ab;
        vw += 0.5 * DT * (aw + aw1);
        vb += 0.5 * DT * (ab + ab1);
        (zw, zb, aw, ab) = (zw1, zb1, aw1, ab1);
        observe(x, nm.displacement(), force);
    }
}

/// The quarter car on `track` (a track on the bridge modes of [`basis`], the bridge starting
/// at x = `approach`), starting at x = `approach` − `lead_in` in static equilibrium; the peak
/// midspan deflection while the wheel is on the span.
fn with_track(track: &Track, lead_in: f64) -> f64 {
    let approach = track.layout().approach();
    let mut phi = vec![0.0; MODES];
    basis(bridge_mass(
        track.sleepers()[0].stack.masses(),
        track.layout().sleeper_spacing(),
    ))
    .eval_all(0.5 * L, Derivative::Shape, &mut phi)
    .unwrap();
    let midspan = |u: &[f64]| -> f64 { (0..MODES).map(|j| phi[j] * u[track.modal_dof(j)]).sum() };
    let steps = ((lead_in + L) / SPEED / DT).round() as usize;
    let mut peak = 0.0f64;
    run_quarter_car(track, approach - lead_in, SPEED, steps, |x, u, _| {
        if x >= approach {
            peak = peak.max(midspan(u));
        }
    });
    peak
}

/// The bridge's own mass per length when the track (rail and chain masses `masses` every `d`)
/// is modelled separately: Frýba's 2303 kg/m is the total, so the runs carry the same mass.
fn bridge_mass(masses: &[f64], d: f64) -> f64 {
    RHO_A - RailSection::e60().mass_per_length() - masses.iter().sum::<f64>() / d
}

fn track_on_bridge(approach: f64, supports: &TrackSupports) -> Track {
    track_on_bridge_with(RailSection::e60(), approach, supports)
}

fn track_on_bridge_with(rail: RailSection, approach: f64, supports: &TrackSupports) -> Track {
    let d = 0.625;
    let layout = TrackLayout::new(approach, L, approach, d).unwrap();
    let modes = basis(bridge_mass(supports.bridge.masses(), d));
    Track::on_bridge(rail, layout, supports, &modes, &damping()).unwrap()
}

/// Stiff track converges to today's model (rail = beam): the rail on pads of 1.6e10 N/m² per
/// length (1e10 N/m at 0.625 m) on the span only, the wheel entering at the bridge's left end as
/// in today's model, the bridge's own mass reduced by the rail's. At the real sleeper spacing
/// the peak midspan deflection is 0.85 % above today's (the wheel rides over a rail that is
/// stiffer over the sleepers than between them: a parametric excitation at v/d = 44 Hz that
/// today's model lacks); halving the spacing twice (support per length kept) the difference
/// falls to 0.15 % and 0.05 % (measured). Asserted: monotone, and below 0.15 % at d = 0.156 m.
#[test]
fn stiff_track_converges_to_todays_model() {
    let reference = today();
    let mut diffs = Vec::new();
    for d in [0.625, 0.3125, 0.15625] {
        let stiff = TrackSupports::uniform(
            SupportStack::direct(SpringDamper::new(1e10 * d / 0.625, 0.0).unwrap()).unwrap(),
        );
        let layout = TrackLayout::new(0.0, L, 0.0, d).unwrap();
        let modes = basis(bridge_mass(&[], d));
        let track =
            Track::on_bridge(RailSection::e60(), layout, &stiff, &modes, &damping()).unwrap();
        diffs.push((d, with_track(&track, 0.0) / reference - 1.0));
    }
    println!(
        "today's peak midspan deflection {reference:.5e} m; stiff track, relative difference by sleeper spacing: {diffs:?}"
    );
    for p in diffs.windows(2) {
        assert!(p[1].1.abs() < p[0].1.abs(), "{diffs:?}");
    }
    assert!(diffs.last().unwrap().1.abs() < 1.5e-3, "{diffs:?}");
}

/// The real ballasted track (the Zhai et al. 2004 preset, continued on embankments; the bridge's
/// own mass reduced to 1192 kg/m so that bridge + track carry Frýba's 2303 kg/m) against
/// today's model: the change of the peak midspan deflection is printed (measured −1.31 %; the
/// modelling difference the track exists for, references.md §D5.3). Asserted: it does not
/// depend on the embankment length once the embankment is much longer than the rail's
/// deflection bowl (1/β ≈ 0.9 m, so e^{−β·10 m} ≈ 1e-5): 20 m and 60 m agree within 1e-4.
#[test]
fn ballasted_track_with_embankments() {
    let reference = today();
    let ballasted = TrackSupports::uniform(SupportStack::ballasted_high_speed());
    let p20 = with_track(&track_on_bridge(20.0, &ballasted), 10.0);
    let p60 = with_track(&track_on_bridge(60.0, &ballasted), 10.0);
    let rel = |p: f64| 100.0 * (p / reference - 1.0);
    println!(
        "peak midspan deflection: today {reference:.5e} m; ballasted track with 20 m embankments {p20:.5e} m ({:+.2} %), with 60 m {p60:.5e} m ({:+.2} %)",
        rel(p20),
        rel(p60)
    );
    assert!((p60 / p20 - 1.0).abs() < 1e-4);
}

/// Largest line of the Hann-windowed spectrum of `series` (sampled every [`DT`]) between `lo`
/// and `hi` Hz on a 0.25 Hz grid.
fn spectral_peak(series: &[f64], lo: f64, hi: f64) -> (f64, f64) {
    let n = series.len();
    let mean = series.iter().sum::<f64>() / n as f64;
    let amplitude = |f: f64| {
        let (mut re, mut im) = (0.0, 0.0);
        for (i, &s) in series.iter().enumerate() {
            let hann = 0.5 - 0.5 * (std::f64::consts::TAU * i as f64 / (n - 1) as f64).cos();
            let phase = -std::f64::consts::TAU * f * i as f64 * DT;
            re += (s - mean) * hann * phase.cos();
            im += (s - mean) * hann * phase.sin();
        }
        (re * re + im * im).sqrt()
    };
    let steps = ((hi - lo) / 0.25) as usize;
    (0..=steps)
        .map(|i| lo + 0.25 * i as f64)
        .map(|f| (f, amplitude(f)))
        .fold((lo, 0.0), |m, p| if p.1 > m.1 { p } else { m })
}

/// The sleeper-passing frequency in the wheel–rail contact force: the quarter car at 50 m/s on
/// the ballasted preset on rigid ground (sleepers 0.625 m apart, so v/d = 80 Hz), 1.2 s; the
/// largest line of the contact-force spectrum between 20 and 300 Hz (after a 0.2 s start-up,
/// resolution 1/1.0 s) lies within 1 Hz of v/d. Measured: 80.00 Hz; the force varies between
/// 61.8 and 62.8 kN around the static 62.3 kN.
#[test]
fn contact_force_shows_the_sleeper_passing_frequency() {
    let d = 0.625;
    let speed = 50.0;
    let layout = TrackLayout::new(40.0, 0.0, 40.0, d).unwrap();
    let track = Track::on_ground(
        RailSection::e60(),
        layout,
        &TrackSupports::uniform(SupportStack::ballasted_high_speed()),
    )
    .unwrap();
    let steps = (1.2 / DT) as usize;
    let skip = (0.2 / DT) as usize;
    let mut forces = Vec::with_capacity(steps);
    run_quarter_car(&track, 5.0, speed, steps, |_, _, f| forces.push(f));
    let (f_peak, amplitude) = spectral_peak(&forces[skip..], 20.0, 300.0);
    println!(
        "contact-force spectrum: peak {f_peak:.2} Hz (v/d = {:.2} Hz), amplitude {amplitude:.3e}; force range {:.1} … {:.1} kN",
        speed / d,
        forces[skip..].iter().cloned().fold(f64::INFINITY, f64::min) / 1e3,
        forces[skip..].iter().cloned().fold(0.0, f64::max) / 1e3
    );
    assert!((f_peak - speed / d).abs() <= 1.0);
}

/// The coupled simulation with `[track]` (`Simulation::with_track`) of the quarter car on
/// `track_spec`, starting at bridge coordinate `x0`, with `method`; the midspan deflection
/// after every step.
fn coupled_history(
    spec: sim::vehicle_bridge::track::TrackSpec,
    rho_a: f64,
    x0: f64,
    method: StructuralMethod,
    duration: f64,
) -> Vec<f64> {
    let wheel = WheelSpec {
        position: x0,
        wheel_mass: M_W,
        body_mass: M_B,
        suspension_stiffness: K_S,
        suspension_damping: C_S,
        static_load: 0.0,
    };
    let sc = Scenario {
        moving_forces: Vec::new(),
        bridge: Box::new(basis(rho_a)),
        damping: damping(),
        wheels: vec![wheel],
        speed: SPEED,
        contact: ContactModel::Hertz,
        geometry: DEFAULT_GEOMETRY,
        irregularity: Irregularity::None,
        integrator: Integrator::Structural(method),
        dt: DT,
        duration: Some(duration),
        coupling: CouplingSpec {
            tol: 1e-10,
            ..CouplingSpec::default()
        },
        gravity: GRAVITY,
        output_point: 0.5 * L,
    };
    let mut sim = Simulation::with_track(sc, Vec::new(), spec).unwrap();
    let mut out = Vec::new();
    sim.run(|s| out.push(s.deflection_at(0.5 * L).unwrap()))
        .unwrap();
    out
}

fn spec_of(
    d: f64,
    approach: f64,
    supports: TrackSupports,
) -> sim::vehicle_bridge::track::TrackSpec {
    sim::vehicle_bridge::track::TrackSpec {
        model: "ballasted".into(),
        rail: RailSection::e60(),
        approach,
        exit: approach,
        sleeper_spacing: d,
        elements_per_bay: 4,
        supports,
    }
}

/// The coupled simulation with `[track]` reproduces this file's monolithic reference (the
/// ballasted preset on 20 m embankments, the quarter car from 10 m before the bridge, Newmark
/// average acceleration): the midspan deflection histories agree to 1e-9 of their peak
/// (the same discrete equations, solved in another order: the reference eliminates the
/// vehicle in closed form and solves the scalar Hertz equation, the simulation puts the
/// vehicle into the factorised step matrix and solves the capacitance system). With the
/// Euler–Bernoulli rail and with the Timoshenko rail (the IIE's displacement shape functions
/// carry the wheel in both codes): measured 4.3e-10 and 3.9e-10 of the peak. The Timoshenko
/// rail raises the peak midspan deflection by 0.12 % (printed, not asserted).
#[test]
fn coupled_simulation_equals_the_monolithic_reference() {
    let mut peaks = Vec::new();
    for rail in [RailSection::e60(), RailSection::e60().timoshenko()] {
        let ballasted = TrackSupports::uniform(SupportStack::ballasted_high_speed());
        let track = track_on_bridge_with(rail, 20.0, &ballasted);
        let lead_in = 10.0;
        let steps = ((lead_in + L) / SPEED / DT).round() as usize;
        let mut phi = vec![0.0; MODES];
        let rho = bridge_mass(ballasted.bridge.masses(), 0.625);
        basis(rho)
            .eval_all(0.5 * L, Derivative::Shape, &mut phi)
            .unwrap();
        let mut reference = Vec::with_capacity(steps);
        run_quarter_car(&track, 20.0 - lead_in, SPEED, steps, |_, u, _| {
            reference.push(
                (0..MODES)
                    .map(|j| phi[j] * u[track.modal_dof(j)])
                    .sum::<f64>(),
            )
        });
        let mut spec = spec_of(0.625, 20.0, ballasted);
        spec.rail = rail;
        let coupled = coupled_history(
            spec,
            rho,
            -lead_in,
            StructuralMethod::average_acceleration(),
            steps as f64 * DT,
        );
        let peak = reference.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let n = reference.len().min(coupled.len());
        let diff = (0..n)
            .map(|i| (reference[i] - coupled[i]).abs())
            .fold(0.0, f64::max);
        println!(
            "{:?}: steps: reference {}, coupled {}; peak {peak:.6e} m; largest difference {diff:.3e} m ({:.2e} of the peak)",
            rail.beam(),
            reference.len(),
            coupled.len(),
            diff / peak
        );
        assert!(coupled.len() >= steps && coupled.len() <= steps + 1);
        assert!(diff <= 1e-9 * peak, "{diff:e}");
        peaks.push(peak);
    }
    println!(
        "peak midspan: Timoshenko / Euler-Bernoulli - 1 = {:+.3e}",
        peaks[1] / peaks[0] - 1.0
    );
}

/// Stiff track converges to today's model through the coupled simulation as through the
/// reference ([`stiff_track_converges_to_todays_model`]): relative differences of the peak
/// midspan deflection at d = 0.625, 0.3125, 0.15625 m, monotone, the last below 0.15 %; for
/// Newmark, HHT-α (α = −0.05) and generalized-α (ρ∞ = 0.9) against today's model with the
/// same method.
#[test]
fn coupled_stiff_track_converges_to_todays_model() {
    for method in [
        StructuralMethod::average_acceleration(),
        StructuralMethod::hht(-0.05).unwrap(),
        StructuralMethod::generalized_alpha(0.9).unwrap(),
    ] {
        let reference = today_with(method);
        let mut diffs = Vec::new();
        for d in [0.625, 0.3125, 0.15625] {
            let stiff = TrackSupports::uniform(
                SupportStack::direct(SpringDamper::new(1e10 * d / 0.625, 0.0).unwrap()).unwrap(),
            );
            let history = coupled_history(
                spec_of(d, 0.0, stiff),
                bridge_mass(&[], d),
                0.0,
                method,
                (L / SPEED / DT).floor() * DT,
            );
            let peak = history.iter().fold(0.0f64, |m, v| m.max(*v));
            diffs.push((d, peak / reference - 1.0));
        }
        println!(
            "{}: today's peak {reference:.5e} m; coupled stiff track by d: {diffs:?}",
            method.name()
        );
        for p in diffs.windows(2) {
            assert!(p[1].1.abs() < p[0].1.abs(), "{diffs:?}");
        }
        assert!(diffs.last().unwrap().1.abs() < 1.5e-3, "{diffs:?}");
    }
}

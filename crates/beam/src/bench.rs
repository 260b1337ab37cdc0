//! Fixed workloads for a benchmark driver (`dyncontact bench`); no timing here, no I/O.
//!
//! Each function runs one representative computation and returns its result so the caller can
//! time it and keep the optimiser from discarding the work.

use crate::analytic::{AnalyticBeam, Support, UniformBeam};
use crate::closed_form::speed_for_parameter;
use crate::damping::ModalDamping;
use crate::error::BeamError;
use crate::fe::{EigenReduction, FeBeam, FeModes, PointSupport, Section, SupportKind};
use crate::modal::{Derivative, ModalBasis};
use crate::moving::{MovingLoadResponse, MovingLoadSettings, MovingLoads, simulate_moving_loads};

/// Frýba's 25 m bridge (references.md §D1.3): EI = 2.87e9·2.90 N m², ρA = 2303 kg/m.
pub fn fryba_bridge() -> Result<UniformBeam, BeamError> {
    UniformBeam::new(25.0, 2.87e9 * 2.90, 2303.0)
}

/// A 56.4 kN force crossing the 25 m simply supported bridge at 27.78 m/s with `n_modes` modes,
/// 2 % damping, time step `dt`, plus 0.5 s of free vibration; response at quarter and mid span.
pub fn moving_load_run(n_modes: usize, dt: f64) -> Result<MovingLoadResponse, BeamError> {
    let beam = fryba_bridge()?;
    let basis = AnalyticBeam::new(Support::SimplySupported, beam, n_modes)?;
    let loads = MovingLoads::single(56.4e3, 27.78)?;
    let settings = MovingLoadSettings::new(dt, 0.5);
    simulate_moving_loads(
        &basis,
        &ModalDamping::Uniform(0.02),
        &loads,
        &settings,
        &[6.25, 12.5],
    )
}

/// Evaluate `n_modes` clamped–clamped modes at `n_points` equally spaced points; returns the sum
/// of all values (a checksum).
pub fn mode_evaluation(n_modes: usize, n_points: usize) -> Result<f64, BeamError> {
    let beam = fryba_bridge()?;
    let basis = AnalyticBeam::new(Support::ClampedClamped, beam, n_modes)?;
    let mut out = vec![0.0; n_modes];
    let mut sum = 0.0;
    for i in 0..n_points {
        let x = beam.length * i as f64 / (n_points.max(2) - 1) as f64;
        basis.eval_all(x.min(beam.length), Derivative::Shape, &mut out)?;
        sum += out.iter().sum::<f64>();
    }
    Ok(sum)
}

/// FE eigen-solve of the simply supported bridge with `n_elements` elements, lowest `n_modes`,
/// by the given reduction.
pub fn fe_eigen_solve(
    n_elements: usize,
    n_modes: usize,
    reduction: EigenReduction,
) -> Result<FeModes, BeamError> {
    let beam = fryba_bridge()?;
    let sections = [Section {
        length: beam.length,
        bending_stiffness: beam.bending_stiffness,
        mass_per_length: beam.mass_per_length,
    }];
    let supports = [
        PointSupport {
            x: 0.0,
            kind: SupportKind::Pinned,
        },
        PointSupport {
            x: beam.length,
            kind: SupportKind::Pinned,
        },
    ];
    FeBeam::new(&sections, &supports, &[], n_elements)?.modes_with(n_modes, reduction)
}

/// Speed giving speed parameter α on Frýba's bridge (convenience for sweeps).
pub fn fryba_speed(alpha: f64) -> Result<f64, BeamError> {
    speed_for_parameter(&fryba_bridge()?, alpha)
}

/// The ballasted high-speed track (60E1 on the preset chain, 0.6 m, `elements_per_bay` rail
/// elements per bay) over `approach` m of embankment, Frýba's 25 m bridge (20 modes, 2 %
/// damping) and `approach` m of exit: the track of the performance target of the track model.
pub fn ballasted_track_on_fryba_bridge(
    approach: f64,
    elements_per_bay: usize,
) -> Result<crate::track::Track, BeamError> {
    use crate::track::{RailSection, SupportStack, Track, TrackLayout, TrackSupports};
    let bridge = fryba_bridge()?;
    let modes = AnalyticBeam::new(Support::SimplySupported, bridge, 20)?;
    let layout = TrackLayout::new(approach, bridge.length, approach, 0.6)?
        .with_elements_per_bay(elements_per_bay)?;
    let supports = TrackSupports::uniform(SupportStack::ballasted_high_speed());
    Track::on_bridge(
        RailSection::e60(),
        layout,
        &supports,
        &modes,
        &ModalDamping::Uniform(0.02),
    )
}

/// A 100 kN force crossing `track` at 80 m/s from x = 1 m: the Newmark set-up (static start,
/// factorisation of the step matrix) and `steps` steps of `dt`. With `split`, each step takes
/// the split form of a coupled step (forward half of the history load, sparse forward sweep of
/// the force's load vector, rail displacement under it, one backward half;
/// `TrackNewmark::predict_forward`), otherwise one full solve with the force in the load.
/// Returns the rail displacement under the force at the end (a checksum).
pub fn track_moving_force(
    track: &crate::track::Track,
    dt: f64,
    steps: usize,
    split: bool,
) -> Result<f64, BeamError> {
    let n = track.n_dofs();
    let mut load = vec![0.0; n];
    let (x0, force) = (1.0, 100e3);
    track.add_point_force(x0, force, &mut load)?;
    let mut nm = crate::track::TrackNewmark::new(track, dt, &load)?;
    let end = track.layout().rail_length() - 1.0;
    let zero = vec![0.0; n];
    let (mut z, mut y) = (vec![0.0; n], vec![0.0; n]);
    let mut x = x0;
    for _ in 0..steps {
        x = (x0 + 80.0 * (nm.time() + dt)).min(end);
        if split {
            let p = track.rail_point(x)?;
            nm.predict_forward(&zero, &mut z)?;
            nm.forward_point(&p, &mut y)?;
            for (zi, yi) in z.iter_mut().zip(&y) {
                *zi += force * yi;
            }
            nm.backward(&mut z)?;
            nm.advance_to(&z)?;
        } else {
            load.fill(0.0);
            track.add_point_force(x, force, &mut load)?;
            nm.step(&load)?;
        }
    }
    track.rail_displacement(x, nm.displacement())
}

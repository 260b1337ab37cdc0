//! Contact geometry and forces of a wheelset against its lateral shift
//! (`dyncontact profile-sweep`, docs/profiles.md): contact-point positions, rolling radius
//! difference Δr(y), contact angles, the roll, the wheel forces of the elastic contact, and
//! the equivalent conicity against amplitude. No I/O.

use serde::Serialize;
use wheelrail::{Roll, Side, WheelRailError, equivalent_conicity, solve_wheel};

use crate::config::wheel_rail::WheelRailConfig;

/// Largest number of shifts of one sweep.
pub const MAX_POINTS: usize = 2001;

/// Nodes of the conicity integral.
pub const CONICITY_NODES: usize = 64;

/// One lateral shift.
#[derive(Debug, Clone, Serialize)]
pub struct SweepPoint {
    pub lateral_shift: f64,
    pub roll: f64,
    pub delta_r: f64,
    pub right_rolling_radius: f64,
    pub left_rolling_radius: f64,
    pub right_contact_angle: f64,
    pub left_contact_angle: f64,
    /// Principal contact points: wheel and rail profile coordinates \[m\].
    pub right_wheel_s: f64,
    pub right_rail_y: f64,
    pub left_wheel_s: f64,
    pub left_rail_y: f64,
    /// Candidates (local minima) on each wheel.
    pub right_candidates: usize,
    pub left_candidates: usize,
    /// Elastic contact under the case's load: patches and forces on each wheel.
    pub right_patches: usize,
    pub left_patches: usize,
    pub right_lateral_force: f64,
    pub left_lateral_force: f64,
    pub right_max_pressure: f64,
    pub left_max_pressure: f64,
}

/// Equivalent conicity at one amplitude.
#[derive(Debug, Clone, Serialize)]
pub struct ConicityPoint {
    pub amplitude: f64,
    pub conicity: f64,
}

/// The sweep.
#[derive(Debug, Clone, Serialize)]
pub struct ProfileSweep {
    pub wheel_profile: String,
    pub rail_profile: String,
    pub inclination: String,
    pub gauge: f64,
    pub points: Vec<SweepPoint>,
    pub conicity: Vec<ConicityPoint>,
    /// λ_e at 3 mm amplitude (when the sweep reaches 3 mm).
    pub conicity_3mm: Option<f64>,
}

/// Sweep the shifts `shifts` \[m\]; conicity at amplitudes `amplitudes` \[m\].
pub fn sweep(
    config: &WheelRailConfig,
    shifts: &[f64],
    amplitudes: &[f64],
) -> Result<ProfileSweep, WheelRailError> {
    let ws = &config.wheelset;
    let mut points = Vec::with_capacity(shifts.len());
    for &y in shifts {
        let c = ws.contact(y, Roll::Equilibrium)?;
        let r = solve_wheel(
            ws,
            &c,
            Side::Right,
            &config.material,
            config.load,
            &config.options,
        )?;
        let l = solve_wheel(
            ws,
            &c,
            Side::Left,
            &config.material,
            config.load,
            &config.options,
        )?;
        let pmax = |s: &wheelrail::WheelSolution| {
            s.patches
                .iter()
                .map(|p| p.solution.max_pressure)
                .fold(0.0, f64::max)
        };
        points.push(SweepPoint {
            lateral_shift: y,
            roll: c.roll,
            delta_r: c.delta_r(),
            right_rolling_radius: c.right.rolling_radius(),
            left_rolling_radius: c.left.rolling_radius(),
            right_contact_angle: c.right.principal().contact_angle(),
            left_contact_angle: c.left.principal().contact_angle(),
            right_wheel_s: c.right.principal().wheel_s,
            right_rail_y: c.right.principal().rail_y,
            left_wheel_s: c.left.principal().wheel_s,
            left_rail_y: c.left.principal().rail_y,
            right_candidates: c.right.candidates.len(),
            left_candidates: c.left.candidates.len(),
            right_patches: r.patches.len(),
            left_patches: l.patches.len(),
            right_lateral_force: r.lateral_force,
            left_lateral_force: l.lateral_force,
            right_max_pressure: pmax(&r),
            left_max_pressure: pmax(&l),
        });
    }
    let mut conicity = Vec::with_capacity(amplitudes.len());
    for &a in amplitudes {
        conicity.push(ConicityPoint {
            amplitude: a,
            conicity: equivalent_conicity(ws, a, CONICITY_NODES)?,
        });
    }
    let conicity_3mm = conicity
        .iter()
        .find(|c| (c.amplitude - 3e-3).abs() < 1e-9)
        .map(|c| c.conicity);
    Ok(ProfileSweep {
        wheel_profile: ws.wheel().name().to_string(),
        rail_profile: ws.rail().name().to_string(),
        inclination: config.inclination_label.clone(),
        gauge: ws.params().gauge,
        points,
        conicity,
        conicity_3mm,
    })
}

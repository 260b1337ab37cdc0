//! A wheel–rail contact case solved (`dyncontact contact` with `[gap] kind = "wheel_rail"`):
//! the rigid contact of the wheelset at its lateral shift, then the elastic contact of each
//! wheel under the prescribed vertical load, patch by patch (docs/profiles.md). No I/O.

use serde::Serialize;
use wheelrail::{Side, WheelRailError, WheelSolution, WheelsetContact, solve_wheel};

use crate::config::wheel_rail::WheelRailConfig;

/// One patch in the summary. Positions in metres in the wheel's side of the track frame
/// mirrored to the right (Y from the track centre towards the field side, Z up, 0 at the rail
/// top), angles in radians.
#[derive(Debug, Clone, Serialize)]
pub struct PatchSummary {
    /// Centre of pressure: along the track x, lateral Y, height Z.
    pub centre: [f64; 3],
    /// Contact angle of the patch's plane.
    pub contact_angle: f64,
    /// Half-lengths of the patch along the track (a) and across it, in its plane (b).
    pub half_length: f64,
    pub half_width: f64,
    pub normal_force: f64,
    pub vertical_force: f64,
    /// Lateral force on the wheel (positive towards its field side).
    pub lateral_force: f64,
    pub max_pressure: f64,
    pub contact_area: f64,
    pub elements_in_contact: usize,
    /// Grid of the patch: nx, ny, dx, dy.
    pub grid: [f64; 4],
    /// Wheel-profile coordinates s of the candidates solved on this grid.
    pub wheel_s: Vec<f64>,
    /// Rail-profile coordinates of the candidates.
    pub rail_y: Vec<f64>,
}

/// One wheel in the summary.
#[derive(Debug, Clone, Serialize)]
pub struct WheelSummary {
    /// Rolling radius at the (principal) contact point \[m\].
    pub rolling_radius: f64,
    /// Contact angle at the principal contact point \[rad\].
    pub contact_angle: f64,
    /// Wheel and rail profile coordinates of the principal contact point \[m\].
    pub wheel_s: f64,
    pub rail_y: f64,
    /// Number of rigid contact candidates (local minima of the distance).
    pub candidates: usize,
    /// Vertical approach from the rigid touching position \[m\].
    pub vertical_approach: f64,
    pub vertical_force: f64,
    pub lateral_force: f64,
    pub patches: Vec<PatchSummary>,
}

/// The JSON summary.
#[derive(Debug, Clone, Serialize)]
pub struct WheelRailSummary {
    pub wheel_profile: String,
    pub rail_profile: String,
    pub inclination: String,
    pub gauge: f64,
    pub back_to_back: f64,
    pub nominal_radius: f64,
    pub lateral_shift: f64,
    pub roll: f64,
    /// Rolling radius difference r_right − r_left \[m\].
    pub delta_r: f64,
    pub right: WheelSummary,
    pub left: WheelSummary,
}

/// The solved case.
pub struct WheelRailOutcome {
    pub summary: WheelRailSummary,
    pub contact: WheelsetContact,
    pub right: WheelSolution,
    pub left: WheelSolution,
}

fn wheel_summary(contact: &WheelsetContact, side: Side, sol: &WheelSolution) -> WheelSummary {
    let w = match side {
        Side::Right => &contact.right,
        Side::Left => &contact.left,
    };
    let p = w.principal();
    WheelSummary {
        rolling_radius: w.rolling_radius(),
        contact_angle: p.contact_angle(),
        wheel_s: p.wheel_s,
        rail_y: p.rail_y,
        candidates: w.candidates.len(),
        vertical_approach: sol.vertical_approach,
        vertical_force: sol.vertical_force,
        lateral_force: sol.lateral_force,
        patches: sol
            .patches
            .iter()
            .map(|pa| {
                let (a, b) = pa.solution.patch_half_widths();
                let g = pa.solution.grid;
                PatchSummary {
                    centre: [pa.centre.0, pa.centre.1, pa.centre.2],
                    contact_angle: pa.contact_angle,
                    half_length: a,
                    half_width: b,
                    normal_force: pa.normal_force,
                    vertical_force: pa.vertical_force,
                    lateral_force: pa.lateral_force,
                    max_pressure: pa.solution.max_pressure,
                    contact_area: pa.solution.contact_area,
                    elements_in_contact: pa.solution.elements_in_contact,
                    grid: [g.nx as f64, g.ny as f64, g.dx, g.dy],
                    wheel_s: pa
                        .candidates
                        .iter()
                        .map(|&i| w.candidates[i].wheel_s)
                        .collect(),
                    rail_y: pa
                        .candidates
                        .iter()
                        .map(|&i| w.candidates[i].rail_y)
                        .collect(),
                }
            })
            .collect(),
    }
}

/// Solve the case: rigid contact, then both wheels under the prescribed load.
pub fn solve(config: &WheelRailConfig) -> Result<WheelRailOutcome, WheelRailError> {
    let ws = &config.wheelset;
    let contact = ws.contact(config.lateral_shift, config.roll)?;
    let right = solve_wheel(
        ws,
        &contact,
        Side::Right,
        &config.material,
        config.load,
        &config.options,
    )?;
    let left = solve_wheel(
        ws,
        &contact,
        Side::Left,
        &config.material,
        config.load,
        &config.options,
    )?;
    let p = ws.params();
    let summary = WheelRailSummary {
        wheel_profile: ws.wheel().name().to_string(),
        rail_profile: ws.rail().name().to_string(),
        inclination: config.inclination_label.clone(),
        gauge: p.gauge,
        back_to_back: p.back_to_back,
        nominal_radius: p.wheel_radius,
        lateral_shift: contact.lateral_shift,
        roll: contact.roll,
        delta_r: contact.delta_r(),
        right: wheel_summary(&contact, Side::Right, &right),
        left: wheel_summary(&contact, Side::Left, &left),
    };
    Ok(WheelRailOutcome {
        summary,
        contact,
        right,
        left,
    })
}

//! `dyncontact contact FILE` for a case with `[gap] kind = "wheel_rail"`: real wheel and rail
//! profiles, several contact patches per wheel (docs/profiles.md).

use anyhow::Result;
use sim::wheel_rail_case::{WheelRailOutcome, WheelRailSummary, WheelSummary};
use wheelrail::{Side, WheelSolution, Wheelset, WheelsetContact};

use crate::output::{self, RunOutput};
use crate::plot;

/// Every file a wheel–rail `contact --out` run may write.
pub const OUTPUT_SET: &[&str] = &[
    "summary.json",
    "patches.csv",
    "pressure_right.csv",
    "pressure_left.csv",
    "pressure_right_1.png",
    "pressure_right_2.png",
    "pressure_right_3.png",
    "pressure_left_1.png",
    "pressure_left_2.png",
    "pressure_left_3.png",
    "profiles.png",
    "wheel_profile.txt",
    "rail_profile.txt",
];

/// Sampling step of the written profiles \[m\].
const PROFILE_STEP: f64 = 1e-4;

/// The profile sampled every 0.1 mm as two columns in millimetres, with `z_sign` applied to
/// its values (wheel: radius increase, positive down; rail: depth below the top, positive
/// down), readable as a profile file by `[gap] wheel`/`rail`.
fn profile_text(p: &wheelrail::Profile, what: &str, z_sign: f64) -> String {
    let (lo, hi) = p.y_range();
    let n = ((hi - lo) / PROFILE_STEP).floor() as usize;
    let mut s = format!(
        "# {what}: profile {} sampled every {} mm; y [mm], z [mm] positive downwards\n",
        p.name(),
        PROFILE_STEP * 1e3
    );
    for k in 0..=n {
        let y = (lo + PROFILE_STEP * k as f64).min(hi);
        if let Some(z) = p.z(y) {
            s.push_str(&format!("{:.4} {:.7}\n", y * 1e3, z_sign * z * 1e3));
        }
    }
    s
}

fn print_wheel(name: &str, w: &WheelSummary) {
    println!(
        "{name} wheel: rolling radius {:.4} mm, contact angle {:.3} deg at wheel s = {:.3} mm, rail y = {:.3} mm ({} candidate(s))",
        w.rolling_radius * 1e3,
        w.contact_angle.to_degrees(),
        w.wheel_s * 1e3,
        w.rail_y * 1e3,
        w.candidates
    );
    println!(
        "  vertical approach {:.3} um, vertical force {:.6e} N, lateral force {:.6e} N",
        w.vertical_approach * 1e6,
        w.vertical_force,
        w.lateral_force
    );
    for (k, p) in w.patches.iter().enumerate() {
        println!(
            "  patch {}: centre Y = {:.3} mm, Z = {:.3} mm, contact angle {:.3} deg, a = {:.3} mm, b = {:.3} mm, Fn = {:.5e} N (vertical {:.5e}, lateral {:.5e}), p_max = {:.1} MPa",
            k + 1,
            p.centre[1] * 1e3,
            p.centre[2] * 1e3,
            p.contact_angle.to_degrees(),
            p.half_length * 1e3,
            p.half_width * 1e3,
            p.normal_force,
            p.vertical_force,
            p.lateral_force,
            p.max_pressure * 1e-6
        );
    }
}

/// Human-readable summary.
pub fn print_summary(s: &WheelRailSummary) {
    println!(
        "wheel-rail contact: {} on {} at {}, gauge {} m, back-to-back {} m, nominal radius {} m",
        s.wheel_profile, s.rail_profile, s.inclination, s.gauge, s.back_to_back, s.nominal_radius
    );
    println!(
        "  lateral shift {:.3} mm, roll {:.4e} rad, rolling radius difference {:.4} mm",
        s.lateral_shift * 1e3,
        s.roll,
        s.delta_r * 1e3
    );
    print_wheel("right", &s.right);
    print_wheel("left", &s.left);
}

fn side_name(side: Side) -> &'static str {
    match side {
        Side::Right => "right",
        Side::Left => "left",
    }
}

fn write_pressure(dir: &RunOutput, side: Side, sol: &WheelSolution) -> Result<()> {
    let name = side_name(side);
    let mut rows = Vec::new();
    for (k, p) in sol.patches.iter().enumerate() {
        let g = p.solution.grid;
        let (s, c) = p.contact_angle.sin_cos();
        for i in 0..g.len() {
            let (x, t) = g.centre(i);
            rows.push(vec![
                (k + 1) as f64,
                x,
                t,
                p.origin.0 + c * t,
                p.origin.1 + s * t,
                p.solution.pressure[i],
            ]);
        }
        if k < 3 {
            let mpa: Vec<f64> = p.solution.pressure.iter().map(|v| v * 1e-6).collect();
            let outside: Vec<bool> = p.solution.pressure.iter().map(|&v| v <= 0.0).collect();
            plot::map(
                &dir.path(&format!("pressure_{name}_{}.png", k + 1)),
                &plot::Map {
                    title: format!(
                        "{name} wheel, patch {}: contact angle {:.2} deg, Fn {:.4e} N",
                        k + 1,
                        p.contact_angle.to_degrees(),
                        p.normal_force
                    ),
                    x_label: "x along the track [mm]",
                    y_label: "t across, in the contact plane [mm]",
                    field: plot::Field::on_grid_mm(&g, &mpa),
                    scale: plot::Scale::Continuous {
                        label: "p [MPa]",
                        exterior: Some((&outside, "no contact (p = 0)")),
                    },
                },
            )?;
        }
    }
    output::write_csv(
        &dir.path(&format!("pressure_{name}.csv")),
        &["patch", "x_m", "t_m", "y_track_m", "z_track_m", "p_pa"],
        rows,
    )
}

/// The profiles of one side at the rigid contact position, with the contact points, and the
/// pressure across (the load per unit width Σ_x p dx against Y).
fn side_panels(
    ws: &Wheelset,
    contact: &WheelsetContact,
    side: Side,
    sol: &WheelSolution,
) -> [plot::Panel; 2] {
    let (y_ws, roll) = match side {
        Side::Right => (contact.lateral_shift, contact.roll),
        Side::Left => (-contact.lateral_shift, -contact.roll),
    };
    let wheel = ws.right_wheel(y_ws, roll, contact.axle_height);
    let rail = ws.right_rail();
    let curve = |p: &wheelrail::PlacedProfile<'_>| -> Vec<(f64, f64)> {
        let (lo, hi) = p.profile.y_range();
        (0..=600)
            .filter_map(|k| p.map(lo + (hi - lo) * k as f64 / 600.0))
            .map(|(y, z)| (y * 1e3, z * 1e3))
            .collect()
    };
    let w = match side {
        Side::Right => &contact.right,
        Side::Left => &contact.left,
    };
    let mut series = vec![
        plot::Series::new(format!("wheel {}", ws.wheel().name()), curve(&wheel)),
        plot::Series::new(format!("rail {}", ws.rail().name()), curve(&rail)),
    ];
    // Each candidate: a short stroke along the common normal through its point.
    for (k, c) in w.candidates.iter().enumerate() {
        let (s, co) = c.contact_angle().sin_cos();
        let len = 4.0;
        series.push(plot::Series::new(
            format!(
                "candidate {} (gap {:.3} mm, {:.1} deg)",
                k + 1,
                c.gap * 1e3,
                c.contact_angle().to_degrees()
            ),
            vec![
                (c.y * 1e3 + len * s, c.z * 1e3 - len * co),
                (c.y * 1e3 - len * s, c.z * 1e3 + len * co),
            ],
        ));
    }
    let name = side_name(side);
    let profiles = plot::Panel {
        title: format!(
            "{name} wheel on its rail (mirrored to the right), lateral shift {:.2} mm",
            contact.lateral_shift * 1e3
        ),
        x_label: "Y from the track centre [mm]".into(),
        y_label: "Z [mm]".into(),
        series,
    };
    let mut across = Vec::new();
    for (k, p) in sol.patches.iter().enumerate() {
        let g = p.solution.grid;
        let c = p.contact_angle.cos();
        let cells: Vec<(f64, f64)> = (0..g.ny)
            .map(|iy| {
                let q: f64 = (0..g.nx)
                    .map(|ix| p.solution.pressure[iy * g.nx + ix] * g.dx)
                    .sum();
                ((p.origin.0 + c * g.y(iy)) * 1e3, q * 1e-3)
            })
            .collect();
        across.push(plot::Series::steps(
            format!("patch {} ({:.1} deg)", k + 1, p.contact_angle.to_degrees()),
            &cells,
            c * g.dy * 1e3,
        ));
    }
    let pressure = plot::Panel {
        title: format!("{name} wheel: pressure across the track, integrated along it"),
        x_label: "Y from the track centre [mm]".into(),
        y_label: "load per unit width [N/mm]".into(),
        series: across,
    };
    [profiles, pressure]
}

/// Write the output set.
pub fn write_outputs(dir: &RunOutput, ws: &Wheelset, outcome: &WheelRailOutcome) -> Result<()> {
    let mut rows = Vec::new();
    for (side, sol) in [(Side::Right, &outcome.right), (Side::Left, &outcome.left)] {
        for (k, p) in sol.patches.iter().enumerate() {
            let (a, b) = p.solution.patch_half_widths();
            rows.push(vec![
                if side == Side::Right { 1.0 } else { -1.0 },
                (k + 1) as f64,
                p.centre.0,
                p.centre.1,
                p.centre.2,
                p.contact_angle,
                a,
                b,
                p.normal_force,
                p.vertical_force,
                p.lateral_force,
                p.solution.max_pressure,
                p.solution.contact_area,
            ]);
        }
        write_pressure(dir, side, sol)?;
    }
    output::write_csv(
        &dir.path("patches.csv"),
        &[
            "side",
            "patch",
            "x_m",
            "y_m",
            "z_m",
            "contact_angle_rad",
            "half_length_m",
            "half_width_m",
            "normal_force_n",
            "vertical_force_n",
            "lateral_force_n",
            "max_pressure_pa",
            "contact_area_m2",
        ],
        rows,
    )?;
    let [a, b] = side_panels(ws, &outcome.contact, Side::Right, &outcome.right);
    let [c, d] = side_panels(ws, &outcome.contact, Side::Left, &outcome.left);
    plot::panels(&dir.path("profiles.png"), &[a, b, c, d])?;
    std::fs::write(
        dir.path("wheel_profile.txt"),
        profile_text(
            ws.wheel(),
            "wheel (s from the tape circle, positive away from the flange; z = radius increase)",
            1.0,
        ),
    )?;
    std::fs::write(
        dir.path("rail_profile.txt"),
        profile_text(
            ws.rail(),
            "rail (y from the head centre, gauge side negative; z = depth below the top)",
            -1.0,
        ),
    )?;
    output::write_summary(&dir.path("summary.json"), &outcome.summary)
}

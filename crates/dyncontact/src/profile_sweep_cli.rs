//! `dyncontact profile-sweep FILE`: contact geometry and forces against the wheelset's
//! lateral shift for a case with `[gap] kind = "wheel_rail"` (docs/profiles.md).

use std::path::Path;

use anyhow::Result;
use sim::profile_sweep::{MAX_POINTS, ProfileSweep};

use crate::errors::BadInput;
use crate::output::{self, RunOutput};
use crate::plot;

/// Every file a profile sweep may write.
pub const OUTPUT_SET: &[&str] = &[
    "profile_sweep.csv",
    "conicity.csv",
    "summary.json",
    "profile_sweep.png",
    "conicity.png",
];

/// The shifts from, to, step \[m\] (checked: |y| ≤ 20 mm, step > 0, at most MAX_POINTS).
pub fn shifts(from: f64, to: f64, step: f64) -> Result<Vec<f64>> {
    for (key, v) in [("--from", from), ("--to", to)] {
        if !v.is_finite() || v.abs() > 0.02 {
            return Err(BadInput::error(format!(
                "{key} {v}: must lie in [-0.02, 0.02] m"
            )));
        }
    }
    if !(step.is_finite() && step > 0.0 && step <= 0.04) {
        return Err(BadInput::error(format!(
            "--step {step}: must lie in (0, 0.04] m"
        )));
    }
    if to < from {
        return Err(BadInput::error(format!(
            "--to {to} must not be below --from {from}"
        )));
    }
    let n = ((to - from) / step + 1e-9).floor() as usize + 1;
    if n > MAX_POINTS {
        return Err(BadInput::error(format!(
            "--from {from} --to {to} --step {step}: {n} shifts, at most {MAX_POINTS}"
        )));
    }
    Ok((0..n).map(|k| from + step * k as f64).collect())
}

/// Amplitudes \[m\] from a comma-separated list (each in [1e-4, 0.02]).
pub fn amplitudes(list: &str) -> Result<Vec<f64>> {
    let mut out = Vec::new();
    for item in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let a: f64 = item.parse().map_err(|_| {
            BadInput::error(format!("--amplitudes: `{item}` is not a number of metres"))
        })?;
        if !(a.is_finite() && (1e-4..=0.02).contains(&a)) {
            return Err(BadInput::error(format!(
                "--amplitudes: {a} must lie in [1e-4, 0.02] m"
            )));
        }
        out.push(a);
    }
    if out.is_empty() || out.len() > 50 {
        return Err(BadInput::error(format!(
            "--amplitudes: give 1 to 50 amplitudes, got {}",
            out.len()
        )));
    }
    Ok(out)
}

/// Print the table.
pub fn print(s: &ProfileSweep) {
    println!(
        "profile sweep: {} on {} at {}, gauge {} m",
        s.wheel_profile, s.rail_profile, s.inclination, s.gauge
    );
    println!(
        "{:>8} {:>10} {:>9} {:>9} {:>9} {:>9} {:>5} {:>11}",
        "y [mm]", "dr [mm]", "gR [deg]", "gL [deg]", "sR [mm]", "sL [mm]", "pR", "FyR [kN]"
    );
    for p in &s.points {
        println!(
            "{:>8.2} {:>10.4} {:>9.3} {:>9.3} {:>9.2} {:>9.2} {:>5} {:>11.3}",
            p.lateral_shift * 1e3,
            p.delta_r * 1e3,
            p.right_contact_angle.to_degrees(),
            p.left_contact_angle.to_degrees(),
            p.right_wheel_s * 1e3,
            p.left_wheel_s * 1e3,
            p.right_patches,
            p.right_lateral_force * 1e-3
        );
    }
    for c in &s.conicity {
        println!(
            "equivalent conicity at amplitude {:.2} mm: {:.4}",
            c.amplitude * 1e3,
            c.conicity
        );
    }
}

/// Write the output set.
pub fn write_outputs(dir: &RunOutput, s: &ProfileSweep) -> Result<()> {
    output::write_csv(
        &dir.path("profile_sweep.csv"),
        &[
            "lateral_shift_m",
            "roll_rad",
            "delta_r_m",
            "right_rolling_radius_m",
            "left_rolling_radius_m",
            "right_contact_angle_rad",
            "left_contact_angle_rad",
            "right_wheel_s_m",
            "right_rail_y_m",
            "left_wheel_s_m",
            "left_rail_y_m",
            "right_candidates",
            "left_candidates",
            "right_patches",
            "left_patches",
            "right_lateral_force_n",
            "left_lateral_force_n",
            "right_max_pressure_pa",
            "left_max_pressure_pa",
        ],
        s.points.iter().map(|p| {
            vec![
                p.lateral_shift,
                p.roll,
                p.delta_r,
                p.right_rolling_radius,
                p.left_rolling_radius,
                p.right_contact_angle,
                p.left_contact_angle,
                p.right_wheel_s,
                p.right_rail_y,
                p.left_wheel_s,
                p.left_rail_y,
                p.right_candidates as f64,
                p.left_candidates as f64,
                p.right_patches as f64,
                p.left_patches as f64,
                p.right_lateral_force,
                p.left_lateral_force,
                p.right_max_pressure,
                p.left_max_pressure,
            ]
        }),
    )?;
    output::write_csv(
        &dir.path("conicity.csv"),
        &["amplitude_m", "equivalent_conicity"],
        s.conicity.iter().map(|c| vec![c.amplitude, c.conicity]),
    )?;
    let mm = |f: &dyn Fn(&sim::profile_sweep::SweepPoint) -> f64, scale: f64| -> Vec<(f64, f64)> {
        s.points
            .iter()
            .map(|p| (p.lateral_shift * 1e3, f(p) * scale))
            .collect()
    };
    let panels = [
        plot::Panel {
            title: "rolling radius difference r_right - r_left".into(),
            x_label: "lateral shift y [mm]".into(),
            y_label: "delta r [mm]".into(),
            series: vec![plot::Series::new("delta r", mm(&|p| p.delta_r, 1e3))],
        },
        plot::Panel {
            title: "contact angle at the contact point".into(),
            x_label: "lateral shift y [mm]".into(),
            y_label: "contact angle [deg]".into(),
            series: vec![
                plot::Series::new(
                    "right wheel",
                    mm(&|p| p.right_contact_angle.to_degrees(), 1.0),
                ),
                plot::Series::new(
                    "left wheel",
                    mm(&|p| p.left_contact_angle.to_degrees(), 1.0),
                ),
            ],
        },
        plot::Panel {
            title: "contact point on the profiles (wheel: from the tape circle; rail: from the head centre)".into(),
            x_label: "lateral shift y [mm]".into(),
            y_label: "position [mm]".into(),
            series: vec![
                plot::Series::new("right wheel s", mm(&|p| p.right_wheel_s, 1e3)),
                plot::Series::new("right rail y", mm(&|p| p.right_rail_y, 1e3)),
                plot::Series::new("left wheel s", mm(&|p| p.left_wheel_s, 1e3)),
                plot::Series::new("left rail y", mm(&|p| p.left_rail_y, 1e3)),
            ],
        },
        plot::Panel {
            title: "lateral force on each wheel under the case's vertical load (+: towards its field side)".into(),
            x_label: "lateral shift y [mm]".into(),
            y_label: "lateral force [kN]".into(),
            series: vec![
                plot::Series::new("right wheel", mm(&|p| p.right_lateral_force, 1e-3)),
                plot::Series::new("left wheel", mm(&|p| p.left_lateral_force, 1e-3)),
            ],
        },
    ];
    plot::panels(&dir.path("profile_sweep.png"), &panels)?;
    plot::panels(
        &dir.path("conicity.png"),
        &[plot::Panel {
            title: "equivalent conicity (first harmonic of delta r)".into(),
            x_label: "amplitude [mm]".into(),
            y_label: "equivalent conicity [-]".into(),
            series: vec![plot::Series::new(
                "equivalent conicity",
                s.conicity
                    .iter()
                    .map(|c| (c.amplitude * 1e3, c.conicity))
                    .collect(),
            )],
        }],
    )?;
    output::write_summary(&dir.path("summary.json"), s)
}

/// Run the sweep of `text` (a contact case with `[gap] kind = "wheel_rail"`).
pub fn run(
    text: &str,
    base: &Path,
    (from, to, step): (f64, f64, f64),
    amplitude_list: &str,
    out: &Path,
    json: bool,
) -> Result<()> {
    let Some(config) = sim::config::wheel_rail::parse(text, base)
        .map_err(|e| crate::errors::bad_input(e.into()))?
    else {
        return Err(BadInput::error(
            "profile-sweep needs a contact case with [gap] kind = \"wheel_rail\"".to_string(),
        ));
    };
    let shifts = shifts(from, to, step)?;
    let amps = amplitudes(amplitude_list)?;
    let run_out = RunOutput::create(out, OUTPUT_SET)?;
    let s = sim::profile_sweep::sweep(&config, &shifts, &amps)?;
    if json {
        println!("{}", output::json_text(&s)?);
    } else {
        print(&s);
    }
    write_outputs(&run_out, &s)?;
    run_out.commit()?;
    if !json {
        println!("wrote {}/{}", out.display(), OUTPUT_SET.join(", "));
    }
    Ok(())
}

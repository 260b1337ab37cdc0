//! `dyncontact contact CASE.toml`: the quasi-static normal contact problem from a case file.
//!
//! Every key is in SI units; unknown keys are errors. See the README for the schema, and
//! docs/tangential.md for the \[friction\] and \[kinematics\] sections (tangential contact).

use std::path::Path;

use anyhow::Result;
use halfspace::{ElementState, TangentialSolution};

use crate::output::{self, RunOutput};
use crate::plot;

pub use sim::config::contact::PreparedCase;
pub use sim::contact_case::{CaseOutcome, ContactSummary, solve};

/// Parse a case file's text (`base` resolves relative table paths).
pub fn parse(text: &str, base: &Path) -> Result<PreparedCase> {
    Ok(sim::config::contact::parse(text, base)?)
}

/// Human-readable summary.
pub fn print_summary(s: &ContactSummary) {
    println!(
        "normal contact ({} × {} grid, {:.3e} × {:.3e} m elements)",
        s.grid.nx, s.grid.ny, s.grid.dx, s.grid.dy
    );
    println!(
        "  combined G = {:.4e} Pa, nu = {:.4}, K = {:.4}, E* = {:.4e} Pa",
        s.material.g, s.material.nu, s.material.k, s.material.e_star
    );
    println!("  normal force      {:>14.6e} N", s.normal_force);
    println!("  approach          {:>14.6e} m", s.approach);
    println!("  max pressure      {:>14.6e} Pa", s.max_pressure);
    println!(
        "  contact area      {:>14.6e} m^2 ({} elements)",
        s.contact_area, s.elements_in_contact
    );
    println!(
        "  centre of press.  ({:.4e}, {:.4e}) m",
        s.centre_of_pressure[0], s.centre_of_pressure[1]
    );
    if let Some(k) = s.dfn_dapproach {
        println!("  dFn/d(approach)   {:>14.6e} N/m", k);
    }
    println!(
        "  NormCG            {} iterations, relative change {:.2e}, {}, {:.3} ms",
        s.iterations,
        s.residual,
        if s.converged {
            "converged"
        } else {
            "NOT CONVERGED"
        },
        1e3 * s.solve_time_s
    );
    if let Some(h) = &s.hertz {
        println!("Hertz (quadratic gap) at F = {:.6e} N:", h.normal_force);
        println!(
            "  approach {:.6e} m ({:+.3} %), p0 {:.6e} Pa ({:+.3} %), a {:.4e} m, b {:.4e} m",
            h.approach,
            100.0 * (s.approach / h.approach - 1.0),
            h.max_pressure,
            100.0 * (s.max_pressure / h.max_pressure - 1.0),
            h.a,
            h.b
        );
    }
    if let Some(h) = &s.hertz_line {
        println!(
            "Hertz line contact at F' = {:.6e} N/m: a {:.4e} m, p0 {:.6e} Pa ({:+.3} %)",
            h.force_per_length,
            h.a,
            h.max_pressure,
            100.0 * (s.max_pressure / h.max_pressure - 1.0)
        );
    }
    if let Some(t) = &s.tangential {
        println!(
            "tangential contact ({}, {}), mu = {}",
            t.tangential_problem, t.tangential_method, t.mu
        );
        println!(
            "  force x, y        {:>14.6e} N, {:.6e} N  (|F|/(mu Fn) = {:.4})",
            t.tangential_force_x,
            t.tangential_force_y,
            t.tangential_force_x.hypot(t.tangential_force_y) / (t.mu * s.normal_force)
        );
        if let Some(m) = t.spin_moment {
            println!("  spin moment       {m:>14.6e} N m");
        }
        if let (Some(x), Some(y)) = (t.creepage_x, t.creepage_y) {
            println!(
                "  creepages         xi = {x:.6e}, eta = {y:.6e}, spin = {:.6e} 1/m",
                t.spin.unwrap_or(0.0)
            );
        }
        if let (Some(x), Some(y)) = (t.shift_x, t.shift_y) {
            println!("  shift             ({x:.6e}, {y:.6e}) m");
        }
        if let (Some(a), Some(sl)) = (t.adhesion_elements, t.slip_elements) {
            println!("  adhesion / slip   {a} / {sl} elements");
        }
        if let Some(p) = t.frictional_power {
            let unit = if t.tangential_problem == "rolling" {
                "N (power per unit rolling speed)"
            } else {
                "J (work of the shift)"
            };
            println!("  friction loss     {p:>14.6e} {unit}");
        }
        if let Some(o) = t.outer_iterations {
            println!(
                "  K != 0: {o} normal-tangential outer iterations (the normal results above include the coupling)"
            );
        }
        if let Some(i) = t.tangential_iterations {
            println!(
                "  solver            {i} iterations, {} Newton iterations on forces, {:.3} ms",
                t.newton_iterations.unwrap_or(0),
                1e3 * t.tangential_time_s
            );
        }
    }
}

/// Every file `contact --out` may write (one run's output set).
pub const OUTPUT_SET: &[&str] = &[
    "pressure.csv",
    "pressure.png",
    "pressure_profile.png",
    "summary.json",
    "traction.csv",
    "traction_x.png",
    "traction_y.png",
    "adhesion_slip.png",
];

/// Write pressure.csv, pressure.png, pressure_profile.png and summary.json (and the tangential
/// files) into the run's output set.
pub fn write_outputs(dir: &RunOutput, outcome: &CaseOutcome) -> Result<()> {
    let sol = &outcome.solution;
    let g = sol.grid;
    output::write_csv(
        &dir.path("pressure.csv"),
        &["x_m", "y_m", "p_pa"],
        (0..g.len()).map(|k| {
            let (x, y) = g.centre(k);
            vec![x, y, sol.pressure[k]]
        }),
    )?;
    let mpa: Vec<f64> = sol.pressure.iter().map(|p| p * 1e-6).collect();
    let outside: Vec<bool> = sol.pressure.iter().map(|&p| p <= 0.0).collect();
    let title = format!(
        "contact pressure (normal force {:.4e} N)",
        outcome.summary.normal_force
    );
    if g.ny == 1 {
        // A single row (a 2-D, line-contact case): the profile is the whole picture.
        plot::panels(
            &dir.path("pressure.png"),
            &[plot::Panel {
                title: format!("{title}, single grid row (2-D case)"),
                x_label: "x [mm]".into(),
                y_label: "pressure p [MPa]".into(),
                series: vec![plot::Series::steps(
                    "boundary elements",
                    &(0..g.nx)
                        .map(|ix| (g.x(ix) * 1e3, mpa[ix]))
                        .collect::<Vec<_>>(),
                    g.dx * 1e3,
                )],
            }],
        )?;
    } else {
        plot::map(
            &dir.path("pressure.png"),
            &plot::Map {
                title,
                x_label: "x [mm]",
                y_label: "y [mm]",
                field: plot::Field::on_grid_mm(&g, &mpa),
                scale: plot::Scale::Continuous {
                    label: "p [MPa]",
                    exterior: Some((&outside, "no contact (p = 0)")),
                },
            },
        )?;
    }
    plot::panels(&dir.path("pressure_profile.png"), &[profile_panel(outcome)])?;
    if let Some(t) = &outcome.tangential {
        write_tangential_outputs(dir, t)?;
    }
    output::write_summary(&dir.path("summary.json"), &outcome.summary)
}

/// State code of an element in outputs: 0 exterior, 1 adhesion, 2 slip.
fn state_code(s: ElementState) -> f64 {
    match s {
        ElementState::Exterior => 0.0,
        ElementState::Adhesion => 1.0,
        ElementState::Slip => 2.0,
    }
}

/// traction.csv, traction_x.png, traction_y.png and adhesion_slip.png.
fn write_tangential_outputs(dir: &RunOutput, t: &TangentialSolution) -> Result<()> {
    let g = t.grid;
    output::write_csv(
        &dir.path("traction.csv"),
        &["x_m", "y_m", "px_pa", "py_pa", "state", "slip_x", "slip_y"],
        (0..g.len()).map(|k| {
            let (x, y) = g.centre(k);
            vec![
                x,
                y,
                t.traction_x[k],
                t.traction_y[k],
                state_code(t.state[k]),
                t.slip_x[k],
                t.slip_y[k],
            ]
        }),
    )?;
    let field = |values: &[f64]| -> Vec<f64> { values.iter().map(|v| v * 1e-6).collect() };
    let (px, py) = (field(&t.traction_x), field(&t.traction_y));
    // (file, title, axis label, values in MPa) of the two traction components.
    let tractions = [
        (
            "traction_x.png",
            "tangential traction p_x",
            "p_x [MPa]",
            &px,
        ),
        (
            "traction_y.png",
            "tangential traction p_y",
            "p_y [MPa]",
            &py,
        ),
    ];
    let exterior: Vec<bool> = t
        .state
        .iter()
        .map(|&s| s == ElementState::Exterior)
        .collect();
    let states: Vec<f64> = t.state.iter().map(|&s| state_code(s)).collect();
    let grid_field = |values| plot::Field::on_grid_mm(&g, values);
    if g.ny == 1 {
        // A single row (2-D case, e.g. Carter's): line plots along x.
        let cells = |values: &[f64]| -> Vec<(f64, f64)> {
            (0..g.nx).map(|ix| (g.x(ix) * 1e3, values[ix])).collect()
        };
        for (name, title, label, values) in tractions {
            plot::panels(
                &dir.path(name),
                &[plot::Panel {
                    title: format!("{title}, single grid row (2-D case)"),
                    x_label: "x [mm]".into(),
                    y_label: label.into(),
                    series: vec![plot::Series::steps(
                        "boundary elements",
                        &cells(values),
                        g.dx * 1e3,
                    )],
                }],
            )?;
        }
        let count = |want: ElementState| t.state.iter().filter(|&&s| s == want).count();
        plot::panels(
            &dir.path("adhesion_slip.png"),
            &[plot::Panel {
                title: format!(
                    "element state along x (single grid row): {} adhesion, {} slip elements",
                    count(ElementState::Adhesion),
                    count(ElementState::Slip)
                ),
                x_label: "x [mm]".into(),
                y_label: "state [0 outside, 1 adhesion, 2 slip]".into(),
                series: vec![plot::Series::steps(
                    "element state",
                    &cells(&states),
                    g.dx * 1e3,
                )],
            }],
        )?;
        return Ok(());
    }
    for (name, title, label, values) in tractions {
        plot::map(
            &dir.path(name),
            &plot::Map {
                title: title.to_string(),
                x_label: "x [mm]",
                y_label: "y [mm]",
                field: grid_field(values),
                scale: plot::Scale::Continuous {
                    label,
                    exterior: Some((&exterior, "outside the contact")),
                },
            },
        )?;
    }
    plot::map(
        &dir.path("adhesion_slip.png"),
        &plot::Map {
            title: "adhesion and slip areas (element count in the legend)".to_string(),
            x_label: "x [mm]",
            y_label: "y [mm]",
            field: grid_field(&states),
            scale: plot::Scale::Categorical(&[
                ("outside the contact", plot::EXTERIOR),
                ("adhesion", plot::RGBColor(44, 160, 44)),
                ("slip", plot::RGBColor(214, 39, 40)),
            ]),
        },
    )?;
    Ok(())
}

/// Pressure along x on the grid row through the centre of pressure, with Hertz's profile
/// p₀√(1 − x²/a²) of the same force when the gap is quadratic.
fn profile_panel(outcome: &CaseOutcome) -> plot::Panel {
    let sol = &outcome.solution;
    let g = sol.grid;
    let yc = sol.centre_of_pressure.1;
    let iy = (((yc - g.y0) / g.dy - 0.5).round().max(0.0) as usize).min(g.ny - 1);
    let bem: Vec<(f64, f64)> = (0..g.nx)
        .map(|ix| (g.x(ix) * 1e3, sol.pressure[iy * g.nx + ix] * 1e-6))
        .collect();
    // Each element carries a constant pressure: drawn as steps.
    let mut series = vec![plot::Series::steps(
        "boundary elements (constant per element)",
        &bem,
        g.dx * 1e3,
    )];
    let hertz_curve = |a: f64, p0: f64| -> Vec<(f64, f64)> {
        (0..=400)
            .map(|k| {
                let x = g.x0 + (g.nx as f64 * g.dx) * k as f64 / 400.0;
                let s = 1.0 - ((x - sol.centre_of_pressure.0) / a).powi(2);
                (x * 1e3, if s > 0.0 { p0 * s.sqrt() * 1e-6 } else { 0.0 })
            })
            .collect()
    };
    if let Some(h) = &outcome.summary.hertz {
        let y = g.y(iy) - yc;
        let scale = (1.0 - (y / h.b).powi(2)).max(0.0).sqrt();
        series.push(plot::Series::reference(
            "Hertz theory, same force",
            hertz_curve(h.a * scale, h.max_pressure * scale),
        ));
    }
    if let Some(h) = &outcome.summary.hertz_line {
        series.push(plot::Series::reference(
            "Hertz line-contact theory, same force per length",
            hertz_curve(h.a, h.max_pressure),
        ));
    }
    plot::Panel {
        title: format!(
            "pressure along x on the grid row through the centre of pressure (y = {:.4} mm)",
            g.y(iy) * 1e3
        ),
        x_label: "x [mm]".into(),
        y_label: "pressure p [MPa]".into(),
        series,
    }
}

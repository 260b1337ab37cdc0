//! `dyncontact modes BRIDGE.toml`: the bridge's modal table, mode shapes and a plot.

use std::path::Path;

use anyhow::{Result, anyhow};

use crate::errors::bad_input;
use crate::output::{self, RunOutput};
use crate::plot;
use sim::config::bridge::Bridge;
use sim::modes::{ModesSummary, summary};

/// Read a file's `[bridge]` block (a bridge file, or any scenario file that has one).
pub fn read_bridge(text: &str) -> Result<Bridge> {
    Ok(sim::config::bridge::parse_bridge_file(text)?)
}

pub fn print_table(s: &ModesSummary) {
    println!("{}", s.bridge);
    println!(
        "{:>5} {:>12} {:>16} {:>14}",
        "n", "beta L", "omega [rad/s]", "f [Hz]"
    );
    for m in &s.modes {
        println!(
            "{:>5} {:>12.8} {:>16.6} {:>14.6}",
            m.n, m.beta_l, m.omega, m.frequency
        );
    }
}

/// Write `mode_shapes.csv` (x and w_1 … w_m at 401 points) and `modes.png` (first 6 modes).
pub fn write_outputs(dir: &RunOutput, b: &Bridge) -> Result<()> {
    let n = b.basis.n_modes();
    let rows = sim::modes::shapes(b, 401).map_err(|e| anyhow!("{e}"))?;
    // Mass-normalised shapes have the unit 1/√kg.
    let names: Vec<String> = std::iter::once("x_m".to_string())
        .chain((1..=n).map(|j| format!("w{j}_1_sqrt_kg")))
        .collect();
    let header: Vec<&str> = names.iter().map(String::as_str).collect();
    let shown = n.min(6);
    let series = (0..shown)
        .map(|j| {
            let f = b.basis.circular_frequencies()[j] / (2.0 * std::f64::consts::PI);
            plot::Series::new(
                format!("mode {} ({f:.2} Hz)", j + 1),
                rows.iter().map(|r| (r[0], r[j + 1])).collect(),
            )
        })
        .collect();
    output::write_csv(&dir.path("mode_shapes.csv"), &header, rows)?;
    plot::panels(
        &dir.path("modes.png"),
        &[plot::Panel {
            title: "mass-normalised mode shapes".into(),
            x_label: "x [m]".into(),
            y_label: "w [1/√kg]".into(),
            series,
        }],
    )
}

/// The files `modes --out` writes (one run's output set).
const OUTPUT_SET: &[&str] = &["mode_shapes.csv", "modes.png", "modes.json"];

pub fn run(text: &str, json: bool, out: Option<&Path>) -> Result<()> {
    let b = read_bridge(text).map_err(bad_input)?;
    let run_out = out
        .map(|dir| RunOutput::create(dir, OUTPUT_SET))
        .transpose()?;
    let s = summary(&b);
    if json {
        println!("{}", output::json_text(&s)?);
    } else {
        print_table(&s);
    }
    if let (Some(dir), Some(run_out)) = (out, run_out) {
        write_outputs(&run_out, &b)?;
        output::write_summary(&run_out.path("modes.json"), &s)?;
        run_out.commit()?;
        if !json {
            println!(
                "wrote {}/mode_shapes.csv, modes.png, modes.json",
                dir.display()
            );
        }
    }
    Ok(())
}

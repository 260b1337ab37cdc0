//! Outputs of a vehicle–bridge run: the time series streamed to `timeseries.csv` as the run
//! advances (nothing of it is held in memory for the whole run), a thinned copy of the rows (at
//! most [`PLOT_ROWS`]) for the plots, and the plots.

use std::path::Path;

use anyhow::Result;
use sim::vehicle_bridge::traction::TractionSample;
use sim::vehicle_bridge::{Simulation, WheelSample};

use crate::output::{CsvStream, RunOutput};
use crate::plot::{self, Panel, Series};

/// Every file a vehicle–bridge run writes (one run's output set).
pub const OUTPUT_SET: &[&str] = &[
    "timeseries.csv",
    "summary.json",
    "contact_force.png",
    "midspan.png",
    "vehicle.png",
    "pressure.png",
    "train.png",
];

/// Rows kept for the plots: beyond this the kept rows are thinned by 2 (every other one) and
/// the recording stride doubles, so a run of any length plots in bounded time and memory.
pub const PLOT_ROWS: usize = 20_000;

/// One recorded row of the time series.
pub struct Row {
    pub t: f64,
    pub midspan: (f64, f64, f64),
    pub wheels: Vec<WheelSample>,
    pub iterations: usize,
    pub traction: Vec<TractionSample>,
}

impl Row {
    fn of(sim: &Simulation, iterations: usize) -> Row {
        Row {
            t: sim.t(),
            midspan: sim.output_point_response(),
            wheels: sim.wheels().to_vec(),
            iterations,
            traction: sim
                .traction()
                .map(|t| t.samples().to_vec())
                .unwrap_or_default(),
        }
    }

    /// The CSV columns of this row (see [`header`]).
    fn values(&self, out: &mut Vec<f64>) {
        sim::vehicle_bridge_series::row(
            self.t,
            self.midspan,
            self.iterations,
            &self.wheels,
            &self.traction,
            out,
        );
    }
}

/// The CSV header for `nw` wheels (with the three traction columns per wheel when
/// `with_traction`).
fn header(nw: usize, with_traction: bool) -> Vec<String> {
    sim::vehicle_bridge_series::columns(nw, with_traction)
}

/// Records the steps it is given: streams each to the CSV and keeps a thinned copy for the
/// plots (the summary's maxima come from the run driver, `sim::vehicle_bridge::run`).
pub struct Recorder {
    csv: Option<CsvStream>,
    line: Vec<f64>,
    /// Rows for the plots: every `stride`-th recorded row.
    pub plot_rows: Vec<Row>,
    stride: usize,
    recorded: usize,
    /// Time of the last recorded row \[s\].
    pub last_t: Option<f64>,
}

impl Recorder {
    /// A recorder streaming to `csv` (none: maxima and plot rows only, as in `bench`).
    pub fn new(sim: &Simulation, csv: Option<&Path>) -> Result<Recorder> {
        let csv = match csv {
            Some(path) => {
                let names = header(sim.wheels().len(), sim.traction().is_some());
                let refs: Vec<&str> = names.iter().map(String::as_str).collect();
                Some(CsvStream::create(path, &refs)?)
            }
            None => None,
        };
        Ok(Recorder {
            csv,
            line: Vec::new(),
            plot_rows: Vec::new(),
            stride: 1,
            recorded: 0,
            last_t: None,
        })
    }

    /// Record the current state (`iterations`: coupling iterations of the last step).
    pub fn record(&mut self, sim: &Simulation, iterations: usize) -> Result<()> {
        let row = Row::of(sim, iterations);
        if let Some(csv) = &mut self.csv {
            row.values(&mut self.line);
            csv.row(&self.line)?;
        }
        self.last_t = Some(row.t);
        if self.recorded.is_multiple_of(self.stride) {
            self.plot_rows.push(row);
            if self.plot_rows.len() > PLOT_ROWS {
                let mut k = 0;
                self.plot_rows.retain(|_| {
                    k += 1;
                    (k - 1) % 2 == 0
                });
                self.stride *= 2;
            }
        }
        self.recorded += 1;
        Ok(())
    }

    /// Flush the CSV to disk; the rows kept for the plots.
    pub fn finish(self) -> Result<Vec<Row>> {
        if let Some(csv) = self.csv {
            csv.finish()?;
        }
        Ok(self.plot_rows)
    }
}

/// contact_force.png, midspan.png, vehicle.png and pressure.png (when there are snapshots).
pub fn write_plots(
    dir: &RunOutput,
    rows: &[Row],
    snapshots: &[(f64, Vec<(f64, f64)>)],
) -> Result<()> {
    let nw = rows.first().map_or(0, |r| r.wheels.len());
    let wheel_series = |f: &dyn Fn(&Row, usize) -> (f64, f64), name: &str| -> Vec<Series> {
        (0..nw)
            .map(|k| {
                Series::new(
                    if nw == 1 {
                        name.to_string()
                    } else {
                        format!("{name} {k}")
                    },
                    rows.iter().map(|r| f(r, k)).collect(),
                )
            })
            .collect()
    };
    plot::panels(
        &dir.path("contact_force.png"),
        &[Panel {
            title: "Contact force against wheel position".into(),
            x_label: "position [m]".into(),
            y_label: "force [kN]".into(),
            series: wheel_series(
                &|r, k| (r.wheels[k].position, 1e-3 * r.wheels[k].contact.force),
                "wheel",
            ),
        }],
    )?;
    plot::panels(
        &dir.path("midspan.png"),
        &[
            Panel {
                title: "Bridge deflection at the output point".into(),
                x_label: "t [s]".into(),
                y_label: "deflection [mm]".into(),
                series: vec![Series::new(
                    "w",
                    rows.iter().map(|r| (r.t, 1e3 * r.midspan.0)).collect(),
                )],
            },
            Panel {
                title: "Bridge acceleration at the output point".into(),
                x_label: "t [s]".into(),
                y_label: "acceleration [m/s²]".into(),
                series: vec![Series::new(
                    "a",
                    rows.iter().map(|r| (r.t, r.midspan.2)).collect(),
                )],
            },
        ],
    )?;
    let mut motion = wheel_series(&|r, k| (r.t, 1e3 * r.wheels[k].wheel_displacement), "wheel");
    motion.extend(wheel_series(
        &|r, k| (r.t, 1e3 * r.wheels[k].body_displacement),
        "body",
    ));
    plot::panels(
        &dir.path("vehicle.png"),
        &[
            Panel {
                title: "Wheel and body displacement (down)".into(),
                x_label: "t [s]".into(),
                y_label: "z [mm]".into(),
                series: motion,
            },
            Panel {
                title: "Body acceleration".into(),
                x_label: "t [s]".into(),
                y_label: "acceleration [m/s²]".into(),
                series: wheel_series(&|r, k| (r.t, r.wheels[k].body_acceleration), "body"),
            },
        ],
    )?;
    if !snapshots.is_empty() {
        plot::panels(
            &dir.path("pressure.png"),
            &[Panel {
                title: "Contact pressure along the track centreline (wheel 0)".into(),
                x_label: "ξ (along track, from the wheel) [mm]".into(),
                y_label: "pressure [MPa]".into(),
                series: snapshots
                    .iter()
                    .map(|(x, p)| {
                        Series::new(
                            format!("x = {x:.2} m"),
                            p.iter().map(|(xi, p)| (1e3 * xi, 1e-6 * p)).collect(),
                        )
                    })
                    .collect(),
            }],
        )?;
    }
    Ok(())
}

/// The train on the bridge at one instant: the deflected track and each vehicle's wheels and
/// body, for `train.png` (schematic vehicles; deflections to scale in mm).
pub struct TrainPicture {
    t: f64,
    /// (x \[m\], deflection \[m\]) of the track along the bridge and 5 m either side.
    track: Vec<(f64, f64)>,
    /// Per vehicle: (x of each wheel \[m\], the wheel's track deflection \[m\]) and the car
    /// body's displacement from its start \[m\].
    vehicles: Vec<(Vec<(f64, f64)>, f64)>,
}

impl TrainPicture {
    /// The picture of `sim` now; `groups` are each vehicle's wheels.
    pub fn of(sim: &Simulation, groups: &[std::ops::Range<usize>]) -> Self {
        let length = sim.scenario().bridge.length();
        let deflection = |x: f64| {
            if (0.0..=length).contains(&x) {
                sim.deflection_at(x).unwrap_or(0.0)
            } else {
                0.0
            }
        };
        // From behind the last wheel to 5 m past the span.
        let last = (0..sim.wheels().len())
            .map(|k| sim.wheel_position(k))
            .fold(0.0f64, f64::min);
        let (x0, x1) = (last.min(0.0) - 3.0, length + 5.0);
        let track = (0..=200)
            .map(|i| {
                let x = x0 + (x1 - x0) * i as f64 / 200.0;
                (x, deflection(x))
            })
            .collect();
        let wheels = sim.wheels();
        let vehicles = groups
            .iter()
            .map(|g| {
                let at: Vec<(f64, f64)> = g
                    .clone()
                    .map(|k| {
                        let x = sim.wheel_position(k);
                        (x, deflection(x))
                    })
                    .collect();
                (at, wheels[g.start].body_displacement)
            })
            .collect();
        Self {
            t: sim.t(),
            track,
            vehicles,
        }
    }
}

/// `train.png`: the train on the bridge at a few instants (y: deflection in mm, downwards
/// plotted down; wheels as ticks on the rail, car bodies as boxes above, schematic).
pub fn write_train_pictures(dir: &RunOutput, pictures: &[TrainPicture]) -> Result<()> {
    let body0: Vec<f64> = pictures
        .first()
        .map(|p| p.vehicles.iter().map(|v| v.1).collect())
        .unwrap_or_default();
    let panels: Vec<Panel> = pictures
        .iter()
        .map(|p| {
            // Boxes 3 … 8 mm above the level rail, moved by the body's displacement.
            let (box_lo, box_hi) = (3.0, 8.0);
            let mut wheels = Vec::new();
            let mut bodies = Vec::new();
            for (i, (at, body)) in p.vehicles.iter().enumerate() {
                for &(x, w) in at {
                    wheels.extend([(x, -1e3 * w), (x, -1e3 * w + 1.5), (f64::NAN, f64::NAN)]);
                }
                let (x0, x1) = (
                    at.first().map_or(0.0, |a| a.0) + 0.8,
                    at.last().map_or(0.0, |a| a.0) - 0.8,
                );
                // The body box moves with the body's displacement from its start (mm).
                let dz = -1e3 * (body - body0.get(i).copied().unwrap_or(*body));
                let (lo, hi) = (box_lo + dz, box_hi + dz);
                bodies.extend([
                    (x0, lo),
                    (x1, lo),
                    (x1, hi),
                    (x0, hi),
                    (x0, lo),
                    (f64::NAN, f64::NAN),
                ]);
            }
            Panel {
                title: format!("train on the bridge at t = {:.3} s", p.t),
                x_label: "x [m] (0 and L: the supports)".into(),
                y_label: "deflection [mm] (vehicles schematic)".into(),
                series: vec![
                    Series::new(
                        "track (deflection)",
                        p.track.iter().map(|&(x, w)| (x, -1e3 * w)).collect(),
                    ),
                    Series::new("wheelsets", wheels),
                    Series::new("car bodies (moving with the body)", bodies),
                ],
            }
        })
        .collect();
    plot::panels(&dir.path("train.png"), &panels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_has_the_traction_columns_after_each_wheel() {
        let h = header(2, true);
        assert_eq!(h.len(), 5 + 2 * 12);
        assert_eq!(h[5 + 8], "max_pressure_0");
        assert_eq!(h[5 + 9], "longitudinal_force_0");
        assert_eq!(h[5 + 12], "position_1");
        assert_eq!(header(1, false)[5..7], ["position", "wheel_z"]);
    }
}

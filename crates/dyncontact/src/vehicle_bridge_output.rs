//! Outputs of a vehicle–bridge run: the time series streamed to `timeseries.csv` as the run
//! advances (nothing of it is held in memory for the whole run), a thinned copy of the rows (at
//! most [`PLOT_ROWS`]) for the plots, and the plots.

use std::path::Path;

use anyhow::Result;
use sim::vehicle_bridge::traction::TractionSample;
use sim::vehicle_bridge::{Simulation, WheelSample};
use sim::vehicle_bridge_series::{SeriesLayout, series_row};

use crate::output::{CsvStream, RunOutput};
use crate::plot::{self, Panel, Series};

/// Every file a vehicle–bridge run writes (one run's output set).
pub const OUTPUT_SET: &[&str] = &[
    "timeseries.csv",
    "summary.json",
    "contact_force.png",
    "midspan.png",
    "vehicle.png",
    "traction.png",
    "pressure.png",
    "train.png",
];

/// Rows kept for the plots: beyond this the kept rows are thinned by 2 (every other one) and
/// the recording stride doubles, so a run of any length plots in bounded time and memory.
pub const PLOT_ROWS: usize = 20_000;

/// One row kept for the plots.
pub struct Row {
    pub t: f64,
    pub midspan: (f64, f64, f64),
    /// (deflection, acceleration) at each response point of `[output] points`.
    pub points: Vec<(f64, f64)>,
    pub wheels: Vec<WheelSample>,
    pub traction: Vec<TractionSample>,
}

impl Row {
    fn of(sim: &Simulation) -> Row {
        Row {
            t: sim.t(),
            midspan: sim.output_point_response(),
            points: (0..sim.output_points().len())
                .map(|i| {
                    let (d, _, a) = sim.point_response(i);
                    (d, a)
                })
                .collect(),
            wheels: sim.wheels().to_vec(),
            traction: sim
                .traction()
                .map(|t| t.samples().to_vec())
                .unwrap_or_default(),
        }
    }
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
                let names = SeriesLayout::of(sim).columns();
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
        if let Some(csv) = &mut self.csv {
            series_row(sim, iterations, &mut self.line);
            csv.row(&self.line)?;
        }
        self.last_t = Some(sim.t());
        if self.recorded.is_multiple_of(self.stride) {
            self.plot_rows.push(Row::of(sim));
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

/// What the plots say about the run besides its rows.
pub struct PlotContext<'a> {
    /// Position of the output point along the bridge \[m\] and the bridge's length \[m\].
    pub output_point: f64,
    pub bridge_length: f64,
    /// The response points of `[output] points` \[m\].
    pub points: &'a [f64],
    /// Static wheel loads \[N\] (the contact force at rest).
    pub static_loads: &'a [f64],
    /// The contact model's name (`bem` snapshots are piecewise constant per element).
    pub contact_model: &'a str,
}

/// The output point named for a title: "x = 12.5 m (midspan of 25 m)".
fn output_point_words(ctx: &PlotContext) -> String {
    let x = ctx.output_point;
    let l = ctx.bridge_length;
    let place = if (x - 0.5 * l).abs() <= 1e-9 * l {
        format!("midspan of the {} m bridge", fmt_num(l))
    } else {
        format!("{:.3} L of the {} m bridge", x / l, fmt_num(l))
    };
    format!("x = {} m, {place}", fmt_num(x))
}

/// A number without redundant trailing zeros (4 significant decimals at most).
fn fmt_num(v: f64) -> String {
    let s = format!("{v:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// contact_force.png, midspan.png, vehicle.png, traction.png (runs with traction) and
/// pressure.png (when a pressure snapshot has contact pressure). One abscissa for the run:
/// position along the track — each wheel's own position for its contact force (so features of
/// the track line up across wheels), the leading wheel's position (x₀ + V t) for the rest.
pub fn write_plots(
    dir: &RunOutput,
    rows: &[Row],
    snapshots: &[(f64, Vec<(f64, f64)>)],
    ctx: &PlotContext,
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
    // The abscissa of the time series: the leading wheel's position [m].
    let lead = |r: &Row| r.wheels.first().map_or(r.t, |w| w.position);
    let x_lead = "position of the leading wheel (wheel 0) [m]";
    let positions = rows
        .iter()
        .flat_map(|r| r.wheels.iter().map(|w| w.position));
    let (x0, x1) = positions.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    });
    let mut force = wheel_series(
        &|r, k| (r.wheels[k].position, 1e-3 * r.wheels[k].contact.force),
        "contact force, wheel",
    );
    // The static load line(s): one per distinct static load.
    let mut loads: Vec<f64> = ctx.static_loads.to_vec();
    loads.sort_by(f64::total_cmp);
    loads.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * b.abs());
    for w in &loads {
        force.push(Series::reference(
            format!("static wheel load {:.2} kN", 1e-3 * w),
            vec![(x0, 1e-3 * w), (x1, 1e-3 * w)],
        ));
    }
    plot::panels(
        &dir.path("contact_force.png"),
        &[Panel {
            title: format!(
                "Wheel–rail contact force ({} contact) against each wheel's position",
                ctx.contact_model
            ),
            x_label: "position of the wheel along the track [m]".into(),
            y_label: "contact force [kN]".into(),
            series: force,
        }],
    )?;
    let point = output_point_words(ctx);
    // The output point, then each response point (one curve each).
    let bridge_series = |name: &str, out: &dyn Fn(&Row) -> f64, at: &dyn Fn(&Row, usize) -> f64| {
        let mut series = vec![Series::new(
            if ctx.points.is_empty() {
                name.to_string()
            } else {
                format!("output point, x = {} m", fmt_num(ctx.output_point))
            },
            rows.iter().map(|r| (lead(r), out(r))).collect(),
        )];
        series.extend(ctx.points.iter().enumerate().map(|(i, &x)| {
            Series::new(
                format!("x = {} m", fmt_num(x)),
                rows.iter().map(|r| (lead(r), at(r, i))).collect(),
            )
        }));
        series
    };
    let and_points = if ctx.points.is_empty() {
        ""
    } else {
        " and the response points"
    };
    plot::panels(
        &dir.path("midspan.png"),
        &[
            Panel {
                title: format!("Bridge deflection at the output point ({point}){and_points}"),
                x_label: x_lead.into(),
                y_label: "deflection, down positive [mm]".into(),
                series: bridge_series("deflection", &|r| 1e3 * r.midspan.0, &|r, i| {
                    1e3 * r.points[i].0
                }),
            },
            Panel {
                title: format!("Bridge acceleration at the output point ({point}){and_points}"),
                x_label: x_lead.into(),
                y_label: "acceleration [m/s²]".into(),
                series: bridge_series("acceleration", &|r| r.midspan.2, &|r, i| r.points[i].1),
            },
        ],
    )?;
    // Displacements from the static start (the first row): the static spring compression
    // (tens of mm) would otherwise hide the wheel's motion (about a mm).
    let first = rows.first();
    let rel = |k: usize, f: &dyn Fn(&WheelSample) -> f64| -> f64 {
        first.map_or(0.0, |r| f(&r.wheels[k]))
    };
    plot::panels(
        &dir.path("vehicle.png"),
        &[
            Panel {
                title: "Car body displacement from its static position (down positive)".into(),
                x_label: x_lead.into(),
                y_label: "body displacement [mm]".into(),
                series: wheel_series(
                    &|r, k| {
                        let z = r.wheels[k].body_displacement;
                        (lead(r), 1e3 * (z - rel(k, &|w| w.body_displacement)))
                    },
                    "body on wheel",
                ),
            },
            Panel {
                title: "Wheel displacement from its static position (down positive)".into(),
                x_label: x_lead.into(),
                y_label: "wheel displacement [mm]".into(),
                series: wheel_series(
                    &|r, k| {
                        let z = r.wheels[k].wheel_displacement;
                        (lead(r), 1e3 * (z - rel(k, &|w| w.wheel_displacement)))
                    },
                    "wheel",
                ),
            },
            Panel {
                title: "Car body acceleration".into(),
                x_label: x_lead.into(),
                y_label: "body acceleration [m/s²]".into(),
                series: wheel_series(
                    &|r, k| (lead(r), r.wheels[k].body_acceleration),
                    "body on wheel",
                ),
            },
        ],
    )?;
    if rows.first().is_some_and(|r| !r.traction.is_empty()) {
        let per_wheel = |f: &dyn Fn(&TractionSample) -> f64, name: &str| -> Vec<Series> {
            (0..nw)
                .map(|k| {
                    Series::new(
                        if nw == 1 {
                            name.to_string()
                        } else {
                            format!("{name}, wheel {k}")
                        },
                        rows.iter()
                            .map(|r| (lead(r), r.traction.get(k).map_or(f64::NAN, f)))
                            .collect(),
                    )
                })
                .collect()
        };
        plot::panels(
            &dir.path("traction.png"),
            &[
                Panel {
                    title: "Longitudinal creep force on the wheel (> 0 forward)".into(),
                    x_label: x_lead.into(),
                    y_label: "F_x [kN]".into(),
                    series: per_wheel(&|t| 1e-3 * t.longitudinal_force, "F_x"),
                },
                Panel {
                    title: "Longitudinal creepage ξ = (V − ωR)/V".into(),
                    x_label: x_lead.into(),
                    y_label: "creepage ξ [-]".into(),
                    series: per_wheel(&|t| t.creepage, "creepage"),
                },
                Panel {
                    title: "Fraction of the contact area in adhesion (0: full slip)".into(),
                    x_label: x_lead.into(),
                    y_label: "adhesion fraction [-]".into(),
                    series: per_wheel(&|t| t.adhesion_fraction, "adhesion fraction"),
                },
            ],
        )?;
    }
    // Snapshots with contact pressure (none for rigid contact, whose pressure is not
    // modelled, nor while the wheel is off the rail).
    let with_pressure: Vec<&(f64, Vec<(f64, f64)>)> = snapshots
        .iter()
        .filter(|(_, p)| p.iter().any(|&(_, p)| p > 0.0))
        .collect();
    if !with_pressure.is_empty() {
        let piecewise = ctx.contact_model.starts_with("bem");
        plot::panels(
            &dir.path("pressure.png"),
            &[Panel {
                title: format!(
                    "Contact pressure along the track centreline, wheel 0 ({} contact{})",
                    ctx.contact_model,
                    if piecewise {
                        ", constant per element"
                    } else {
                        ""
                    }
                ),
                x_label: "ξ (along the track, from the wheel) [mm]".into(),
                y_label: "pressure [MPa]".into(),
                series: with_pressure
                    .iter()
                    .map(|(x, p)| {
                        let label = format!("wheel 0 at x = {x:.2} m");
                        let cells: Vec<(f64, f64)> =
                            p.iter().map(|(xi, p)| (1e3 * xi, 1e-6 * p)).collect();
                        if piecewise && cells.len() > 1 {
                            let width = cells[1].0 - cells[0].0;
                            Series::steps(label, &cells, width)
                        } else {
                            Series::new(label, cells)
                        }
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
    /// The moving forces (axles without a vehicle model): (x, w(x)) \[m\].
    forces: Vec<(f64, f64)>,
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
        // From behind the last wheel or force to 5 m past the span (or past the first force).
        let scenario = sim.scenario();
        let force_at: Vec<f64> = scenario
            .moving_forces
            .iter()
            .map(|f| f.position + scenario.speed * sim.t())
            .collect();
        let last = (0..sim.wheels().len())
            .map(|k| sim.wheel_position(k))
            .chain(force_at.iter().copied())
            .fold(0.0f64, f64::min);
        let first = force_at.iter().copied().fold(length, f64::max);
        let (x0, x1) = (last.min(0.0) - 3.0, first + 5.0);
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
        let forces = force_at.iter().map(|&x| (x, deflection(x))).collect();
        Self {
            t: sim.t(),
            track,
            vehicles,
            forces,
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
    // One abscissa for every picture: each track from the first picture's rear end (the
    // train moves forward, so its last wheel is furthest back then) to the common far end;
    // off the span the track is rigid (w = 0), so the extension is the level rail.
    let x_from = pictures
        .iter()
        .filter_map(|p| p.track.first().map(|t| t.0))
        .fold(f64::INFINITY, f64::min);
    let x_to = pictures
        .iter()
        .filter_map(|p| p.track.last().map(|t| t.0))
        .fold(f64::NEG_INFINITY, f64::max);
    let panels: Vec<Panel> = pictures
        .iter()
        .map(|p| {
            let mut track: Vec<(f64, f64)> = p.track.iter().map(|&(x, w)| (x, -1e3 * w)).collect();
            if track.first().is_some_and(|t| t.0 > x_from) {
                track.insert(0, (x_from, 0.0));
            }
            if track.last().is_some_and(|t| t.0 < x_to) {
                track.push((x_to, 0.0));
            }
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
            // Moving forces as arrows pointing down onto the rail.
            let mut forces = Vec::new();
            for &(x, w) in &p.forces {
                let y = -1e3 * w;
                forces.extend([
                    (x, y + 8.0),
                    (x, y),
                    (f64::NAN, f64::NAN),
                    (x - 0.4, y + 1.5),
                    (x, y),
                    (x + 0.4, y + 1.5),
                    (f64::NAN, f64::NAN),
                ]);
            }
            let mut series = vec![
                Series::new("track (deflection)", track),
                Series::new("wheelsets", wheels),
                Series::new("car bodies (moving with the body)", bodies),
            ];
            if !forces.is_empty() {
                series.push(Series::new("moving forces (axle loads)", forces));
            }
            Panel {
                title: format!("train on the bridge at t = {:.3} s", p.t),
                x_label: "x [m] (0 and L: the supports)".into(),
                y_label: "deflection [mm] (vehicles schematic)".into(),
                series,
            }
        })
        .collect();
    plot::panels(&dir.path("train.png"), &panels)
}

//! Trains: an ordered list of rail vehicles (module [`vehicle`]) crossing the bridge.
//!
//! A train is described by its vehicles in running order; vehicle i's leading axle is the sum
//! of the `length`s of the vehicles before it behind the train's leading axle. This module
//! holds the description (parameters, geometry, statics); the scenario keys are parsed in
//! `config`, the dynamics are in `vehicle_bridge`, the moving-force passages in `beam`.
//! SI units.
//!
//! * [`hslm`]: HSLM-A1 … A10 of EN 1991-2 Annex E;
//! * [`hslm_vehicles`]: the same trains with (assumed) vehicle models, for interaction sweeps;
//! * [`presets`]: real trains with published parameters (by name);
//! * [`bogie_vehicle`]: the bogie vehicle's matrices and rigid-track natural frequencies;
//! * [`articulated`]: the articulated train's matrices (bodies sharing bogies);
//! * [`multibody`]: what both share (their matrices, spring–damper assembly).

pub mod articulated;
pub mod bogie_vehicle;
pub mod hslm;
pub mod hslm_vehicles;
pub mod multibody;
pub mod presets;
pub mod vehicle;

#[cfg(test)]
pub(crate) mod fixtures;

pub use vehicle::{
    Articulated, ArticulatedBody, ArticulatedBogie, BogieVehicle, MovingForces, QuarterCar,
    SprungMass, UniformArticulated, VehicleSpec,
};

/// A train: a name and its vehicles in running order (`count` already expanded).
#[derive(Debug, Clone, PartialEq)]
pub struct Train {
    /// Name (a preset name, or the scenario's).
    pub name: String,
    /// The vehicles, leading vehicle first.
    pub vehicles: Vec<VehicleSpec>,
}

/// One axle of a train.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Axle {
    /// Distance behind the train's leading axle \[m\] (≥ 0).
    pub offset: f64,
    /// Static axle load \[N\] (downwards), from the vehicle's statics.
    pub load: f64,
}

/// A train description that is not physically valid; names the key as written in a train
/// table.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("train vehicle {vehicle} (`{key}` = {value}): {reason}")]
pub struct TrainError {
    /// Index of the vehicle in running order.
    pub vehicle: usize,
    /// The key.
    pub key: &'static str,
    /// Its value.
    pub value: f64,
    /// The allowed range.
    pub reason: &'static str,
}

impl Train {
    /// The axles in running order (offsets non-decreasing) with their static loads at
    /// gravity `g` \[m/s²\]: each vehicle's statics with the suspension forces of a symmetric
    /// body (a bogie vehicle's body rests half on each bogie, a bogie half on each wheelset;
    /// an articulated train's end bogies carry half a body, its inner bogies two halves).
    pub fn axles(&self, g: f64) -> Result<Vec<Axle>, TrainError> {
        let mut axles = Vec::new();
        let mut start = 0.0;
        for (i, v) in self.vehicles.iter().enumerate() {
            validate(i, v)?;
            for (offset, load) in vehicle_axles(v, g) {
                axles.push(Axle {
                    offset: start + offset,
                    load,
                });
            }
            start += vehicle_length(v);
        }
        Ok(axles)
    }

    /// First axle to last axle \[m\].
    pub fn length(&self) -> f64 {
        self.axles(9.81)
            .ok()
            .and_then(|a| a.last().map(|a| a.offset))
            .unwrap_or(0.0)
    }

    /// Total mass \[kg\] (moving forces: their loads / 9.81 m/s²).
    pub fn mass(&self) -> f64 {
        self.vehicles.iter().map(vehicle_mass).sum()
    }
}

fn vehicle_length(v: &VehicleSpec) -> f64 {
    match v {
        VehicleSpec::MovingForces(m) => m.length,
        VehicleSpec::QuarterCar(q) => q.length,
        VehicleSpec::SprungMass(s) => s.length,
        VehicleSpec::BogieVehicle(b) => b.length,
        VehicleSpec::Articulated(a) => a.length,
    }
}

fn vehicle_mass(v: &VehicleSpec) -> f64 {
    match v {
        VehicleSpec::MovingForces(m) => m.axle_loads.iter().sum::<f64>() / 9.81,
        VehicleSpec::QuarterCar(q) => q.wheel_mass + q.body_mass,
        VehicleSpec::SprungMass(s) => s.body_mass,
        VehicleSpec::BogieVehicle(b) => b.body_mass + 2.0 * b.bogie_mass + 4.0 * b.wheelset_mass,
        VehicleSpec::Articulated(a) => a.mass(),
    }
}

/// (offset behind the vehicle's leading axle, static load) of each axle.
fn vehicle_axles(v: &VehicleSpec, g: f64) -> Vec<(f64, f64)> {
    match v {
        VehicleSpec::MovingForces(m) => m
            .axle_positions
            .iter()
            .copied()
            .zip(m.axle_loads.iter().copied())
            .collect(),
        VehicleSpec::QuarterCar(q) => vec![(0.0, (q.wheel_mass + q.body_mass) * g)],
        VehicleSpec::SprungMass(s) => vec![(0.0, s.body_mass * g)],
        VehicleSpec::BogieVehicle(b) => {
            let load = (0.25 * b.body_mass + 0.5 * b.bogie_mass + b.wheelset_mass) * g;
            [
                0.0,
                b.wheelbase,
                b.bogie_spacing,
                b.bogie_spacing + b.wheelbase,
            ]
            .into_iter()
            .map(|x| (x, load))
            .collect()
        }
        VehicleSpec::Articulated(a) => a.axles(g),
    }
}

/// Range checks of one vehicle's geometry and masses.
fn validate(i: usize, v: &VehicleSpec) -> Result<(), TrainError> {
    let err = |key, value, reason| TrainError {
        vehicle: i,
        key,
        value,
        reason,
    };
    let positive = |key: &'static str, value: f64| {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(err(key, value, "must be positive and finite"))
        }
    };
    let non_negative = |key: &'static str, value: f64| {
        if value.is_finite() && value >= 0.0 {
            Ok(())
        } else {
            Err(err(key, value, "must be non-negative and finite"))
        }
    };
    match v {
        VehicleSpec::MovingForces(m) => {
            non_negative("length", m.length)?;
            if m.axle_positions.is_empty() || m.axle_positions.len() != m.axle_loads.len() {
                return Err(err(
                    "axle_positions",
                    m.axle_positions.len() as f64,
                    "one position per axle load, at least one axle",
                ));
            }
            let mut previous = 0.0;
            for &x in &m.axle_positions {
                non_negative("axle_positions", x)?;
                if x < previous {
                    return Err(err("axle_positions", x, "must be non-decreasing"));
                }
                previous = x;
            }
            for &f in &m.axle_loads {
                if !f.is_finite() {
                    return Err(err("axle_loads", f, "must be finite"));
                }
            }
        }
        VehicleSpec::QuarterCar(q) => {
            non_negative("length", q.length)?;
            positive("wheel_mass", q.wheel_mass)?;
            non_negative("body_mass", q.body_mass)?;
        }
        VehicleSpec::SprungMass(s) => {
            non_negative("length", s.length)?;
            positive("body_mass", s.body_mass)?;
        }
        VehicleSpec::BogieVehicle(b) => {
            for (key, value) in [
                ("body_mass", b.body_mass),
                ("bogie_spacing", b.bogie_spacing),
                ("wheelbase", b.wheelbase),
                ("wheelset_mass", b.wheelset_mass),
            ] {
                positive(key, value)?;
            }
            non_negative("bogie_mass", b.bogie_mass)?;
            if b.bogie_spacing < b.wheelbase {
                return Err(err(
                    "bogie_spacing",
                    b.bogie_spacing,
                    "must be at least the wheelbase",
                ));
            }
            if b.length < b.bogie_spacing + b.wheelbase {
                return Err(err(
                    "length",
                    b.length,
                    "must be at least bogie_spacing + wheelbase",
                ));
            }
        }
        VehicleSpec::Articulated(a) => {
            if a.bodies.is_empty() {
                return Err(err("bodies", 0.0, "at least one body"));
            }
            if a.bogies.len() != a.bodies.len() + 1 {
                return Err(err(
                    "bodies",
                    a.bodies.len() as f64,
                    "one bogie more than bodies (the inner bogies shared)",
                ));
            }
            for body in &a.bodies {
                positive("body_mass", body.mass)?;
                // A body's supports: f ≥ 0 ahead of and r ≥ 0 behind its centre of gravity,
                // f + r > 0 (the bogie spacing of a uniform rake is f + r).
                positive("bogie_spacing", body.front + body.rear)?;
                non_negative("bogie_spacing", body.front)?;
                non_negative("bogie_spacing", body.rear)?;
            }
            for bogie in &a.bogies {
                positive("wheelbase", bogie.wheelbase)?;
                positive("wheelset_mass", bogie.wheelset_mass)?;
            }
            for (body, (ahead, behind)) in a.bodies.iter().zip(a.bogies.iter().zip(&a.bogies[1..]))
            {
                let span = body.front + body.rear;
                if span < 0.5 * (ahead.wheelbase + behind.wheelbase) {
                    return Err(err(
                        "bogie_spacing",
                        span,
                        "must be at least the wheelbase (neighbouring bogies would overlap)",
                    ));
                }
            }
            // The last axle is a running sum of the spans: 1e-12 relative of round-off allowed
            // (43 × 18.7 + 3 sums to 807.1000000000001).
            let last = a.last_axle();
            if a.length < last - 1e-12 * last {
                return Err(err(
                    "length",
                    a.length,
                    "must reach at least the last axle (bodies × bogie_spacing + wheelbase)",
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::train::fixtures::{chain, manchester};

    #[test]
    fn bogie_vehicle_statics_give_the_published_wheelset_load() {
        let t = Train {
            name: "two cars".into(),
            vehicles: vec![VehicleSpec::BogieVehicle(manchester()); 2],
        };
        let axles = t.axles(9.81).unwrap();
        assert_eq!(axles.len(), 8);
        // (32,000 + 2 × 2,615 + 4 × 1,813) × 9.81 / 4 = 109.09 kN.
        for a in &axles {
            assert!((a.load / 1e3 - 109.09).abs() < 0.005, "{}", a.load);
        }
        let offsets: Vec<f64> = axles.iter().map(|a| a.offset).collect();
        assert_eq!(offsets[..4], [0.0, 2.56, 19.0, 21.56]);
        // The preset car is 25 m from its leading axle to the next car's.
        assert!((offsets[4] - 25.0).abs() < 1e-12 && (t.length() - 46.56).abs() < 1e-12);
        assert!((t.mass() - 2.0 * 44_482.0).abs() < 1e-9);
        let total: f64 = axles.iter().map(|a| a.load).sum();
        assert!((total - t.mass() * 9.81).abs() < 1e-6 * total);
    }

    #[test]
    fn articulated_statics_balance_the_weight() {
        let a = chain(3).build();
        let t = Train {
            name: "articulated".into(),
            vehicles: vec![VehicleSpec::Articulated(a)],
        };
        let axles = t.axles(9.81).unwrap();
        assert_eq!(axles.len(), 8);
        let total: f64 = axles.iter().map(|a| a.load).sum();
        assert!((total - t.mass() * 9.81).abs() < 1e-6 * total);
        // Inner bogies carry a whole body, end bogies half of one.
        let end = (0.5 * (0.5 * 28_000.0 + 3000.0) + 2000.0) * 9.81;
        let inner = (0.5 * (28_000.0 + 3000.0) + 2000.0) * 9.81;
        assert!((axles[0].load - end).abs() < 1e-6 && (axles[2].load - inner).abs() < 1e-6);
    }

    #[test]
    fn bad_geometry_names_the_key() {
        let mut b = manchester();
        b.length = 10.0;
        let t = Train {
            name: "x".into(),
            vehicles: vec![VehicleSpec::BogieVehicle(b)],
        };
        let e = t.axles(9.81).unwrap_err();
        assert_eq!(e.key, "length");
        assert!(e.to_string().contains("bogie_spacing + wheelbase"), "{e}");
    }
}

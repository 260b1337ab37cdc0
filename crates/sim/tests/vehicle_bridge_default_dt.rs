//! The default time step of a vehicle–bridge scenario follows the fastest contact mode
//! (`sim::config::vehicle_bridge::default_dt`): checked against the closed-form Hertz contact
//! stiffness k_c = 3W/(2δ) (references.md §C4.1) of the wheel's static load.

use std::path::Path;

use sim::config::vehicle_bridge::{
    DEFAULT_DT, DEFAULT_DT_CONTACT, DEFAULT_DT_CONTACT_FIRST_ORDER, DEFAULT_GEOMETRY as G,
};
use sim::config::{self, LoadOptions, ScenarioConfig};

/// The time step the reader picks for one bare wheel of `mass` kg.
fn chosen_dt(mass: f64, model: &str, method: &str) -> f64 {
    let text = format!(
        "kind = \"vehicle_bridge\"\n[bridge]\nlength = 25.0\nEI = 8.323e9\nmass_per_length = 2303.0\nmodes = 4\n\
         [vehicle]\nspeed = 30.0\n[[vehicle.wheels]]\nposition = 0.0\nwheel_mass = {mass:e}\n\
         [contact]\nmodel = \"{model}\"\n[integrator]\nmethod = \"{method}\"\nduration = 0.01\n"
    );
    match config::load(&text, Path::new("."), &LoadOptions::default()) {
        Ok(ScenarioConfig::VehicleBridge(v)) => v.scenario.dt,
        Ok(_) => panic!("not a vehicle_bridge scenario"),
        Err(e) => panic!("{e}"),
    }
}

/// f_c = √(k_c/m)/2π of a bare wheel of mass m on its Hertz spring at W = m g.
fn contact_frequency(mass: f64) -> f64 {
    let load = mass * sim::vehicle_bridge::GRAVITY;
    let material = halfspace::Material::identical(G.youngs_modulus, G.poisson_ratio).unwrap();
    let hertz = halfspace::Hertz::elliptic(
        0.5 / G.wheel_radius,
        0.5 / G.rail_profile_radius,
        material.e_star,
        load,
    )
    .unwrap();
    (1.5 * load / hertz.approach / mass).sqrt() / std::f64::consts::TAU
}

#[test]
fn light_wheels_get_a_step_that_resolves_their_contact_mode() {
    for mass in [1.0, 10.0, 100.0] {
        let f_c = contact_frequency(mass);
        let expected = (DEFAULT_DT_CONTACT / f_c).min(DEFAULT_DT);
        let dt = chosen_dt(mass, "hertz", "newmark");
        println!("{mass} kg: f_c = {f_c:.1} Hz, dt = {dt:e} s (closed form {expected:e})");
        assert!(
            expected < DEFAULT_DT,
            "{mass} kg should need a shorter step"
        );
        // The closed-form Hertz approach and the law's static_approach agree to round-off.
        assert!((dt / expected - 1.0).abs() < 1e-9, "{dt} vs {expected}");
        let first_order = chosen_dt(mass, "hertz", "backward_euler");
        assert!((first_order / (DEFAULT_DT_CONTACT_FIRST_ORDER / f_c) - 1.0).abs() < 1e-9);
        // BEM contact has the Hertz stiffness to its discretisation error: same rule.
        assert!((chosen_dt(mass, "bem", "newmark") / expected - 1.0).abs() < 1e-9);
    }
}

#[test]
fn heavy_wheels_rigid_contact_and_radau5_keep_the_default_step() {
    // A 1.8 t wheelset: f_c ≈ 150 Hz, Δt f_c = 0.015 at 1e-4 s.
    let f_c = contact_frequency(1800.0);
    assert!(f_c * DEFAULT_DT < DEFAULT_DT_CONTACT, "{f_c}");
    assert_eq!(chosen_dt(1800.0, "hertz", "newmark"), DEFAULT_DT);
    assert_eq!(chosen_dt(1.0, "rigid", "newmark"), DEFAULT_DT);
    assert_eq!(chosen_dt(1.0, "hertz", "radau5"), DEFAULT_DT);
}

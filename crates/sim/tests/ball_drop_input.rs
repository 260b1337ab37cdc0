//! Bad input gives an error that names the scenario key, never a panic.

use halfspace::Body;
use sim::ball_drop::{
    BallDrop, BallDropError, BallShape, ForceModel, Integrator, IntegratorSettings,
};

fn key_of(s: &BallDrop) -> String {
    match s.simulate(false) {
        Err(BallDropError::InvalidParameter { key, .. }) => key.to_string(),
        Err(BallDropError::Material { key, .. }) => key.to_string(),
        other => panic!("expected a parameter error, got {other:?}"),
    }
}

#[test]
fn invalid_parameters_name_their_key() {
    let base = BallDrop::steel_ball;
    let cases: Vec<(BallDrop, &str)> = vec![
        (
            BallDrop {
                mass: -1.0,
                ..base()
            },
            "[ball] mass",
        ),
        (
            BallDrop {
                mass: f64::NAN,
                ..base()
            },
            "[ball] mass",
        ),
        (
            BallDrop {
                shape: BallShape::Sphere { radius: 0.0 },
                ..base()
            },
            "[ball] radius",
        ),
        (
            BallDrop {
                shape: BallShape::Ellipsoid {
                    radius_x: 0.01,
                    radius_y: f64::INFINITY,
                },
                ..base()
            },
            "[ball] radius_y",
        ),
        (
            BallDrop {
                height: -0.1,
                ..base()
            },
            "[initial] height",
        ),
        (
            BallDrop {
                velocity: f64::NAN,
                ..base()
            },
            "[initial] velocity",
        ),
        (
            BallDrop {
                duration: 0.0,
                ..base()
            },
            "duration",
        ),
        (
            BallDrop {
                gravity: -9.81,
                ..base()
            },
            "gravity",
        ),
        (
            BallDrop {
                damping: -1.0,
                ..base()
            },
            "[contact] damping",
        ),
        (
            BallDrop {
                surface: Body::Elastic { e: 210e9, nu: 0.5 },
                ..base()
            },
            "[surface]",
        ),
        (
            BallDrop {
                ball: Body::Elastic { e: -1.0, nu: 0.3 },
                ..base()
            },
            "[ball]",
        ),
        (
            BallDrop {
                surface: Body::Rigid,
                ..base()
            },
            "[ball]/[surface]",
        ),
        (
            BallDrop {
                model: ForceModel::Bem {
                    elements: 2,
                    tol: 1e-8,
                },
                ..base()
            },
            "[contact] elements",
        ),
        (
            BallDrop {
                output_interval: Some(0.0),
                ..base()
            },
            "[output] interval",
        ),
        (
            BallDrop {
                integrator: Integrator::from_name(
                    "verlet",
                    &IntegratorSettings {
                        dt: -1e-6,
                        ..IntegratorSettings::default()
                    },
                )
                .unwrap(),
                ..base()
            },
            "[integrator] dt",
        ),
        (
            BallDrop {
                integrator: Integrator::from_name(
                    "rk4",
                    &IntegratorSettings {
                        dt: 1e-12,
                        ..IntegratorSettings::default()
                    },
                )
                .unwrap(),
                ..base()
            },
            "[integrator] dt",
        ),
        (
            BallDrop {
                damping: 1.0,
                integrator: Integrator::from_name("newmark", &IntegratorSettings::default())
                    .unwrap(),
                ..base()
            },
            "[contact] damping",
        ),
    ];
    for (scenario, key) in cases {
        assert_eq!(key_of(&scenario), key);
    }
}

#[test]
fn unknown_methods_and_misplaced_settings_are_rejected() {
    let err = Integrator::from_name("rk45", &IntegratorSettings::default()).unwrap_err();
    assert!(err.to_string().contains("[integrator] method"), "{err}");
    assert!(
        err.to_string().contains("radau5"),
        "lists the known methods: {err}"
    );
    let with_param = IntegratorSettings {
        parameters: vec![("rho_inf", 0.5)],
        ..IntegratorSettings::default()
    };
    assert!(Integrator::from_name("radau5", &with_param).is_err());
    assert!(Integrator::from_name("generalized_alpha", &with_param).is_ok());
    let bad_rho = IntegratorSettings {
        parameters: vec![("rho_inf", 1.5)],
        ..IntegratorSettings::default()
    };
    assert!(Integrator::from_name("generalized_alpha", &bad_rho).is_err());
    let flight = IntegratorSettings {
        dt_flight: Some(1e-3),
        ..IntegratorSettings::default()
    };
    assert!(Integrator::from_name("dopri5", &flight).is_err());
    let guard = IntegratorSettings {
        guard_step: Some(1e-6),
        ..IntegratorSettings::default()
    };
    assert!(Integrator::from_name("verlet", &guard).is_err());
}

/// `integrator.atol = 0` with an adaptive method is refused naming the key (the state starts
/// with zero components, so the step control would have no error scale: before, Radau5
/// failed at t = 0 with "singular iteration matrix").
#[test]
fn zero_atol_is_refused_for_adaptive_methods() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let text = std::fs::read_to_string(path.join("ball_drop_steel.toml"))
        .unwrap()
        .replace("atol = 1e-12", "atol = 0.0");
    let message = match sim::config::load(&text, &path, &Default::default()) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("atol = 0 accepted"),
    };
    assert!(
        message.contains("integrator.atol") || message.contains("[integrator] atol"),
        "{message}"
    );
}

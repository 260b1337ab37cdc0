//! Reliability (issue 9): sizes checked before allocating, physical ranges of EI, ρA and L,
//! and the stability limit of the explicit methods checked before a moving-load run starts.

use beam::{
    AnalyticBeam, BeamError, FeBeam, ModalBasis, ModalDamping, ModalIntegrator, MovingLoadSettings,
    MovingLoads, PointSupport, Section, Support, SupportKind, UniformBeam, simulate_moving_loads,
};
use integrate::structural::StructuralMethod;

const L: f64 = 25.0;
const EI: f64 = 8.323e9;
const RHO_A: f64 = 2303.0;

fn bridge() -> UniformBeam {
    UniformBeam::new(L, EI, RHO_A).unwrap()
}

#[test]
fn huge_mode_counts_are_refused_before_allocating() {
    for modes in [100_000, 20_000_000] {
        let err = AnalyticBeam::new(Support::SimplySupported, bridge(), modes).unwrap_err();
        assert!(
            matches!(err, BeamError::TooLarge { name: "n_modes", value, .. } if value == modes),
            "{err:?}"
        );
        assert!(err.to_string().contains("bytes"), "{err}");
    }
}

#[test]
fn huge_element_counts_are_refused_with_the_memory_needed() {
    let sections = [Section {
        length: L,
        bending_stiffness: EI,
        mass_per_length: RHO_A,
    }];
    let supports = [
        PointSupport {
            x: 0.0,
            kind: SupportKind::Pinned,
        },
        PointSupport {
            x: L,
            kind: SupportKind::Pinned,
        },
    ];
    let err = FeBeam::new(&sections, &supports, &[], 20_000_000).unwrap_err();
    let BeamError::TooLarge { bytes_required, .. } = err else {
        panic!("{err:?}")
    };
    // Six dense matrices of n = 2 (elements + 1) rows: 48 n² bytes.
    let n = 2.0 * (20_000_000.0 + 1.0);
    assert!((bytes_required / (48.0 * n * n) - 1.0).abs() < 1e-12);
    assert!(FeBeam::new(&sections, &supports, &[], 100).is_ok());
}

#[test]
fn unphysical_beam_properties_name_the_quantity_and_range() {
    for (beam, name) in [
        (UniformBeam::new(L, 1e-299, RHO_A), "bending_stiffness"),
        (UniformBeam::new(L, 1e300, RHO_A), "bending_stiffness"),
        (UniformBeam::new(L, EI, 1e-200), "mass_per_length"),
        (UniformBeam::new(1e-9, EI, RHO_A), "length"),
        (UniformBeam::new(1e9, EI, RHO_A), "length"),
    ] {
        let err = beam.unwrap_err();
        assert!(
            matches!(err, BeamError::OutOfRange { name: n, .. } if n == name),
            "{err:?}"
        );
        assert!(err.to_string().contains("physical range"), "{err}");
    }
}

#[test]
fn explicit_moving_load_above_the_stability_limit_is_refused_up_front() {
    // 200 modes of the 25 m bridge: ω_200 = (200π/L)² √(EI/ρA) (references.md §D1.6), so the
    // central-difference limit 2/ω_200 ≈ 1.7 µs is far below dt = 1e-4 s.
    let basis = AnalyticBeam::new(Support::SimplySupported, bridge(), 200).unwrap();
    let omega_200 = (200.0 * std::f64::consts::PI / L).powi(2) * (EI / RHO_A).sqrt();
    let loads = MovingLoads::single(1e5, 30.0).unwrap();
    for method in [
        StructuralMethod::central_difference(),
        StructuralMethod::StormerVerlet,
    ] {
        let settings = MovingLoadSettings {
            integrator: ModalIntegrator::Structural(method),
            ..MovingLoadSettings::new(1e-4, 0.0)
        };
        let err =
            simulate_moving_loads(&basis, &ModalDamping::Undamped, &loads, &settings, &[12.5])
                .unwrap_err();
        let BeamError::StepAboveStabilityLimit {
            limit, omega_max, ..
        } = err
        else {
            panic!("{err:?}")
        };
        assert!(
            (omega_max / omega_200 - 1.0).abs() < 1e-9,
            "{omega_max} vs {omega_200}"
        );
        assert!((limit * omega_200 / 2.0 - 1.0).abs() < 1e-9, "{limit}");
        assert!(err.to_string().contains("implicit method"), "{err}");
    }
    // Below the limit the explicit run starts and finishes (12 modes, dt = 0.9 × 2/ω_12).
    let basis = AnalyticBeam::new(Support::SimplySupported, bridge(), 12).unwrap();
    let omega_max = basis.circular_frequencies()[11];
    let settings = MovingLoadSettings {
        integrator: ModalIntegrator::Structural(StructuralMethod::central_difference()),
        output_every: 100,
        ..MovingLoadSettings::new(0.9 * 2.0 / omega_max, 0.0)
    };
    let r =
        simulate_moving_loads(&basis, &ModalDamping::Undamped, &loads, &settings, &[12.5]).unwrap();
    assert!(r.deflection.iter().all(|w| w.is_finite()));
    // Implicit methods have no limit: 200 modes at dt = 1e-4 s are accepted.
    let basis = AnalyticBeam::new(Support::SimplySupported, bridge(), 200).unwrap();
    let settings = MovingLoadSettings {
        integrator: ModalIntegrator::Structural(StructuralMethod::average_acceleration()),
        output_every: 100,
        ..MovingLoadSettings::new(1e-3, 0.0)
    };
    assert!(
        simulate_moving_loads(&basis, &ModalDamping::Undamped, &loads, &settings, &[12.5]).is_ok()
    );
}

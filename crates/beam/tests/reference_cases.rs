//! The reference-case harness of the moving-load bridge solver: one table of published values
//! (Frýba's undamped moving-force table, references.md §D1.1: the maximum midspan deflection /
//! δ_st during the passage and in the free vibration after it, at speed parameters α) run with
//! every method — the analytic simply supported modes and the finite-element modes, each
//! stepped by the exact piecewise-linear modal step and by Newmark's average acceleration.
//!
//! Tolerance: the table is rounded to 4 decimals (5e-5); 20-mode truncation ≈ 1.2e-5 δ_st; the
//! FE frequency error of the first modes ≈ 1e-9; Newmark's period error at Δt = T₁/4000 is
//! (ω_j Δt)²/12 ≈ 2e-6 (j = 1) to 3e-4 (j = 5) of each mode's share, which is itself ≤ 1e-2
//! for j ≥ 3 — together ≤ 1e-4. Hence 2e-4 for every method.

use std::f64::consts::PI;

use beam::closed_form::{speed_for_parameter, ss_midspan_static_deflection};
use beam::{
    AnalyticBeam, FeBeam, ModalBasis, ModalDamping, ModalIntegrator, MovingLoadSettings,
    MovingLoads, PointSupport, Section, Support, SupportKind, UniformBeam, simulate_moving_loads,
};
use integrate::StructuralMethod;

/// Frýba's example bridge (references.md §D1.3): L = 25 m, EI = 2.87e9·2.90 N m²,
/// ρA = 2303 kg/m, F = 56.4 kN.
const L: f64 = 25.0;
const EI: f64 = 2.87e9 * 2.90;
const RHO_A: f64 = 2303.0;
const FORCE: f64 = 56.4e3;
const MODES: usize = 20;

/// When the maximum is taken.
#[derive(Clone, Copy, Debug)]
enum Phase {
    /// While the force is on the span.
    Passage,
    /// During one period T₁ of free vibration after it left.
    Free,
}

/// One row: speed parameter α, phase, table value of max |w(L/2)| / δ_st, source.
struct Row {
    alpha: f64,
    phase: Phase,
    value: f64,
    source: &'static str,
}

const ROWS: [Row; 5] = [
    Row {
        alpha: 0.5,
        phase: Phase::Passage,
        value: 1.7054,
        source: "Frýba (1972) table, α = 0.5",
    },
    Row {
        alpha: 0.5,
        phase: Phase::Free,
        value: 1.3101,
        source: "Frýba (1972) table, α = 0.5, free vibration",
    },
    Row {
        alpha: 0.618,
        phase: Phase::Passage,
        value: 1.7317,
        source: "Frýba (1972) table, α = 0.618",
    },
    Row {
        alpha: 1.0,
        phase: Phase::Passage,
        value: 1.5481,
        source: "Frýba (1972) table, α = 1",
    },
    Row {
        alpha: 1.0,
        phase: Phase::Free,
        value: 1.5481,
        source: "Frýba (1972) table, α = 1, free vibration",
    },
];

const TOLERANCE: f64 = 2e-4;

fn bases() -> Vec<(&'static str, Box<dyn ModalBasis>)> {
    let beam = UniformBeam::new(L, EI, RHO_A).unwrap();
    let analytic = AnalyticBeam::new(Support::SimplySupported, beam, MODES).unwrap();
    let supports = [0.0, L].map(|x| PointSupport {
        x,
        kind: SupportKind::Pinned,
    });
    let section = [Section {
        length: L,
        bending_stiffness: EI,
        mass_per_length: RHO_A,
    }];
    let fe = FeBeam::new(&section, &supports, &[], 60)
        .unwrap()
        .modes(MODES)
        .unwrap();
    vec![("analytic", Box::new(analytic)), ("fe", Box::new(fe))]
}

#[test]
fn every_method_reproduces_the_moving_force_table() {
    let beam = UniformBeam::new(L, EI, RHO_A).unwrap();
    let d_st = ss_midspan_static_deflection(FORCE, L, EI);
    let steppers = [
        ("exact step", ModalIntegrator::default()),
        (
            "newmark",
            ModalIntegrator::Structural(StructuralMethod::average_acceleration()),
        ),
    ];
    let mut failures = Vec::new();
    let mut checked = 0;
    for (basis_name, basis) in bases() {
        let t1 = 2.0 * PI / basis.circular_frequencies()[0];
        for (stepper_name, integrator) in &steppers {
            for alpha in [0.5, 0.618, 1.0] {
                let c = speed_for_parameter(&beam, alpha).unwrap();
                let loads = MovingLoads::single(FORCE, c).unwrap();
                let settings = MovingLoadSettings {
                    integrator: *integrator,
                    ..MovingLoadSettings::new(t1 / 4000.0, t1)
                };
                let r = simulate_moving_loads(
                    basis.as_ref(),
                    &ModalDamping::Undamped,
                    &loads,
                    &settings,
                    &[0.5 * L],
                )
                .unwrap();
                for row in ROWS.iter().filter(|r| r.alpha == alpha) {
                    let (t0, t_end) = match row.phase {
                        Phase::Passage => (0.0, r.exit_time),
                        Phase::Free => (r.exit_time, r.exit_time + t1),
                    };
                    let got = r.max_abs_deflection_between(0, t0, t_end).unwrap() / d_st;
                    checked += 1;
                    if (got - row.value).abs() > TOLERANCE {
                        failures.push(format!(
                            "[{basis_name}, {stepper_name}] α = {alpha} {:?}: {got:.6}, {} gives {} ± {TOLERANCE}",
                            row.phase, row.source, row.value
                        ));
                    }
                }
            }
        }
    }
    assert_eq!(checked, ROWS.len() * 4);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

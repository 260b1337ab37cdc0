//! HSLM-A1 … A10, the universal dynamic trains of EN 1991-2 Annex E (Table E.4, Figure E.8;
//! references.md §T1), as moving-force trains.
//!
//! Each train: power car, end coach, N articulated intermediate coaches, end coach, power car;
//! every axle carries the point force P. The geometry, from the leading axle:
//!
//! * power car: four axles 3 m, 11 m, 3 m apart (two bogies of 3 m wheelbase, 11 m between
//!   their inner axles);
//! * 3.525 m from the power car's last axle to the end coach's first axle;
//! * end coach: an outer bogie of axle spacing d whose first axle is 3.525/2 m behind the
//!   coupling point between power car and end coach, and the first articulation bogie whose
//!   centre is D behind that coupling point: its first axle is D − 1.5 d − 1.7625 m behind
//!   the outer bogie's second axle;
//! * N + 1 articulation bogies (axle spacing d) shared by neighbouring coaches, their centres
//!   D apart;
//! * the rear end coach and power car mirror the front.
//!
//! Axles: 8 + 2 (N + 3) (A1: N = 18, 50 axles; A10: N = 11, 36 axles). First axle to last:
//! 37.525 + (N + 2) D \[m\] (A1: 397.525 m). The regular coach length D is what makes the
//! train resonate a bridge of first frequency n₀ at v_i = n₀ D / i.
//!
//! The geometry equals the axle lists published with CALDINTAV for all ten trains, and the
//! power-car and end-coach geometry that of TrainLoad's HSLM-A builder (references.md §T1;
//! unit test `the_geometry_equals_the_published_caldintav_trains`).

use super::{MovingForces, Train, VehicleSpec};

/// One HSLM-A train's parameters (EN 1991-2 Table E.4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HslmParameters {
    /// Number of intermediate coaches N.
    pub coaches: usize,
    /// Coach length D \[m\].
    pub coach_length: f64,
    /// Bogie axle spacing d \[m\].
    pub axle_spacing: f64,
    /// Point force P per axle \[N\].
    pub point_force: f64,
}

/// Table E.4 of EN 1991-2: A1 … A10 (N, D \[m\], d \[m\], P \[kN\]).
pub const HSLM_A: [(usize, f64, f64, f64); 10] = [
    (18, 18.0, 2.0, 170.0),
    (17, 19.0, 3.5, 200.0),
    (16, 20.0, 2.0, 180.0),
    (15, 21.0, 3.0, 190.0),
    (14, 22.0, 2.0, 170.0),
    (13, 23.0, 2.0, 180.0),
    (13, 24.0, 2.0, 190.0),
    (12, 25.0, 2.5, 190.0),
    (11, 26.0, 2.0, 210.0),
    (11, 27.0, 2.0, 210.0),
];

/// Power-car axle spacings \[m\] (Figure E.8).
const POWER_CAR: [f64; 3] = [3.0, 11.0, 3.0];
/// From the power car's last axle to the end coach's first axle \[m\] (Figure E.8).
const POWER_CAR_TO_END_COACH: f64 = 3.525;

/// The parameters of HSLM-A`number` (1 … 10).
pub fn parameters(number: usize) -> Option<HslmParameters> {
    let (coaches, coach_length, axle_spacing, force_kn) = *HSLM_A.get(number.checked_sub(1)?)?;
    Some(HslmParameters {
        coaches,
        coach_length,
        axle_spacing,
        point_force: force_kn * 1e3,
    })
}

/// The train `HSLM-A1` … `HSLM-A10` by name (case-insensitive, `HSLM-A3` or `A3`).
pub fn by_name(name: &str) -> Option<Train> {
    let upper = name.trim().to_ascii_uppercase();
    let number = upper
        .strip_prefix("HSLM-")
        .unwrap_or(&upper)
        .strip_prefix('A')?
        .parse::<usize>()
        .ok()?;
    parameters(number).map(|p| train(&format!("HSLM-A{number}"), p))
}

/// All ten trains, A1 first.
pub fn all() -> Vec<Train> {
    (1..=10).filter_map(|i| by_name(&format!("A{i}"))).collect()
}

/// The axle offsets behind the leading axle \[m\] of an HSLM-A train with `p`'s geometry.
pub fn axle_offsets(p: HslmParameters) -> Vec<f64> {
    let (d, big_d) = (p.axle_spacing, p.coach_length);
    let end_coach_gap = big_d - 1.5 * d - 0.5 * POWER_CAR_TO_END_COACH;
    let mut gaps: Vec<f64> = POWER_CAR.to_vec();
    gaps.extend([POWER_CAR_TO_END_COACH, d, end_coach_gap]);
    for i in 0..=p.coaches {
        gaps.push(d);
        if i < p.coaches {
            gaps.push(big_d - d);
        }
    }
    gaps.extend([end_coach_gap, d, POWER_CAR_TO_END_COACH]);
    gaps.extend(POWER_CAR.iter().rev());
    let mut offsets = Vec::with_capacity(gaps.len() + 1);
    offsets.push(0.0);
    for g in gaps {
        let last = *offsets.last().unwrap_or(&0.0);
        offsets.push(last + g);
    }
    offsets
}

/// HSLM-A with parameters `p` as one moving-force vehicle named `name`.
pub fn train(name: &str, p: HslmParameters) -> Train {
    let axle_positions = axle_offsets(p);
    let span = axle_positions.last().copied().unwrap_or(0.0);
    Train {
        name: name.to_string(),
        vehicles: vec![VehicleSpec::MovingForces(MovingForces {
            length: span,
            axle_loads: vec![p.point_force; axle_positions.len()],
            axle_positions,
        })],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axle_counts_lengths_and_loads_follow_the_standard() {
        for (i, &(n, d_big, d, p)) in HSLM_A.iter().enumerate() {
            let train = by_name(&format!("HSLM-A{}", i + 1)).unwrap();
            let axles = train.axles(9.81).unwrap();
            assert_eq!(axles.len(), 8 + 2 * (n + 3), "A{}", i + 1);
            let span = axles.last().unwrap().offset;
            assert!(
                (span - (37.525 + (n + 2) as f64 * d_big)).abs() < 1e-9,
                "A{}",
                i + 1
            );
            assert!(axles.iter().all(|a| a.load == p * 1e3));
            // Articulation bogies: centres D apart, axle spacing d.
            let first = 8 / 2 + 2; // power car (4) + end coach outer bogie (2)
            assert!((axles[first + 1].offset - axles[first].offset - d).abs() < 1e-12);
            assert!((axles[first + 2].offset - axles[first].offset - d_big).abs() < 1e-9);
        }
        assert_eq!(by_name("HSLM-A1").unwrap().axles(9.81).unwrap().len(), 50);
        assert_eq!(by_name("a10").unwrap().axles(9.81).unwrap().len(), 36);
        assert!((by_name("A1").unwrap().length() - 397.525).abs() < 1e-9);
        assert!(by_name("HSLM-A11").is_none() && by_name("HSLM-B1").is_none());
        assert_eq!(all().len(), 10);
    }

    /// HSLM-A1 and A2 axle positions \[m\] as published in CALDINTAV's train files
    /// `caldintav/trains/a01.def`, `a02.def` (references.md §T1): an independent statement of
    /// the power-car and end-coach geometry (A2 has d = 3.5 m, so the d-dependent end-coach gap
    /// D − 1.5 d − 3.525/2 is exercised).
    const CALDINTAV_A1: [f64; 50] = [
        0.0, 3.0, 14.0, 17.0, 20.525, 22.525, 35.7625, 37.7625, 53.7625, 55.7625, 71.7625, 73.7625,
        89.7625, 91.7625, 107.7625, 109.7625, 125.7625, 127.7625, 143.7625, 145.7625, 161.7625,
        163.7625, 179.7625, 181.7625, 197.7625, 199.7625, 215.7625, 217.7625, 233.7625, 235.7625,
        251.7625, 253.7625, 269.7625, 271.7625, 287.7625, 289.7625, 305.7625, 307.7625, 323.7625,
        325.7625, 341.7625, 343.7625, 359.7625, 361.7625, 375.0, 377.0, 380.525, 383.525, 394.525,
        397.525,
    ];
    const CALDINTAV_A2: [f64; 48] = [
        0.0, 3.0, 14.0, 17.0, 20.525, 24.025, 36.0125, 39.5125, 55.0125, 58.5125, 74.0125, 77.5125,
        93.0125, 96.5125, 112.0125, 115.5125, 131.0125, 134.5125, 150.0125, 153.5125, 169.0125,
        172.5125, 188.0125, 191.5125, 207.0125, 210.5125, 226.0125, 229.5125, 245.0125, 248.5125,
        264.0125, 267.5125, 283.0125, 286.5125, 302.0125, 305.5125, 321.0125, 324.5125, 340.0125,
        343.5125, 359.0125, 362.5125, 374.5, 378.0, 381.525, 384.525, 395.525, 398.525,
    ];
    /// Every CALDINTAV file `a01.def` … `a10.def`: (axles, 7th axle = first axle of the first
    /// articulation bogie \[m\], last axle \[m\], axle load \[N\]).
    const CALDINTAV_SUMMARY: [(usize, f64, f64, f64); 10] = [
        (50, 35.7625, 397.525, 170_000.0),
        (48, 36.0125, 398.525, 200_000.0),
        (46, 37.7625, 397.525, 180_000.0),
        (44, 38.2625, 394.525, 190_000.0),
        (42, 39.7625, 389.525, 170_000.0),
        (40, 40.7625, 382.525, 180_000.0),
        (40, 41.7625, 397.525, 190_000.0),
        (38, 42.5125, 387.525, 190_000.0),
        (36, 43.7625, 375.525, 210_000.0),
        (36, 44.7625, 388.525, 210_000.0),
    ];

    #[test]
    fn the_geometry_equals_the_published_caldintav_trains() {
        for (published, number) in [(&CALDINTAV_A1[..], 1), (&CALDINTAV_A2[..], 2)] {
            let axles = by_name(&format!("A{number}")).unwrap().axles(9.81).unwrap();
            assert_eq!(axles.len(), published.len(), "A{number}");
            for (a, &x) in axles.iter().zip(published) {
                // The files print 4 decimals; every published value is exact in them.
                assert!(
                    (a.offset - x).abs() < 1e-9,
                    "A{number}: {} vs {x}",
                    a.offset
                );
            }
        }
        for (i, &(count, seventh, last, load)) in CALDINTAV_SUMMARY.iter().enumerate() {
            let axles = by_name(&format!("A{}", i + 1))
                .unwrap()
                .axles(9.81)
                .unwrap();
            assert_eq!(axles.len(), count, "A{}", i + 1);
            assert!((axles[6].offset - seventh).abs() < 1e-9, "A{}", i + 1);
            assert!((axles[count - 1].offset - last).abs() < 1e-9, "A{}", i + 1);
            assert!(axles.iter().all(|a| a.load == load), "A{}", i + 1);
        }
    }

    #[test]
    fn the_train_is_symmetric() {
        for t in all() {
            let axles = t.axles(9.81).unwrap();
            let span = axles.last().unwrap().offset;
            for (a, b) in axles.iter().zip(axles.iter().rev()) {
                assert!((a.offset - (span - b.offset)).abs() < 1e-9, "{}", t.name);
            }
        }
    }
}

//! Helpers shared by the track verification tests (`track_reference.rs`,
//! `track_timoshenko.rs`).

use beam::track::{
    RailSection, Receptance, SpringDamper, SupportStack, Track, TrackLayout, TrackSupports,
};

/// The rail `rail` on `bays` sleeper bays of the ballasted preset (its damping scaled by
/// `c_factor`), on ground, `elements_per_bay` rail elements per bay.
pub fn preset_track(
    rail: RailSection,
    bays: usize,
    elements_per_bay: usize,
    c_factor: f64,
) -> Track {
    let d = SupportStack::BALLASTED_HIGH_SPEED_SPACING;
    let half = bays as f64 * d / 2.0;
    let layout = TrackLayout::new(half, 0.0, half, d)
        .unwrap()
        .with_elements_per_bay(elements_per_bay)
        .unwrap();
    let stack = SupportStack::ballasted_high_speed()
        .scaled(1.0, c_factor)
        .unwrap();
    Track::on_ground(rail, layout, &TrackSupports::uniform(stack)).unwrap()
}

/// Frequency of the largest |f(ν)| on a grid from `lo` to `hi` (step `step`), then refined by a
/// grid 40 times finer around it.
pub fn peak(lo: f64, hi: f64, step: f64, f: impl Fn(f64) -> f64) -> f64 {
    let argmax = |a: f64, b: f64, s: f64| {
        let n = ((b - a) / s).round() as usize;
        (0..=n)
            .map(|i| a + i as f64 * s)
            .map(|x| (x, f(x)))
            .fold((a, f64::MIN), |m, p| if p.1 > m.1 { p } else { m })
            .0
    };
    let coarse = argmax(lo, hi, step);
    argmax(coarse - step, coarse + step, step / 40.0)
}

/// The rail `rail` on springs k_f × `spacing` every `spacing` (a Winkler foundation of modulus
/// k_f \[N/m²\] in the limit of close sleepers), 20 m on either side of the middle, 2 elements
/// per bay; and the position of the middle (a bay boundary, mid-way between two sleepers).
fn close_springs(rail: RailSection, k_f: f64, spacing: f64) -> (Track, f64) {
    let stack = SupportStack::direct(SpringDamper::new(k_f * spacing, 0.0).unwrap()).unwrap();
    let layout = TrackLayout::new(20.0, 0.0, 20.0, spacing)
        .unwrap()
        .with_elements_per_bay(2)
        .unwrap();
    let track = Track::on_ground(rail, layout, &TrackSupports::uniform(stack)).unwrap();
    (track, (layout.n_bays() / 2) as f64 * spacing)
}

/// The static displacements of `track` under a force `force` \[N\] on the rail at x.
fn static_under(track: &Track, x: f64, force: f64) -> Vec<f64> {
    let mut load = vec![0.0; track.n_dofs()];
    track.add_point_force(x, force, &mut load).unwrap();
    track.static_solution(&load).unwrap()
}

/// The pinned–pinned resonance of `rail` on 40 bays of the ballasted preset (8 elements per
/// bay): the frequency \[Hz\] of the largest mid-bay point receptance within −10 % … +5 % of
/// the rail's closed-form f_pp at 0.6 m, and |α| there mid-bay and over the sleeper \[m/N\].
pub fn pinned_pinned_peak(rail: RailSection) -> (f64, f64, f64) {
    let track = preset_track(rail, 40, 8, 1.0);
    let f_pp = rail.pinned_pinned_frequency(0.6);
    let r = Receptance::new(&track);
    let x_mid = 20.0 * 0.6;
    let f = peak(0.9 * f_pp, 1.05 * f_pp, 2.0, |f| {
        r.rail(x_mid, x_mid, f).unwrap().norm()
    });
    let at_mid = r.rail(x_mid, x_mid, f).unwrap().norm();
    let at_sleeper = r.rail(x_mid + 0.3, x_mid + 0.3, f).unwrap().norm();
    (f, at_mid, at_sleeper)
}

/// The mean rail deflection \[m\] of [`close_springs`] under `force` over a sleeper and
/// mid-way between two (the two loads in turn); `each(track, x, u)` sees every solution.
pub fn mean_deflection(
    rail: RailSection,
    k_f: f64,
    spacing: f64,
    force: f64,
    mut each: impl FnMut(&Track, f64, &[f64]),
) -> f64 {
    let (track, mid) = close_springs(rail, k_f, spacing);
    let mut w = 0.0;
    for x in [mid, mid + 0.5 * spacing] {
        let u = static_under(&track, x, force);
        w += 0.5 * track.rail_displacement(x, &u).unwrap();
        each(&track, x, &u);
    }
    w
}

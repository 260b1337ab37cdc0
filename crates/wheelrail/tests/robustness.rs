//! Odd profile files never panic: every stage (parse, wheelset, rigid contact, patches)
//! returns a value or an error. (A saw-tooth wheel on a saw-tooth rail also ends in an
//! error, "patch grid ... kept reaching the grid's edge", but takes minutes: not run here.)

use halfspace::Material;
use wheelrail::{
    PatchOptions, ProfileKind, Roll, Side, WheelLoad, Wheelset, WheelsetParams, parse_profile,
    solve_wheel,
};

fn pipeline(wheel: Option<&str>, rail: Option<&str>) -> String {
    let w = match wheel {
        Some(t) => match parse_profile("w", t, ProfileKind::Wheel, 1e-3, 0.0) {
            Ok(p) => p,
            Err(e) => return format!("wheel: {e}"),
        },
        None => wheelrail::s1002(),
    };
    let r = match rail {
        Some(t) => match parse_profile("r", t, ProfileKind::Rail, 1e-3, 0.0) {
            Ok(p) => p,
            Err(e) => return format!("rail: {e}"),
        },
        None => wheelrail::rail_60e1(),
    };
    let ws = match Wheelset::new(w, r, WheelsetParams::default()) {
        Ok(ws) => ws,
        Err(e) => return format!("wheelset: {e}"),
    };
    let mut report = String::new();
    for y in [-0.01, 0.0, 0.004] {
        match ws.contact(y, Roll::Equilibrium) {
            Err(e) => report.push_str(&format!("contact: {e}; ")),
            Ok(c) => {
                let m = Material::identical(210e9, 0.3).unwrap();
                let opts = PatchOptions {
                    nx: 16,
                    ny: 16,
                    ..PatchOptions::default()
                };
                match solve_wheel(
                    &ws,
                    &c,
                    Side::Right,
                    &m,
                    WheelLoad::VerticalForce(5e4),
                    &opts,
                ) {
                    Ok(s) => report.push_str(&format!("{} patches; ", s.patches.len())),
                    Err(e) => report.push_str(&format!("patches: {e}; ")),
                }
            }
        }
    }
    report
}

#[test]
fn odd_profiles_give_errors_not_panics() {
    let flat = "-40 0\n-10 0\n10 0\n40 0\n";
    let tiny = "0 0\n0.1 0.01\n0.2 0.0\n0.3 0.01\n";
    let huge = "-1e6 0\n0 1e6\n1e6 0\n2e6 5\n";
    let saw: String = (-400..=400)
        .map(|k| {
            format!(
                "{} {}\n",
                0.1 * k as f64,
                0.05 * ((k % 7) as f64).abs() + 1e-4 * (k * k) as f64
            )
        })
        .collect();
    let vertical = "-30 20\n-30 10\n0 0\n30 10\n";
    let inf = "-30 20\n-20 1e400\n0 0\n30 10\n";
    let cases: Vec<(Option<&str>, Option<&str>)> = vec![
        (None, Some(flat)),
        (None, Some(tiny)),
        (None, Some(huge)),
        (None, Some(&saw)),
        (None, Some(vertical)),
        (None, Some(inf)),
        (Some(flat), None),
        (Some(tiny), None),
        (Some(huge), None),
        (Some(&saw), None),
    ];
    for (k, (w, r)) in cases.iter().enumerate() {
        let out = pipeline(*w, *r);
        println!("case {k}: {out}");
        assert!(!out.is_empty());
    }
}

//! Times the benchmark workloads of `beam::bench` (run with `--release`).

use std::time::Instant;

fn main() -> Result<(), beam::BeamError> {
    let t = Instant::now();
    let r = beam::bench::moving_load_run(50, 1e-4)?;
    println!(
        "moving load, 50 modes, dt = 1e-4 s, {} samples: {:.3} s (DAF midspan {:.4})",
        r.times.len(),
        t.elapsed().as_secs_f64(),
        r.dynamic_amplification(1)?
    );
    let t = Instant::now();
    let s = beam::bench::mode_evaluation(100, 10_000)?;
    println!(
        "100 modes at 1e4 points: {:.3} s (checksum {s:.6e})",
        t.elapsed().as_secs_f64()
    );
    use beam::{EigenReduction, ModalBasis};
    let exact = 9.869604401089358 * (2.87e9 * 2.90 / (2303.0 * 25f64.powi(4))).sqrt();
    for n in [200, 500, 1000] {
        for r in [
            EigenReduction::Mass,
            EigenReduction::ShiftedStiffness,
            EigenReduction::StiffnessSquareRoot,
            EigenReduction::BandedSubspace,
        ] {
            let t = Instant::now();
            let m = beam::bench::fe_eigen_solve(n, 20, r)?;
            println!(
                "FE eigen-solve, {n} elements, {r:?}: {:.3} s (omega_1 rel. error {:.2e})",
                t.elapsed().as_secs_f64(),
                m.circular_frequencies()[0] / exact - 1.0
            );
        }
    }
    Ok(())
}

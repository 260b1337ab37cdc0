//! The small-grid part of `dyncontact bench contact`: one cold NormCG solve (force
//! prescribed, no sensitivity) over the FFT operator, over the dense sums and over the
//! default operator that picks one of the two per product (`halfspace::NormalInfluence`,
//! references.md §C3.3), on Hertz spheres whose contact patch covers 30 % and 90 % of the
//! grid width.

use std::time::Instant;

use anyhow::{Result, anyhow};
use halfspace::{
    DenseInfluence, FftInfluence, GapShape, Grid, Hertz, InfluenceOperator, Material, NormalLoad,
    NormalSolver, SolverOptions,
};

/// Best of 5 mean wall times \[s\] of `repeats` cold solves.
fn time_solves<A: InfluenceOperator>(
    solver: &mut NormalSolver<A>,
    gap: &[f64],
    force: f64,
    repeats: usize,
) -> Result<f64> {
    let options = SolverOptions {
        warm_start: false,
        sensitivity: false,
        ..Default::default()
    };
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let t = Instant::now();
        for _ in 0..repeats {
            solver
                .solve(gap, NormalLoad::Force(force), &options)
                .map_err(|e| anyhow!("{e}"))?;
        }
        best = best.min(t.elapsed().as_secs_f64() / repeats as f64);
    }
    Ok(best)
}

/// Print the table (module documentation) for the sphere of `bench contact`.
pub fn small_grids(material: Material, radius: f64, force: f64, hertz: &Hertz) -> Result<()> {
    println!(
        "small grids, one cold solve (force prescribed): FFT, dense sums, default (per product; dense share)"
    );
    println!(
        "{:>6} {:>7} {:>6} {:>10} {:>10} {:>10} {:>7}",
        "N", "patch", "iter", "FFT µs", "dense µs", "auto µs", "dense"
    );
    let shape = GapShape::Quadratic {
        a: 0.5 / radius,
        b: 0.5 / radius,
    };
    let e = |err: halfspace::ContactError| anyhow!("{err}");
    for fill in [0.3, 0.9] {
        for n in [4usize, 8, 12, 16, 24, 32] {
            let d = 2.0 * hertz.a / fill / n as f64;
            let grid = Grid::centred(n, n, d, d, 0.0, 0.0).map_err(e)?;
            let gap = shape.sample(&grid).map_err(e)?;
            let repeats = (100_000 / (n * n)).max(3);
            let mut fft =
                NormalSolver::with_operator(FftInfluence::new(grid, &material).map_err(e)?)
                    .map_err(e)?;
            let mut dense =
                NormalSolver::with_operator(DenseInfluence::new(grid, &material).map_err(e)?)
                    .map_err(e)?;
            let mut auto = NormalSolver::new(grid, material).map_err(e)?;
            let t_fft = time_solves(&mut fft, &gap, force, repeats)?;
            let t_dense = time_solves(&mut dense, &gap, force, repeats)?;
            let t_auto = time_solves(&mut auto, &gap, force, repeats)?;
            let iterations = auto
                .solve(
                    &gap,
                    NormalLoad::Force(force),
                    &SolverOptions {
                        warm_start: false,
                        sensitivity: false,
                        ..Default::default()
                    },
                )
                .map_err(e)?
                .iterations;
            println!(
                "{:>6} {:>6.0}% {:>6} {:>10.1} {:>10.1} {:>10.1} {:>6.0}%",
                n,
                100.0 * fill,
                iterations,
                1e6 * t_fft,
                1e6 * t_dense,
                1e6 * t_auto,
                100.0 * auto.operator().dense_products() as f64 / auto.convolutions() as f64
            );
        }
    }
    Ok(())
}

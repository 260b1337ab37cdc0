//! Results independent of the number of rayon threads: the FFT convolution splits rows and
//! columns over the threads (each transform is independent of the split) and NormCG's grid
//! pass splits the grid (element-wise, no sums over parts), so a solve on 1, 2 or 3 threads
//! gives the same pressure bit for bit. The grid (160 × 160) is above the size from which
//! both are split (128 × 128).

use halfspace::{
    GapShape, Grid, Material, NormalLoad, NormalSolution, NormalSolver, SolverOptions,
};

/// A solve with the solver built and run on a pool of `threads` threads.
fn solve_on(threads: usize, gap: &[f64], grid: Grid, load: NormalLoad) -> NormalSolution {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool");
    pool.install(|| {
        let material = Material::identical(210e9, 0.3).unwrap();
        let mut solver = NormalSolver::new(grid, material).unwrap();
        solver.solve(gap, load, &SolverOptions::default()).unwrap()
    })
}

#[test]
fn normcg_is_independent_of_the_thread_count() {
    let grid = Grid::centred(160, 160, 5e-6, 5e-6, 0.0, 0.0).unwrap();
    // A sphere with a waviness: a contact set with holes and an irregular edge.
    let sphere = GapShape::Quadratic { a: 50.0, b: 50.0 }
        .sample(&grid)
        .unwrap();
    let gap: Vec<f64> = sphere
        .iter()
        .enumerate()
        .map(|(k, h)| {
            let (x, y) = grid.centre(k);
            h + 2e-7 * (x / 3e-5).sin() * (y / 4e-5).cos()
        })
        .collect();
    for load in [NormalLoad::Force(40.0), NormalLoad::Approach(2e-6)] {
        let one = solve_on(1, &gap, grid, load);
        assert!(one.converged && one.elements_in_contact > 100, "{load:?}");
        for threads in [2, 3] {
            let other = solve_on(threads, &gap, grid, load);
            assert_eq!(
                one.iterations, other.iterations,
                "{load:?}, {threads} threads"
            );
            assert_eq!(one.approach.to_bits(), other.approach.to_bits());
            assert_eq!(one.dfn_dapproach, other.dfn_dapproach);
            for (a, b) in one.pressure.iter().zip(&other.pressure) {
                assert_eq!(a.to_bits(), b.to_bits(), "{load:?}, {threads} threads");
            }
        }
    }
}

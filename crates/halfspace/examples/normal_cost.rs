//! Work of one cold NormCG solve against one padded FFT convolution, for counting with
//! `perf stat` or `valgrind --tool=callgrind` when wall times are noisy (a loaded machine):
//!
//! ```text
//! cargo build --release --example normal_cost
//! perf stat -e instructions:u,cycles:u target/release/examples/normal_cost 512 setup
//! perf stat -e instructions:u,cycles:u target/release/examples/normal_cost 512 conv 20
//! perf stat -e instructions:u,cycles:u target/release/examples/normal_cost 512 solve
//! ```
//!
//! `setup` builds the solver of the `bench contact` case (Hertz sphere, steel, R = 10 mm,
//! F = 1 kN, contact radius 0.3 of the grid half-width) and a convolution; `conv K` adds K
//! dense convolutions, `solve` one cold solve with the force prescribed (tol 1e-8, no
//! sensitivity). Subtract `setup` from the others. The solve prints its iteration and
//! convolution counts and the approach with all digits (to compare two builds).

use halfspace::convolution::FftConvolution;
use halfspace::influence::circulant_kernel;
use halfspace::{GapShape, Grid, Hertz, Material, NormalLoad, NormalSolver, SolverOptions};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(512);
    let mode = args.get(2).map_or("setup", String::as_str);
    let repeats: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1);
    let material = Material::identical(210e9, 0.3).expect("steel");
    let (radius, force) = (0.01, 1000.0);
    let hertz = Hertz::sphere(radius, material.e_star, force).expect("Hertz sphere");
    let half = hertz.a / 0.3;
    let d = 2.0 * half / n as f64;
    let grid = Grid::centred(n, n, d, d, 0.0, 0.0).expect("grid");
    let gap = GapShape::Quadratic {
        a: 0.5 / radius,
        b: 0.5 / radius,
    }
    .sample(&grid)
    .expect("gap");
    let mut solver = NormalSolver::new(grid, material).expect("solver");
    let mut conv = FftConvolution::new(n, n);
    let spectrum = conv.kernel_spectrum(&circulant_kernel(&material, &grid));
    let p: Vec<f64> = (0..grid.len()).map(|k| (k % 7) as f64).collect();
    let mut u = vec![0.0; grid.len()];
    match mode {
        "setup" => {}
        "conv" => {
            for _ in 0..repeats {
                conv.apply(&spectrum, &p, &mut u);
            }
        }
        "solve" => {
            let options = SolverOptions {
                warm_start: false,
                sensitivity: false,
                ..Default::default()
            };
            for _ in 0..repeats {
                let s = solver
                    .solve(&gap, NormalLoad::Force(force), &options)
                    .expect("solve");
                println!(
                    "iterations {} convolutions {} approach {:.17e}",
                    s.iterations,
                    solver.convolutions(),
                    s.approach
                );
            }
        }
        other => panic!("mode {other}: setup, conv or solve"),
    }
    println!("{}", u[0] + p[1]);
}

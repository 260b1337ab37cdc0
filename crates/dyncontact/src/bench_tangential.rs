//! `dyncontact bench tangential`: steady rolling of CONTACT's `tractcurv` ellipse with
//! creepage prescribed, by the Newton–Krylov solver with the upstream line preconditioner and
//! the nested start, the same with the two-level preconditioner (the default since
//! 2026-11-27, which is the line solve alone below 6000 elements; against the grid size only),
//! the same from zero tractions, with the Jacobi preconditioner and the
//! Gauss–Seidel reference: a 44 × 44 table over ξ (cold and warm starts), the cost against
//! the grid size (44² … 400²: wall and CPU time, iterations, operator products on the fine
//! and on the coarse grids per solve), the 41-point
//! creep curve at 44 × 44, and the shift and transient-rolling solves (which the steady
//! solver does not touch) for before/after comparisons.

use std::time::Instant;

use anyhow::{Result, anyhow};
use halfspace::{
    Creepages, FastsimInput, GapShape, Grid, Hertz, Material, NkPreconditioner, NormalLoad,
    NormalSolution, NormalSolver, RollingLoad, ShiftLoad, SolverOptions, SteadySolver, StepMotion,
    TangentialOptions, TangentialSolver, fastsim,
};

/// Normal force of tractcurv \[N\] and the friction coefficient of the benchmark.
const FN: f64 = 106.7e3;
const MU: f64 = 0.3;

/// The tractcurv ellipse of references.md §C4.1 (A = 0.8 /m, a/b = 0.5, F_n = 106.7 kN,
/// G = 82 GPa, ν = 0.28) on n × n elements over 1.05 × the ellipse, with its normal solution.
fn tractcurv(n: usize) -> Result<(Grid, Material, NormalSolution, Hertz)> {
    let m = Material::from_combined(82e9, 0.28).map_err(|e| anyhow!("{e}"))?;
    let shape = GapShape::Quadratic {
        a: 0.8,
        b: 0.281417,
    };
    let h = shape
        .hertz(&m, NormalLoad::Force(FN))
        .ok_or_else(|| anyhow!("Hertz"))?;
    let grid = Grid::centred(n, n, 2.1 * h.a / n as f64, 2.1 * h.b / n as f64, 0.0, 0.0)
        .map_err(|e| anyhow!("{e}"))?;
    let gap = shape.sample(&grid).map_err(|e| anyhow!("{e}"))?;
    let normal = NormalSolver::new(grid, m)
        .map_err(|e| anyhow!("{e}"))?
        .solve(&gap, NormalLoad::Force(FN), &SolverOptions::default())
        .map_err(|e| anyhow!("{e}"))?;
    Ok((grid, m, normal, h))
}

/// The steady-rolling solvers compared: Newton–Krylov with the upstream line preconditioner
/// (the default until 2026-11-27), with the two-level preconditioner (the default), with the
/// Jacobi preconditioner (the default before), and the Gauss–Seidel reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Solver {
    Nested,
    TwoLevel,
    Line,
    Jacobi,
    GaussSeidel,
}

const SOLVERS: [Solver; 5] = [
    Solver::Nested,
    Solver::TwoLevel,
    Solver::Line,
    Solver::Jacobi,
    Solver::GaussSeidel,
];

fn options(solver: Solver) -> TangentialOptions {
    let (steady_solver, nk_preconditioner) = match solver {
        Solver::Nested | Solver::Line => {
            (SteadySolver::NewtonKrylov, NkPreconditioner::UpstreamLine)
        }
        Solver::TwoLevel => (SteadySolver::NewtonKrylov, NkPreconditioner::TwoLevel),
        Solver::Jacobi => (SteadySolver::NewtonKrylov, NkPreconditioner::Jacobi),
        Solver::GaussSeidel => (SteadySolver::GaussSeidel, NkPreconditioner::default()),
    };
    TangentialOptions {
        steady_solver,
        nk_preconditioner,
        nested_start: matches!(solver, Solver::Nested | Solver::TwoLevel),
        ..Default::default()
    }
}

fn name(solver: Solver) -> &'static str {
    match solver {
        Solver::Nested => "NK",
        Solver::TwoLevel => "NK-2L",
        Solver::Line => "NK-0",
        Solver::Jacobi => "NK-J",
        Solver::GaussSeidel => "GS",
    }
}

fn creep(xi: f64) -> RollingLoad {
    RollingLoad::Creepages(Creepages {
        xi,
        eta: 0.0,
        phi: 0.0,
    })
}

/// CPU time of all threads of this process \[s\] (Linux: the sum of
/// /proc/self/task/*/schedstat, nanoseconds on a CPU; the FFTs run on rayon's threads), or NaN
/// where unavailable. On a shared machine the wall time includes waiting for a core; the CPU
/// time does not.
fn process_cpu_s() -> f64 {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return f64::NAN;
    };
    let mut ns = 0.0;
    for task in tasks.flatten() {
        let path = task.path().join("schedstat");
        if let Some(t) = std::fs::read_to_string(path)
            .ok()
            .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        {
            ns += t;
        }
    }
    1e-9 * ns
}

/// All tables (module documentation).
pub fn tangential() -> Result<()> {
    xi_table()?;
    grid_table()?;
    creep_curve()?;
    shift_and_transient()
}

fn xi_table() -> Result<()> {
    let (grid, m, normal, h) = tractcurv(44)?;
    println!(
        "steady rolling, tractcurv ellipse (a = {:.3} mm, b = {:.3} mm), 44 x 44 grid, {} elements in contact, mu = {MU}, tol 1e-7, {} rayon threads",
        h.a * 1e3,
        h.b * 1e3,
        normal.elements_in_contact,
        rayon::current_num_threads()
    );
    println!(
        "(NK: Newton-Krylov with the upstream line preconditioner and the nested start from coarser grids, the default (on this grid the two-level default is the line solve alone); NK-0: the same from zero tractions, the default before; NK-J: with the Jacobi preconditioner from zero; iterations = Newton steps; GS: Gauss-Seidel reference, iterations = sweeps; products = operator products on this grid, 4 FFT convolutions each; a warm start uses no coarse grid)"
    );
    println!(
        "{:>10} {:>7} {:>13} {:>6} {:>6} {:>6} {:>6} {:>9} {:>7} {:>10}",
        "xi", "solver", "Fx/muFn", "start", "adh", "slip", "iters", "products", "total", "time ms"
    );
    for xi in [1e-5, 3e-4, 1e-3, 3e-3] {
        // NK-2L equals NK on this 44 x 44 grid (below the two-level threshold): not repeated.
        for solver in SOLVERS.into_iter().filter(|&s| s != Solver::TwoLevel) {
            let opts = options(solver);
            for warm in [false, true] {
                let mut ts = TangentialSolver::new(grid, m).map_err(|e| anyhow!("{e}"))?;
                if warm {
                    // Warm start from a neighbouring creepage (as in a creep curve).
                    ts.steady_rolling(&normal.pressure, MU, creep(0.9 * xi), &opts)
                        .map_err(|e| anyhow!("{e}"))?;
                }
                let t = Instant::now();
                let s = ts
                    .steady_rolling(&normal.pressure, MU, creep(xi), &opts)
                    .map_err(|e| anyhow!("{e}"))?;
                let ms = 1e3 * t.elapsed().as_secs_f64();
                println!(
                    "{:>10.1e} {:>7} {:>13.9} {:>6} {:>6} {:>6} {:>6} {:>9} {:>7.1} {:>10.2}",
                    xi,
                    name(solver),
                    s.force_x / (MU * FN),
                    if warm { "warm" } else { "cold" },
                    s.adhesion_elements,
                    s.slip_elements,
                    s.iterations,
                    s.products,
                    s.products as f64 + s.coarse_products.fine_equivalent(grid.len()),
                    ms
                );
            }
        }
    }
    Ok(())
}

/// Cost per solve against the grid size at ξ = 1e-3, cold start. The Gauss–Seidel reference
/// is run up to 100 × 100 (its dense column updates cost O(n_c²) per sweep), the Jacobi
/// Newton–Krylov solver up to 300 × 300. "products" are those on the fine grid; the nested
/// start's coarse-grid products are listed separately and, weighted by the cost of one
/// product (N log N) relative to the fine grid's, added in "total".
fn grid_table() -> Result<()> {
    println!();
    println!("steady rolling, tractcurv, xi = 1e-3, cold start, against the grid size:");
    println!(
        "(NK: nested start with the line solve, the default until 2026-11-27; NK-2L: the same with the two-level preconditioner, the default (issue #18; line solve alone below 6000 elements); NK-0: the same as NK from zero tractions, the default before; products on the fine grid; coarse: products on the coarser grids (elements: products); total: fine + coarse in fine-grid products, weighted by N log N)"
    );
    println!(
        "{:>9} {:>8} {:>7} {:>13} {:>6} {:>6} {:>6} {:>9} {:>7} {:>10} {:>10} {:>11}  coarse",
        "grid",
        "contact",
        "solver",
        "Fx/muFn",
        "adh",
        "slip",
        "iters",
        "products",
        "total",
        "time ms",
        "cpu ms",
        "ms/product"
    );
    for n in [44, 100, 200, 300, 400] {
        let (grid, m, normal, _) = tractcurv(n)?;
        for solver in SOLVERS {
            if (solver == Solver::GaussSeidel && n > 100) || (solver == Solver::Jacobi && n > 300) {
                continue;
            }
            let mut ts = TangentialSolver::new(grid, m).map_err(|e| anyhow!("{e}"))?;
            let (t, cpu) = (Instant::now(), process_cpu_s());
            let s = ts
                .steady_rolling(&normal.pressure, MU, creep(1e-3), &options(solver))
                .map_err(|e| anyhow!("{e}"))?;
            let ms = 1e3 * t.elapsed().as_secs_f64();
            let cpu_ms = 1e3 * (process_cpu_s() - cpu);
            let total = s.products as f64 + s.coarse_products.fine_equivalent(grid.len());
            let coarse: Vec<String> = s
                .coarse_products
                .levels
                .iter()
                .map(|(m, p)| format!("{m}: {p}"))
                .collect();
            println!(
                "{:>9} {:>8} {:>7} {:>13.9} {:>6} {:>6} {:>6} {:>9} {:>7.1} {:>10.1} {:>10.1} {:>11.3}  {}",
                format!("{n} x {n}"),
                normal.elements_in_contact,
                name(solver),
                s.force_x / (MU * FN),
                s.adhesion_elements,
                s.slip_elements,
                s.iterations,
                s.products,
                total,
                ms,
                cpu_ms,
                ms / total.max(1.0),
                coarse.join(", ")
            );
        }
    }
    Ok(())
}

/// The 41-point creep curve ξ = 0 … 0.004 at 44 × 44, each solver warm-started along the
/// curve on one solver object (kernels tabulated and FFTs planned once), against FASTSIM.
fn creep_curve() -> Result<()> {
    let (grid, m, normal, h) = tractcurv(44)?;
    println!();
    for solver in SOLVERS {
        if solver == Solver::Line || solver == Solver::TwoLevel {
            // Identical to NK here: the curve starts at ξ = 0 (zero tractions, no
            // iteration) and warm-starts every later point, so no point uses a coarse grid;
            // the 44 x 44 grid lies below the two-level threshold.
            continue;
        }
        let opts = options(solver);
        let mut ts = TangentialSolver::new(grid, m).map_err(|e| anyhow!("{e}"))?;
        let t = Instant::now();
        let (mut iters, mut products) = (0, 0);
        for k in 0..41 {
            let s = ts
                .steady_rolling(&normal.pressure, MU, creep(0.004 * k as f64 / 40.0), &opts)
                .map_err(|e| anyhow!("{e}"))?;
            iters += s.iterations;
            products += s.products;
        }
        let ms = 1e3 * t.elapsed().as_secs_f64();
        println!(
            "creep curve, 41 points xi = 0 .. 0.004, 44 x 44, {}: {ms:.1} ms ({iters} iterations, {products} products)",
            name(solver)
        );
    }
    let t = Instant::now();
    for k in 0..41 {
        let input = FastsimInput {
            a: h.a,
            b: h.b,
            g: m.g,
            nu: m.nu,
            mu: MU,
            normal_force: FN,
            xi: 0.004 * k as f64 / 40.0,
            eta: 0.0,
            phi: 0.0,
        };
        fastsim(&input, 44, 44).map_err(|e| anyhow!("{e}"))?;
    }
    println!(
        "creep curve, FASTSIM 44 x 44: {:.3} ms",
        1e3 * t.elapsed().as_secs_f64()
    );
    Ok(())
}

/// A shift with the force prescribed (0.5 μ F_n) and 44 transient rolling steps from rest
/// (δq = δx, ξ = 1e-3) on the 44 × 44 tractcurv grid: unchanged by the steady solver.
fn shift_and_transient() -> Result<()> {
    let (grid, m, normal, _) = tractcurv(44)?;
    let opts = TangentialOptions::default();
    println!();
    let mut ts = TangentialSolver::new(grid, m).map_err(|e| anyhow!("{e}"))?;
    let t = Instant::now();
    let s = ts
        .shift(
            &normal.pressure,
            MU,
            ShiftLoad::Forces {
                fx: 0.5 * MU * FN,
                fy: 0.0,
            },
            &opts,
        )
        .map_err(|e| anyhow!("{e}"))?;
    println!(
        "shift, Fx = 0.5 mu Fn, 44 x 44: {:.1} ms ({} sweeps, {} Newton steps)",
        1e3 * t.elapsed().as_secs_f64(),
        s.iterations,
        s.newton_iterations
    );
    let mut ts = TangentialSolver::new(grid, m).map_err(|e| anyhow!("{e}"))?;
    let (mut px, mut py) = (vec![0.0; grid.len()], vec![0.0; grid.len()]);
    let motion = StepMotion {
        delta_q: grid.dx,
        creepages: Creepages {
            xi: 1e-3,
            eta: 0.0,
            phi: 0.0,
        },
        shift: (0.0, 0.0),
    };
    let t = Instant::now();
    let (mut sweeps, mut fx) = (0, 0.0);
    for _ in 0..44 {
        let s = ts
            .transient_step(&normal.pressure, MU, (&px, &py), motion, &opts)
            .map_err(|e| anyhow!("{e}"))?;
        sweeps += s.iterations;
        fx = s.force_x;
        px = s.traction_x;
        py = s.traction_y;
    }
    println!(
        "transient rolling, 44 steps from rest, xi = 1e-3, 44 x 44: {:.1} ms ({sweeps} sweeps), Fx/muFn {:.5} at the end",
        1e3 * t.elapsed().as_secs_f64(),
        fx / (MU * FN)
    );
    Ok(())
}

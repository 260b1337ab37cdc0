//! `dyncontact bench tangential`: steady rolling of a Hertzian case on 44 × 44 elements with
//! creepage prescribed (time and sweeps), and a full creep curve of 41 points.

use std::time::Instant;

use anyhow::{Result, anyhow};
use halfspace::{
    Creepages, FastsimInput, GapShape, Grid, Material, NormalLoad, NormalSolver, RollingLoad,
    SolverOptions, TangentialOptions, TangentialSolver, fastsim,
};

/// The tractcurv ellipse of references.md §C4.1 (A = 0.8 /m, a/b = 0.5, F_n = 106.7 kN,
/// G = 82 GPa, ν = 0.28), μ = 0.3, on 44 × 44 elements over 1.05 × the ellipse.
pub fn tangential() -> Result<()> {
    let m = Material::from_combined(82e9, 0.28).map_err(|e| anyhow!("{e}"))?;
    let shape = GapShape::Quadratic {
        a: 0.8,
        b: 0.281417,
    };
    let fn_ = 106.7e3;
    let mu = 0.3;
    let h = shape
        .hertz(&m, NormalLoad::Force(fn_))
        .ok_or_else(|| anyhow!("Hertz"))?;
    let n = 44;
    let grid = Grid::centred(n, n, 2.1 * h.a / n as f64, 2.1 * h.b / n as f64, 0.0, 0.0)
        .map_err(|e| anyhow!("{e}"))?;
    let gap = shape.sample(&grid).map_err(|e| anyhow!("{e}"))?;
    let normal = NormalSolver::new(grid, m)
        .map_err(|e| anyhow!("{e}"))?
        .solve(&gap, NormalLoad::Force(fn_), &SolverOptions::default())
        .map_err(|e| anyhow!("{e}"))?;
    println!(
        "steady rolling, tractcurv ellipse (a = {:.3} mm, b = {:.3} mm), {n} x {n} grid, {} elements in contact, mu = {mu}, tol 1e-7, {} rayon threads",
        h.a * 1e3,
        h.b * 1e3,
        normal.elements_in_contact,
        rayon::current_num_threads()
    );
    println!(
        "{:>10} {:>10} {:>10} {:>6} {:>6} {:>8} {:>10}",
        "xi", "Fx/muFn", "start", "adh", "slip", "sweeps", "time ms"
    );
    let opts = TangentialOptions::default();
    for xi in [1e-5, 3e-4, 1e-3, 3e-3] {
        let load = RollingLoad::Creepages(Creepages {
            xi,
            eta: 0.0,
            phi: 0.0,
        });
        for warm in [false, true] {
            let mut solver = TangentialSolver::new(grid, m).map_err(|e| anyhow!("{e}"))?;
            if warm {
                // Warm start from a neighbouring creepage (as in a creep curve).
                let prev = RollingLoad::Creepages(Creepages {
                    xi: 0.9 * xi,
                    eta: 0.0,
                    phi: 0.0,
                });
                solver
                    .steady_rolling(&normal.pressure, mu, prev, &opts)
                    .map_err(|e| anyhow!("{e}"))?;
            }
            let t = Instant::now();
            let s = solver
                .steady_rolling(&normal.pressure, mu, load, &opts)
                .map_err(|e| anyhow!("{e}"))?;
            let ms = 1e3 * t.elapsed().as_secs_f64();
            println!(
                "{:>10.1e} {:>10.5} {:>10} {:>6} {:>6} {:>8} {:>10.2}",
                xi,
                s.force_x / (mu * fn_),
                if warm { "warm" } else { "cold" },
                s.adhesion_elements,
                s.slip_elements,
                s.iterations,
                ms
            );
        }
    }
    // A full creep curve: 41 points ξ = 0 … 0.004, warm-started.
    let mut solver = TangentialSolver::new(grid, m).map_err(|e| anyhow!("{e}"))?;
    let t = Instant::now();
    let mut sweeps = 0;
    for k in 0..41 {
        let xi = 0.004 * k as f64 / 40.0;
        let s = solver
            .steady_rolling(
                &normal.pressure,
                mu,
                RollingLoad::Creepages(Creepages {
                    xi,
                    eta: 0.0,
                    phi: 0.0,
                }),
                &opts,
            )
            .map_err(|e| anyhow!("{e}"))?;
        sweeps += s.iterations;
    }
    let exact_ms = 1e3 * t.elapsed().as_secs_f64();
    let t = Instant::now();
    for k in 0..41 {
        let input = FastsimInput {
            a: h.a,
            b: h.b,
            g: m.g,
            nu: m.nu,
            mu,
            normal_force: fn_,
            xi: 0.004 * k as f64 / 40.0,
            eta: 0.0,
            phi: 0.0,
        };
        fastsim(&input, n, n).map_err(|e| anyhow!("{e}"))?;
    }
    let fastsim_ms = 1e3 * t.elapsed().as_secs_f64();
    println!(
        "creep curve, 41 points xi = 0 .. 0.004: exact {exact_ms:.1} ms ({sweeps} sweeps), FASTSIM {n} x {n} {fastsim_ms:.3} ms"
    );
    Ok(())
}

//! Tests of the frozen-set model (module `reuse`).

use super::{BASIS, FrozenSet, Responses, SHAPE_CONVOLUTIONS_AFTER, invert3};
use crate::grid::Grid;
use crate::material::Material;
use crate::normcg::{NormalLoad, NormalSolver, SolverOptions};

/// The entering check of `predict` (one convolution of Σ_k a_k y_k, skipped when the bound
/// max |Δg| + Σ_k |a_k| U_k stays below the least distance) refuses exactly when visiting
/// every element off the set finds one whose predicted distance
/// e_r − Δg_i + Σ_k a_k (A y_k)_e is negative, with A y_k by one convolution per shape (the
/// independent reference: no bound, no combination). A wheel-on-rail gap on a 24 × 24
/// grid (about 140 elements in contact, 430 off), approach changes of −3 … +5 % and tilts
/// and curvatures of the column corrections up to 3e-6 m: both outcomes occur; U_k bounds
/// |A y_k| off the set; small changes (quasi-Newton corrections) need no convolution; the
/// first checks convolve the combination, the later ones the three shapes once.
#[test]
fn entering_check_equals_visiting_every_element() {
    let grid = Grid::centred(24, 24, 5e-4, 4e-4, 0.0, 0.0).unwrap();
    let material = Material::identical(210e9, 0.3).unwrap();
    let gap = grid.sample(|x, y| x * x / 0.92 + y * y / 0.6);
    let mut solver = NormalSolver::new(grid, material).unwrap();
    let options = SolverOptions {
        tol: 1e-12,
        max_iter: 2000,
        ..SolverOptions::default()
    };
    let delta = 3e-5;
    let solution = solver
        .solve(&gap, NormalLoad::Approach(delta), &options)
        .unwrap();
    let mut responses = Responses::new(&grid, &mut solver).unwrap();
    let column_force = vec![0.0; grid.nx];
    let mut model = FrozenSet::build(
        &mut solver,
        &mut responses,
        &solution,
        delta,
        &[],
        &column_force,
        0.0,
        2000,
    )
    .unwrap()
    .expect("a model");
    // The reference A y_k off the set.
    let reference: Vec<[f64; BASIS]> = {
        let mut full: [Vec<f64>; BASIS] = std::array::from_fn(|_| vec![0.0; grid.len()]);
        for (k, u) in full.iter_mut().enumerate() {
            let mut y = vec![0.0; grid.len()];
            for (c, &e) in model.active.iter().enumerate() {
                y[e] = model.y[k][c];
            }
            solver.displacement(&y, u).unwrap();
        }
        let reference: Vec<[f64; BASIS]> = model
            .inactive
            .iter()
            .map(|&e| std::array::from_fn(|k| full[k][e as usize]))
            .collect();
        for k in 0..BASIS {
            let max = reference.iter().fold(0.0_f64, |m, u| m.max(u[k].abs()));
            assert!(max <= model.bound[k], "{k}: {max} > {}", model.bound[k]);
        }
        reference
    };
    let convolutions = solver.convolutions();
    let (mut out, mut pressure, mut delta_g) =
        (vec![0.0; grid.nx], vec![0.0; grid.len()], Vec::new());
    for step in 0..20 {
        let d = delta * (1.0 + 1e-7 * (1.0 + step as f64));
        let small = model.predict(
            &mut solver,
            &mut responses,
            d,
            &[],
            &mut out,
            &mut pressure,
            &mut delta_g,
        );
        assert!(small.is_some());
    }
    assert_eq!(solver.convolutions(), convolutions);
    let (mut refused, mut accepted, mut convolved) = (0, 0, 0);
    let (mut out, mut pressure, mut delta_g) =
        (vec![0.0; grid.nx], vec![0.0; grid.len()], Vec::new());
    for step in 0..400 {
        let f = step as f64;
        let d = delta * (1.0 + 0.08 * ((0.37 * f).sin() * 0.5 + 0.125));
        let (tilt, bend) = (3e-6 * (0.71 * f).sin(), 3e-6 * (1.13 * f).cos());
        let column_gap: Vec<f64> = (0..grid.nx)
            .map(|i| {
                let xi = (i as f64 + 0.5) / grid.nx as f64 * 2.0 - 1.0;
                tilt * xi + bend * xi * xi
            })
            .collect();
        let before = solver.convolutions();
        let predicted = model.predict(
            &mut solver,
            &mut responses,
            d,
            &column_gap,
            &mut out,
            &mut pressure,
            &mut delta_g,
        );
        let a = model.fit(&responses, d, &column_gap, &mut delta_g);
        let every = (0..model.distance.len()).any(|j| {
            let mut e = model.distance[j] - delta_g[model.inactive_column[j] as usize];
            for (k, ak) in a.iter().enumerate().take(BASIS) {
                e += ak * reference[j][k];
            }
            e < 0.0
        });
        assert_eq!(predicted.is_none(), every, "step {step}");
        convolved += solver.convolutions() - before;
        if every {
            refused += 1;
        } else {
            accepted += 1;
        }
    }
    // The first checks convolve the combination, the later ones combine A y_k of the
    // three shapes (convolved once): both paths were compared with the reference.
    assert!(
        refused > 20
            && accepted > 20
            && convolved == SHAPE_CONVOLUTIONS_AFTER + BASIS
            && model.shape_u.is_some(),
        "{refused} {accepted} {convolved}"
    );
}

/// The cofactor inverse times the matrix is the identity (1e-12, round-off).
#[test]
fn inverse_of_a_gram_matrix() {
    let m = [[4.0, 1.0, 0.5], [1.0, 3.0, 0.25], [0.5, 0.25, 2.0]];
    let inv = invert3(&m).unwrap();
    for r in 0..3 {
        for c in 0..3 {
            let v: f64 = (0..3).map(|k| m[r][k] * inv[k][c]).sum();
            assert!((v - f64::from(u8::from(r == c))).abs() < 1e-12);
        }
    }
    assert!(invert3(&[[1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).is_none());
}

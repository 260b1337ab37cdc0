//! The band factorisation of an articulated rake's block of the step matrix, and the folding
//! of its off-span wheels into it, against dense LU solves (faer) of the same matrices.

use faer::linalg::solvers::Solve;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use sim::train::VehicleSpec;
use sim::train::hslm_vehicles::interaction_train;
use sim::vehicle_bridge::linalg::{
    BlockDiagonal, CapacitanceWork, DenseWork, contact_update, dense_contact_update,
};

/// The step matrix A = M/(β Δt²) + γ C/(β Δt) + K (Newmark, β = 1/4, γ = 1/2, Δt = 1e-4 s)
/// of HSLM-A`number`'s articulated rake, row-major, and its number of wheelsets.
fn rake_step_matrix(number: usize) -> (Vec<f64>, usize, usize) {
    let train = interaction_train(number, 9.81).unwrap();
    let rake = train
        .vehicles
        .iter()
        .find_map(|v| match v {
            VehicleSpec::Articulated(a) => Some(a.matrices()),
            _ => None,
        })
        .unwrap();
    let d = rake.dofs();
    let dt = 1e-4;
    let (cm, cc) = (1.0 / (0.25 * dt * dt), 0.5 / (0.25 * dt));
    let mut a = vec![0.0; d * d];
    for i in 0..d {
        for j in 0..d {
            a[i * d + j] = cc * rake.damping[(i, j)] + rake.stiffness[(i, j)];
        }
        a[i * d + i] += cm * rake.mass[i];
    }
    (a, d, rake.own_dofs)
}

/// The largest entry-wise relative difference |a_i − b_i|/|b_i| (entries of b below 1e-9 of
/// its largest count as that size: the modes' and the rake's entries differ by orders of
/// magnitude, and a norm-wise difference would hide errors in the small ones).
fn rel(a: &[f64], b: &[f64]) -> f64 {
    let floor = 1e-9 * b.iter().fold(0.0f64, |m, y| m.max(y.abs()));
    a.iter().zip(b).fold(0.0f64, |m, (x, y)| {
        m.max((x - y).abs() / y.abs().max(floor))
    })
}

/// The dense LU solve of the row-major n × n `a` (the reference).
fn dense_solve(a: &[f64], n: usize, rhs: &[f64]) -> Vec<f64> {
    let full = faer::Mat::from_fn(n, n, |i, j| a[i * n + j]);
    let b = faer::Mat::from_fn(n, 1, |i, _| rhs[i]);
    let x = full.partial_piv_lu().solve(&b);
    (0..n).map(|i| x[(i, 0)]).collect()
}

/// A system of `modes` 1×1 modal blocks and the rake's block on the following indices
/// (scattered: its DOF order reversed), with the rake's index of each vehicle DOF.
fn rake_system(number: usize, modes: usize) -> (BlockDiagonal, Vec<usize>, usize) {
    let (block, d, own) = rake_step_matrix(number);
    let n = modes + d;
    let mut a = BlockDiagonal::new(n);
    for j in 0..modes {
        a.push1(j, 1e9 * (1.0 + j as f64)).unwrap();
    }
    let indices: Vec<usize> = (0..d).map(|r| n - 1 - r).collect();
    a.push_dense(&indices, &block).unwrap();
    (a, indices, own)
}

/// HSLM-A1 (124 DOFs) and A10 (88 DOFs): the rake's block is solved in its band
/// (half-bandwidth at most 6 whatever the number of bodies) and equals the dense LU solve of
/// the same matrix to 1e-12 (relative, random right-hand sides; A has a condition number near
/// 1e3 here, so round-off stays near 1e-14); the product A x by the block's non-zeros equals
/// the dense product to 1e-15.
#[test]
fn rake_band_solve_equals_dense_lu() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for number in [1usize, 10] {
        let (a, _, _) = rake_system(number, 3);
        let n = a.dimension();
        let band = a.banded(0).expect("the rake's block is banded");
        assert!(band.half_bandwidth() <= 6, "{}", band.half_bandwidth());
        let dense = a.to_dense();
        for _ in 0..4 {
            let rhs: Vec<f64> = (0..n).map(|_| rng.random::<f64>() - 0.5).collect();
            let reference = dense_solve(&dense, n, &rhs);
            let mut x = rhs.clone();
            a.solve_in_place(&mut x);
            let e = rel(&x, &reference);
            println!(
                "HSLM-A{number}: n = {n}, half-bandwidth {}, band vs dense LU {e:.2e}",
                band.half_bandwidth()
            );
            assert!(e < 1e-12, "{e}");
            let mut y = vec![0.0; n];
            a.mul(&rhs, &mut y);
            let product: Vec<f64> = (0..n)
                .map(|i| (0..n).map(|j| dense[i * n + j] * rhs[j]).sum())
                .collect();
            assert!(rel(&y, &product) < 1e-15);
        }
    }
}

/// The wheels' ĝ, v and patterns for the rake of [`rake_system`]: the first 4 on the span (ĝ, v
/// on the modes, v = −w(x) with random shapes, ĝ within 5 % of it as for a contact of
/// several columns, and 1 on the wheel), the others off it (the wheel only).
type Wheels = (Vec<Vec<f64>>, Vec<Vec<f64>>, Vec<Vec<usize>>);

fn rake_wheels(rng: &mut ChaCha8Rng, n: usize, modes: usize, wheel_dofs: &[usize]) -> Wheels {
    let mut gs = Vec::new();
    let mut vs = Vec::new();
    let mut patterns = Vec::new();
    for (k, &dof) in wheel_dofs.iter().enumerate() {
        let (mut g, mut v) = (vec![0.0; n], vec![0.0; n]);
        let mut pattern = Vec::new();
        if k < 4 {
            for j in 0..modes {
                let w = rng.random::<f64>() * 2.0 - 1.0;
                v[j] = -w;
                g[j] = -w * (1.0 + 0.1 * (rng.random::<f64>() - 0.5));
                pattern.push(j);
            }
        }
        g[dof] = 1.0;
        v[dof] = 1.0;
        pattern.push(dof);
        gs.push(g);
        vs.push(v);
        patterns.push(pattern);
    }
    (gs, vs, patterns)
}

/// The rake of HSLM-A1 over 3 modes, its first 4 wheels on the span (ĝ, v on the modes and the
/// wheel), the others off it (the wheel only), one of those rigid and two out of contact. The
/// update folds the compliant off-span wheels into the rake's band and keeps the rest in the
/// capacitance form; it must equal the dense bordered solve (faer LU of the whole system) to
/// 1e-12 in Δx and ΔF, also when the work space is reused with other compliances, and when
/// the same compliances come again (the band's factorisation is then reused).
#[test]
fn folded_update_equals_dense_for_a_rake() {
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    let modes = 3;
    let (a, indices, own) = rake_system(1, modes);
    let n = a.dimension();
    let wheel_dofs: Vec<usize> = indices[own..].to_vec();
    let nw = wheel_dofs.len();
    let (gs, vs, patterns) = rake_wheels(&mut rng, n, modes, &wheel_dofs);
    let rigid = 20;
    let active: Vec<usize> = (0..nw).filter(|&k| k != 7 && k != 30).collect();
    let delta: Vec<f64> = active
        .iter()
        .map(|&k| if k == rigid { 1e-5 } else { 0.0 })
        .collect();
    let rhs: Vec<f64> = (0..n).map(|_| rng.random::<f64>() - 0.5).collect();
    let mut work = CapacitanceWork::default();
    let mut compliance: Vec<f64> = Vec::new();
    let mut last: Option<(Vec<f64>, Vec<f64>)> = None;
    // Rounds 0 and 1 with new compliances (the band factorised again), round 2 with round
    // 1's (its factorisation reused).
    for round in 0..3 {
        if round < 2 {
            compliance = active
                .iter()
                .map(|&k| {
                    if k == rigid {
                        0.0
                    } else {
                        1.0 / (5e8 + 1e9 * rng.random::<f64>())
                    }
                })
                .collect();
        }
        let mut x = rhs.clone();
        let mut df = vec![0.0; active.len()];
        contact_update(
            &a,
            0.8,
            &gs,
            &vs,
            &patterns,
            &active,
            &compliance,
            &delta,
            &mut x,
            &mut df,
            &mut work,
        )
        .unwrap();
        let mut x2 = rhs.clone();
        let mut df2 = vec![0.0; active.len()];
        dense_contact_update(
            &a,
            0.8,
            &gs,
            &vs,
            &active,
            &compliance,
            &delta,
            &mut x2,
            &mut df2,
            &mut DenseWork::default(),
        )
        .unwrap();
        let (ex, ef) = (rel(&x, &x2), rel(&df, &df2));
        println!("round {round}: folded vs dense: state {ex:.2e}, forces {ef:.2e}");
        assert!(ex < 1e-12 && ef < 1e-12, "{ex} {ef}");
        if round == 2 {
            // The same inputs as round 1: the same update bit for bit.
            let (x1, df1) = last.as_ref().unwrap();
            assert!(x.iter().zip(x1).all(|(a, b)| a.to_bits() == b.to_bits()));
            assert!(df.iter().zip(df1).all(|(a, b)| a.to_bits() == b.to_bits()));
        }
        last = Some((x.clone(), df.clone()));
        let r = active.iter().position(|&k| k == rigid).unwrap();
        let vdx: f64 = vs[rigid].iter().zip(&x).map(|(a, b)| a * b).sum();
        assert!((vdx + delta[r]).abs() < 1e-10 * delta[r]);
    }
    // Every compliant off-span wheel in contact was folded, in every round; the band was
    // factorised in rounds 0 and 1 and reused in round 2 only.
    let folded = active.iter().filter(|&&k| k >= 4 && k != rigid).count() as u64;
    assert_eq!(work.fold_count(), 3 * folded);
    assert_eq!(work.fold_reuse_count(), 1);
    // Round 2 took the A_c⁻¹ĝ on the band of every wheel not folded (the 4 on the span and the
    // rigid one) from round 1, where they were solved with the same factorisation.
    assert_eq!(work.column_reuse_count(), 5);
}

/// The chord step (`CapacitanceWork::set_fold_tolerance`): with the off-span wheels'
/// stiffnesses changed by 5e-4 (relative) the band's factorisation with the old ones is kept
/// (tolerance 1e-3), so one update is no longer the exact solve of the linear system
/// (A + s Σ k_c ĝ_c v_cᵀ) x = b; the iteration x ← x + update(b − (A + s Σ k_c ĝ_c v_cᵀ) x)
/// converges to it (the dense bordered solve) to 1e-12 within 4 updates, and with tolerance 0
/// the factorisation is redone and the first update is already exact.
#[test]
fn chord_updates_converge_to_the_dense_solve() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let modes = 3;
    let (a, indices, own) = rake_system(1, modes);
    let n = a.dimension();
    let wheel_dofs: Vec<usize> = indices[own..].to_vec();
    let (gs, vs, patterns) = rake_wheels(&mut rng, n, modes, &wheel_dofs);
    let active: Vec<usize> = (0..wheel_dofs.len()).collect();
    let zero = vec![0.0; active.len()];
    let b: Vec<f64> = (0..n).map(|_| rng.random::<f64>() - 0.5).collect();
    let old: Vec<f64> = active
        .iter()
        .map(|_| 1.0 / (5e8 + 1e9 * rng.random::<f64>()))
        .collect();
    let new: Vec<f64> = old.iter().map(|c| c / (1.0 + 5e-4)).collect();
    let s = 0.8;
    let mut exact = b.clone();
    let mut df = vec![0.0; active.len()];
    dense_contact_update(
        &a,
        s,
        &gs,
        &vs,
        &active,
        &new,
        &zero,
        &mut exact,
        &mut df,
        &mut DenseWork::default(),
    )
    .unwrap();
    for tolerance in [1e-3, 0.0] {
        let mut work = CapacitanceWork::default();
        work.set_fold_tolerance(tolerance);
        // Factorised with the old stiffnesses.
        let mut x = b.clone();
        contact_update(
            &a, s, &gs, &vs, &patterns, &active, &old, &zero, &mut x, &mut df, &mut work,
        )
        .unwrap();
        let mut x = vec![0.0; n];
        let mut errors = Vec::new();
        for _ in 0..4 {
            // −R = b − A x − s Σ k_c ĝ_c v_cᵀ x.
            let mut res = vec![0.0; n];
            a.mul(&x, &mut res);
            for (r, bi) in res.iter_mut().zip(&b) {
                *r = bi - *r;
            }
            for (c, &k) in active.iter().enumerate() {
                let vx: f64 = vs[k].iter().zip(&x).map(|(v, y)| v * y).sum();
                for (r, g) in res.iter_mut().zip(&gs[k]) {
                    *r -= s * g * vx / new[c];
                }
            }
            contact_update(
                &a, s, &gs, &vs, &patterns, &active, &new, &zero, &mut res, &mut df, &mut work,
            )
            .unwrap();
            for (xi, d) in x.iter_mut().zip(&res) {
                *xi += d;
            }
            errors.push(rel(&x, &exact));
        }
        println!("fold tolerance {tolerance:e}: errors {errors:?}");
        if tolerance > 0.0 {
            assert_eq!(work.fold_reuse_count(), 4);
            assert!(errors[0] > 1e-9 && errors[0] < 1e-3, "{errors:?}");
            assert!(errors[3] < 1e-12, "{errors:?}");
        } else {
            assert_eq!(work.fold_reuse_count(), 3);
            assert!(errors[0] < 1e-12, "{errors:?}");
        }
    }
}

/// `|A⁻¹| e` at the wheels only (the force floor's need) equals the full product there bit for
/// bit, and the modes' entries too, for the rake of HSLM-A1 over 3 modes.
#[test]
fn absolute_solve_at_the_wheels_equals_the_full_one_there() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let (a, indices, own) = rake_system(1, 3);
    let n = a.dimension();
    let wheels = &indices[own..];
    let e: Vec<f64> = (0..n).map(|_| rng.random::<f64>()).collect();
    let (mut full, mut at) = (e.clone(), e.clone());
    a.solve_abs_in_place(&mut full);
    a.solve_abs_at(&mut at, wheels);
    for &i in wheels.iter().chain(&[0, 1, 2]) {
        assert_eq!(full[i].to_bits(), at[i].to_bits(), "index {i}");
    }
    // The other entries are the full product's only by chance: some must differ here.
    assert!(indices[..own].iter().any(|&i| full[i] != at[i]));
}

/// The force floor's bound of `|A⁻¹| e` at the wheels (`solve_abs_bound_at`: the diagonal term
/// plus the off-diagonal row sum times the largest entry) is never below the exact product
/// there (to the round-off of both sums), for random and for one-hot e on the rake of HSLM-A1
/// over 3 modes (a one-hot e off a wheel's row is bounded by that row's off-diagonal sum
/// alone), and equals it on the modes.
#[test]
fn absolute_bound_at_the_wheels_is_above_the_exact_product() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let (a, indices, own) = rake_system(1, 3);
    let n = a.dimension();
    let wheels = &indices[own..];
    let mut cases: Vec<Vec<f64>> = (0..4)
        .map(|_| (0..n).map(|_| rng.random::<f64>()).collect())
        .collect();
    for &i in indices.iter().step_by(7) {
        let mut e = vec![0.0; n];
        e[i] = 1.0;
        cases.push(e);
    }
    for e in &cases {
        let (mut exact, mut bound) = (e.clone(), e.clone());
        a.solve_abs_at(&mut exact, wheels);
        a.solve_abs_bound_at(&mut bound, wheels);
        for &i in wheels {
            assert!(
                bound[i] >= exact[i] * (1.0 - 1e-13),
                "index {i}: {} < {}",
                bound[i],
                exact[i]
            );
        }
        for j in 0..3 {
            assert_eq!(bound[j].to_bits(), exact[j].to_bits(), "mode {j}");
        }
    }
}

//! The coupled-step solves: Sherman–Morrison (one wheel) and Woodbury (several wheels, with and
//! without rigid contacts) against a dense LU solve (faer) of the full matrix.

use faer::linalg::solvers::Solve;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use sim::vehicle_bridge::linalg::{
    BlockDiagonal, CapacitanceWork, DenseWork, contact_update, dense_contact_update,
};

/// A random step matrix like the simulation's: 20 modal 1×1 blocks and `wheels` 2×2
/// wheel–body blocks, diagonally dominant.
fn random_system(rng: &mut ChaCha8Rng, wheels: usize) -> (BlockDiagonal, usize) {
    let m = 20;
    let n = m + 2 * wheels;
    let mut a = BlockDiagonal::new(n);
    for j in 0..m {
        a.push1(j, 1e3 + 1e6 * rng.random::<f64>()).unwrap();
    }
    for k in 0..wheels {
        let (i, j) = (m + 2 * k, m + 2 * k + 1);
        let c = 1e5 * rng.random::<f64>();
        a.push2(i, j, 2e6 + c, -c, -c, 3e6 + c + 1e5 * rng.random::<f64>())
            .unwrap();
    }
    (a, m)
}

fn random_vectors(rng: &mut ChaCha8Rng, n: usize, m: usize, wheel: usize) -> (Vec<f64>, Vec<f64>) {
    let mut v = vec![0.0; n];
    let mut g = vec![0.0; n];
    for j in 0..m {
        let w = rng.random::<f64>() * 2.0 - 1.0;
        v[j] = -w;
        g[j] = -w * (1.0 + 0.1 * (rng.random::<f64>() - 0.5));
    }
    v[wheel] = 1.0;
    g[wheel] = 1.0;
    (v, g)
}

/// Per wheel: ĝ, v and the pattern.
type Wheels = (Vec<Vec<f64>>, Vec<Vec<f64>>, Vec<Vec<usize>>);

/// `wheels` wheels' ĝ and v (`random_vectors`, wheel k on DOF m + 2k) and their patterns.
fn random_wheels(rng: &mut ChaCha8Rng, n: usize, m: usize, wheels: usize) -> Wheels {
    let mut gs = Vec::new();
    let mut vs = Vec::new();
    for k in 0..wheels {
        let (v, g) = random_vectors(rng, n, m, m + 2 * k);
        vs.push(v);
        gs.push(g);
    }
    let patterns = (0..wheels).map(|k| pattern(m, m + 2 * k)).collect();
    (gs, vs, patterns)
}

/// Where a wheel's ĝ and v can be non-zero: the m modes and its own DOF.
fn pattern(m: usize, wheel: usize) -> Vec<usize> {
    (0..m).chain([wheel]).collect()
}

/// Relative difference ‖a − b‖∞/‖b‖∞.
fn rel(a: &[f64], b: &[f64]) -> f64 {
    let d = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    d / b.iter().fold(0.0f64, |m, y| m.max(y.abs()))
}

/// For compliant contacts the update solves (A + s Σ k_c ĝ vᵀ) Δx = −R; Sherman–Morrison
/// (k = 1) and Woodbury (k = 2, 4, 8: the small elimination with a fixed size; k = 3 with any
/// size; k = 20: the blocked LU of larger groups) must equal the dense solve of that n × n matrix to 1e-12 (condition numbers here
/// are below 1e3, so round-off stays near 1e-14).
#[test]
fn sherman_morrison_and_woodbury_equal_dense() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for wheels in [1usize, 2, 3, 4, 8, 20] {
        let (a, m) = random_system(&mut rng, wheels);
        let n = a.dimension();
        let s = 0.9;
        let mut gs = Vec::new();
        let mut vs = Vec::new();
        let mut kc = Vec::new();
        for k in 0..wheels {
            let (v, g) = random_vectors(&mut rng, n, m, m + 2 * k);
            vs.push(v);
            gs.push(g);
            kc.push(1e6 + 1e7 * rng.random::<f64>());
        }
        let rhs: Vec<f64> = (0..n).map(|_| rng.random::<f64>() - 0.5).collect();
        // Dense reference of the full matrix.
        let mut full = a.to_dense();
        for k in 0..wheels {
            for i in 0..n {
                for j in 0..n {
                    full[i * n + j] += s * kc[k] * gs[k][i] * vs[k][j];
                }
            }
        }
        let full = faer::Mat::from_fn(n, n, |i, j| full[i * n + j]);
        let b = faer::Mat::from_fn(n, 1, |i, _| rhs[i]);
        let solution = full.partial_piv_lu().solve(&b);
        let reference: Vec<f64> = (0..n).map(|i| solution[(i, 0)]).collect();
        let g_refs: Vec<&[f64]> = gs.iter().map(|g| &g[..]).collect();
        let v_refs: Vec<&[f64]> = vs.iter().map(|v| &v[..]).collect();
        let patterns: Vec<Vec<usize>> = (0..wheels).map(|k| pattern(m, m + 2 * k)).collect();
        let active: Vec<usize> = (0..wheels).collect();
        let compliance: Vec<f64> = kc.iter().map(|k| 1.0 / k).collect();
        let zero = vec![0.0; wheels];
        let mut x = rhs.clone();
        let mut df = vec![0.0; wheels];
        let mut work = CapacitanceWork::new(n, wheels);
        contact_update(
            &a,
            s,
            &g_refs,
            &v_refs,
            &patterns,
            &active,
            &compliance,
            &zero,
            &mut x,
            &mut df,
            &mut work,
        )
        .unwrap();
        let e = rel(&x, &reference);
        println!("k = {wheels}: low-rank vs dense {e:.2e}");
        assert!(e < 1e-12, "{e}");
        // The force increments are the linearised law ΔF = k_c vᵀΔx.
        for k in 0..wheels {
            let dot: f64 = vs[k].iter().zip(&x).map(|(a, b)| a * b).sum();
            assert!((df[k] - kc[k] * dot).abs() <= 1e-10 * df[k].abs().max(1e-300) + 1e-12);
        }
        // The bordered dense form gives the same answer.
        let mut x2 = rhs.clone();
        let mut df2 = vec![0.0; wheels];
        let mut dense = DenseWork::default();
        dense_contact_update(
            &a,
            s,
            &g_refs,
            &v_refs,
            &active,
            &compliance,
            &zero,
            &mut x2,
            &mut df2,
            &mut dense,
        )
        .unwrap();
        assert!(rel(&x2, &reference) < 1e-12);
    }
}

/// Rigid contacts (zero compliance, δ̃ = δ): the update must satisfy the constraints
/// vᵀΔx = −δ exactly (to round-off, 1e-12 relative) and equal the bordered dense solve.
#[test]
fn rigid_constraints_are_met() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let wheels = 2;
    let (a, m) = random_system(&mut rng, wheels);
    let n = a.dimension();
    let mut gs = Vec::new();
    let mut vs = Vec::new();
    for k in 0..wheels {
        let (v, _) = random_vectors(&mut rng, n, m, m + 2 * k);
        gs.push(v.clone());
        vs.push(v);
    }
    let g_refs: Vec<&[f64]> = gs.iter().map(|g| &g[..]).collect();
    let v_refs: Vec<&[f64]> = vs.iter().map(|v| &v[..]).collect();
    let patterns: Vec<Vec<usize>> = (0..wheels).map(|k| pattern(m, m + 2 * k)).collect();
    let active: Vec<usize> = (0..wheels).collect();
    let compliance = [0.0, 1e-7];
    let delta = [2e-4, 0.0];
    let rhs: Vec<f64> = (0..n).map(|_| rng.random::<f64>() - 0.5).collect();
    let mut x = rhs.clone();
    let mut df = vec![0.0; wheels];
    let mut work = CapacitanceWork::new(n, wheels);
    contact_update(
        &a,
        1.0,
        &g_refs,
        &v_refs,
        &patterns,
        &active,
        &compliance,
        &delta,
        &mut x,
        &mut df,
        &mut work,
    )
    .unwrap();
    let vdx: f64 = vs[0].iter().zip(&x).map(|(a, b)| a * b).sum();
    assert!((vdx + delta[0]).abs() < 1e-12 * delta[0]);
    let mut x2 = rhs;
    let mut df2 = vec![0.0; wheels];
    let mut dense = DenseWork::default();
    dense_contact_update(
        &a,
        1.0,
        &g_refs,
        &v_refs,
        &active,
        &compliance,
        &delta,
        &mut x2,
        &mut df2,
        &mut dense,
    )
    .unwrap();
    assert!(rel(&x, &x2) < 1e-12);
    assert!(rel(&df, &df2) < 1e-12);
}

/// A train-like system: bogie-vehicle-like dense blocks (4 wheels + 6 own DOFs each), some
/// wheels on the span (modal part) and some off it (no modal part), a subset active. The
/// capacitance matrix then splits into groups (the span's wheels with their vehicles' other
/// wheels, and each vehicle wholly off the span); the grouped update must equal the dense
/// bordered solve (faer LU of the full system) to 1e-12, for compliant and rigid contacts.
#[test]
fn grouped_capacitance_equals_dense_for_a_train() {
    let mut rng = ChaCha8Rng::seed_from_u64(23);
    let m = 12;
    let vehicles = 5;
    let n = m + 10 * vehicles;
    let mut a = BlockDiagonal::new(n);
    for j in 0..m {
        a.push1(j, 1e3 + 1e6 * rng.random::<f64>()).unwrap();
    }
    let mut wheel_dofs = Vec::new();
    for veh in 0..vehicles {
        let indices: Vec<usize> = (m + 10 * veh..m + 10 * (veh + 1)).collect();
        // Diagonally dominant, non-symmetric dense block.
        let mut e = vec![0.0; 100];
        for r in 0..10 {
            for c in 0..10 {
                e[r * 10 + c] = if r == c {
                    5e6 + 1e6 * rng.random::<f64>()
                } else {
                    2e5 * (rng.random::<f64>() - 0.5)
                };
            }
        }
        a.push_dense(&indices, &e).unwrap();
        wheel_dofs.extend_from_slice(&indices[6..]);
    }
    let nw = wheel_dofs.len();
    // Wheels 0..7 (vehicles 0 and 1) on the span; the rest off it.
    let mut gs = Vec::new();
    let mut vs = Vec::new();
    for (k, &dof) in wheel_dofs.iter().enumerate() {
        let (mut v, mut g) = random_vectors(&mut rng, n, m, dof);
        if k >= 8 {
            v[..m].fill(0.0);
            g[..m].fill(0.0);
        }
        vs.push(v);
        gs.push(g);
    }
    let patterns: Vec<Vec<usize>> = wheel_dofs.iter().map(|&d| pattern(m, d)).collect();
    // Every wheel but 3 and 13 in contact; wheel 5 rigid (zero compliance, δ̃ ≠ 0).
    let active: Vec<usize> = (0..nw).filter(|&k| k != 3 && k != 13).collect();
    let compliance: Vec<f64> = active
        .iter()
        .map(|&k| {
            if k == 5 {
                0.0
            } else {
                1.0 / (1e6 + 1e7 * rng.random::<f64>())
            }
        })
        .collect();
    let delta: Vec<f64> = active
        .iter()
        .map(|&k| if k == 5 { 1e-4 } else { 0.0 })
        .collect();
    let rhs: Vec<f64> = (0..n).map(|_| rng.random::<f64>() - 0.5).collect();
    let mut x = rhs.clone();
    let mut df = vec![0.0; active.len()];
    let mut work = CapacitanceWork::default();
    for _ in 0..2 {
        // Twice with the same work space: stale entries of the first call must not leak.
        x.copy_from_slice(&rhs);
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
    }
    let mut x2 = rhs.clone();
    let mut df2 = vec![0.0; active.len()];
    let mut dense = DenseWork::default();
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
        &mut dense,
    )
    .unwrap();
    let (ex, ef) = (rel(&x, &x2), rel(&df, &df2));
    println!("grouped vs dense: state {ex:.2e}, forces {ef:.2e}");
    assert!(ex < 1e-12 && ef < 1e-12, "{ex} {ef}");
    // The rigid wheel's constraint holds: v·Δx = −δ̃.
    let r = active.iter().position(|&k| k == 5).unwrap();
    let vdx: f64 = vs[5].iter().zip(&x).map(|(a, b)| a * b).sum();
    assert!((vdx + delta[r]).abs() < 1e-10 * delta[r]);
}

/// The work space keeps A⁻¹ĝ per wheel and reuses it while A and ĝ are unchanged, and the
/// capacitance entries s vᵀA⁻¹ĝ of a group while its wheels' A⁻¹ĝ and v are: a work space
/// carried through a sequence of updates (new right-hand sides, a changed ĝ, a changed v, a
/// smaller active set, a rebuilt A) gives the same Δx and ΔF, bit for bit, as a fresh one each
/// time, and recomputes exactly the solves and the groups' entries whose inputs changed.
#[test]
fn reused_solves_equal_fresh_ones_bit_for_bit() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let wheels = 4;
    let (mut a, m) = random_system(&mut rng, wheels);
    let n = a.dimension();
    let s = 0.9;
    let (mut gs, vs, patterns) = random_wheels(&mut rng, n, m, wheels);
    let compliance: Vec<f64> = (0..wheels).map(|k| 1e-7 * (1.0 + k as f64)).collect();
    let zero = vec![0.0; wheels];
    let mut kept = CapacitanceWork::new(n, wheels);
    let update = |a: &BlockDiagonal,
                  gs: &[Vec<f64>],
                  vs: &[Vec<f64>],
                  active: &[usize],
                  rng: &mut ChaCha8Rng,
                  kept: &mut CapacitanceWork| {
        let rhs: Vec<f64> = (0..n).map(|_| rng.random::<f64>() - 0.5).collect();
        let run = |work: &mut CapacitanceWork| {
            let mut x = rhs.clone();
            let mut df = vec![0.0; active.len()];
            contact_update(
                a,
                s,
                gs,
                vs,
                &patterns,
                active,
                &compliance[..active.len()],
                &zero[..active.len()],
                &mut x,
                &mut df,
                work,
            )
            .unwrap();
            (x, df)
        };
        let before = kept.solve_counts();
        let entries_before = kept.entry_counts();
        let reused = run(kept);
        let fresh = run(&mut CapacitanceWork::default());
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&reused.0), bits(&fresh.0));
        assert_eq!(bits(&reused.1), bits(&fresh.1));
        let after = kept.solve_counts();
        let entries_after = kept.entry_counts();
        // (solves, reused solves, groups' entries kept, groups' entries formed)
        (
            after.0 - before.0,
            after.1 - before.1,
            entries_after.0 - entries_before.0,
            entries_after.1 - entries_before.1,
        )
    };
    let all = [0, 1, 2, 3];
    // The wheels share the modes: one group. The coupling groups are kept from the update
    // before while the active wheels and their A⁻¹ĝ are the same (`groups_kept`).
    assert_eq!(
        update(&a, &gs, &vs, &all, &mut rng, &mut kept),
        (4, 0, 0, 1)
    );
    assert_eq!(kept.groups_kept(), 0);
    // Same A, ĝ and v, a new right-hand side: every solve and the entries are reused.
    assert_eq!(
        update(&a, &gs, &vs, &all, &mut rng, &mut kept),
        (0, 4, 1, 0)
    );
    assert_eq!(kept.groups_kept(), 1);
    // One ĝ changed in its last bit: only that wheel is solved again, the entries formed again.
    gs[2][3] = f64::from_bits(gs[2][3].to_bits() + 1);
    assert_eq!(
        update(&a, &gs, &vs, &all, &mut rng, &mut kept),
        (1, 3, 0, 1)
    );
    assert_eq!(kept.groups_kept(), 1);
    // One v changed in its last bit: the solves are reused, the entries formed again.
    let mut changed = vs.clone();
    changed[1][0] = f64::from_bits(changed[1][0].to_bits() + 1);
    assert_eq!(
        update(&a, &gs, &changed, &all, &mut rng, &mut kept),
        (0, 4, 0, 1)
    );
    assert_eq!(
        update(&a, &gs, &changed, &all, &mut rng, &mut kept),
        (0, 4, 1, 0)
    );
    assert_eq!(kept.groups_kept(), 3);
    // A smaller active set reuses the solves it has and forms its group's entries.
    assert_eq!(
        update(&a, &gs, &vs, &[1, 3], &mut rng, &mut kept),
        (0, 2, 0, 1)
    );
    assert_eq!(kept.groups_kept(), 3);
    // A rebuilt A (even with the same blocks) invalidates every stored solve and entry.
    let (rebuilt, _) = random_system(&mut ChaCha8Rng::seed_from_u64(11), wheels);
    a = rebuilt;
    assert_eq!(
        update(&a, &gs, &vs, &all, &mut rng, &mut kept),
        (4, 0, 0, 1)
    );
    assert_eq!(kept.groups_kept(), 3);
    // A declared geometry: v is not compared; the entries are formed once per declaration.
    kept.new_geometry();
    assert_eq!(
        update(&a, &gs, &vs, &all, &mut rng, &mut kept),
        (0, 4, 0, 1)
    );
    assert_eq!(
        update(&a, &gs, &vs, &all, &mut rng, &mut kept),
        (0, 4, 1, 0)
    );
    kept.new_geometry();
    assert_eq!(
        update(&a, &gs, &changed, &all, &mut rng, &mut kept),
        (0, 4, 0, 1)
    );
}

/// The contract of `CapacitanceWork::new_geometry` (v fixed until the next declaration) is
/// checked when asked for: the same v under one declaration and a changed v under a new one
/// pass; a v changed in its last bit under the same declaration stops the update, naming
/// the wheel.
#[test]
#[should_panic(expected = "wheel 1's v changed within a declared geometry")]
fn a_v_changed_within_a_declared_geometry_is_refused() {
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let wheels = 2;
    let (a, m) = random_system(&mut rng, wheels);
    let n = a.dimension();
    let (gs, vs, patterns) = random_wheels(&mut rng, n, m, wheels);
    let mut work = CapacitanceWork::new(n, wheels);
    work.verify_declared_geometry(true);
    let mut update = |vs: &[Vec<f64>], work: &mut CapacitanceWork| {
        let mut x: Vec<f64> = (0..n).map(|_| rng.random::<f64>() - 0.5).collect();
        let mut df = vec![0.0; wheels];
        contact_update(
            &a,
            0.9,
            &gs,
            vs,
            &patterns,
            &[0, 1],
            &[1e-7, 2e-7],
            &[0.0, 0.0],
            &mut x,
            &mut df,
            work,
        )
        .unwrap();
    };
    let mut changed = vs.clone();
    changed[1][0] = f64::from_bits(changed[1][0].to_bits() + 1);
    work.new_geometry();
    update(&vs, &mut work);
    update(&vs, &mut work);
    work.new_geometry();
    update(&changed, &mut work);
    update(&changed, &mut work);
    // The contract broken: v changes under the same declaration.
    update(&vs, &mut work);
}

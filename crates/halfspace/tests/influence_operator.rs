//! The FFT influence operators against the direct O(n²) oracles from the closed-form
//! coefficients (Love's formula, Cerruti's and Boussinesq's) on random grids, materials and
//! loads.

use halfspace::operator::Update;
use halfspace::{
    Body, DenseInfluence, DirectInfluence, DirectTangentialInfluence, FftInfluence,
    FftTangentialInfluence, Grid, InfluenceOperator, Material, TangentialInfluenceOperator,
    TangentialKernel,
};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Agreement to 1e-12 of max |u|: the FFT's round-off is ~1e-15 · log n, the direct sum's
    /// ~1e-16 · n for these sizes.
    #[test]
    fn fft_equals_direct_sum(
        nx in 1usize..14,
        ny in 1usize..14,
        dx in 1e-6f64..1e-3,
        aspect in 0.2f64..5.0,
        g in 1e6f64..1e11,
        nu in -0.5f64..0.49,
        seed in any::<u64>(),
    ) {
        let grid = Grid::new(nx, ny, dx, dx * aspect, -0.3 * dx, 0.7 * dx).unwrap();
        let material = Material::from_combined(g, nu).unwrap();
        let mut state = seed | 1;
        let pressure: Vec<f64> = (0..grid.len())
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                1e8 * (state >> 11) as f64 / (1u64 << 53) as f64
            })
            .collect();
        let mut fast = vec![0.0; grid.len()];
        FftInfluence::new(grid, &material).unwrap().apply(&pressure, &mut fast);
        let mut slow = vec![0.0; grid.len()];
        DirectInfluence::new(grid, material).unwrap().apply(&pressure, &mut slow);
        let scale = slow.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (a, b) in fast.iter().zip(&slow) {
            prop_assert!((a - b).abs() <= 1e-12 * scale, "{nx}x{ny}: {a} vs {b}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The fast paths for inputs with zero rows (not transformed) and for a band of output
    /// rows (`precondition_rows`: only those rows transformed back), as NormCG uses them: the
    /// product with zero rows against the direct sum (1e-12 of max |u|, as above); the
    /// banded preconditioner equal bit for bit to the full one on the band, zero elsewhere.
    #[test]
    fn fft_fast_paths_for_zero_rows_and_output_bands(
        nx in 1usize..14,
        ny in 1usize..14,
        dx in 1e-6f64..1e-3,
        g in 1e6f64..1e11,
        zero_rows in any::<u16>(),
        band in (0usize..14, 0usize..14),
        seed in any::<u64>(),
    ) {
        let grid = Grid::new(nx, ny, dx, 1.3 * dx, 0.0, 0.0).unwrap();
        let material = Material::from_combined(g, 0.3).unwrap();
        let mut state = seed | 1;
        let pressure: Vec<f64> = (0..grid.len())
            .map(|k| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                // Rows whose bit is set in `zero_rows` are zero.
                if zero_rows >> (k / nx) & 1 == 1 {
                    0.0
                } else {
                    1e8 * (state >> 11) as f64 / (1u64 << 53) as f64
                }
            })
            .collect();
        let mut fft = FftInfluence::new(grid, &material).unwrap();
        let mut fast = vec![0.0; grid.len()];
        fft.apply(&pressure, &mut fast);
        let mut slow = vec![0.0; grid.len()];
        DirectInfluence::new(grid, material).unwrap().apply(&pressure, &mut slow);
        let scale = slow.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (a, b) in fast.iter().zip(&slow) {
            prop_assert!((a - b).abs() <= 1e-12 * scale, "{nx}x{ny}: {a} vs {b}");
        }
        let (lo, hi) = (band.0.min(band.1).min(ny), band.0.max(band.1).min(ny));
        let mut full = vec![0.0; grid.len()];
        fft.precondition(&pressure, &mut full);
        let mut banded = vec![1.0; grid.len()];
        fft.precondition_rows(&pressure, &mut banded, lo..hi);
        for (k, (a, b)) in banded.iter().zip(&full).enumerate() {
            let expected = if (lo..hi).contains(&(k / nx)) { *b } else { 0.0 };
            prop_assert!(a.to_bits() == expected.to_bits(), "element {k}: {a} vs {expected}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The dense sums ([`DenseInfluence`]) against the FFT operator: the product (same
    /// kernel table; 1e-12 of max |u|, the FFT's round-off) and the preconditioner (the FFT
    /// one tabulated as its impulse response; 1e-12 of max |z|) on inputs with some zero
    /// values, and the product against the direct sum of Love's formula.
    #[test]
    fn dense_sums_equal_fft_and_direct(
        nx in 1usize..14,
        ny in 1usize..14,
        dx in 1e-6f64..1e-3,
        aspect in 0.2f64..5.0,
        g in 1e6f64..1e11,
        nu in -0.5f64..0.49,
        sparsity in 0u64..4,
        seed in any::<u64>(),
    ) {
        let grid = Grid::new(nx, ny, dx, dx * aspect, 0.2 * dx, -0.4 * dx).unwrap();
        let material = Material::from_combined(g, nu).unwrap();
        let mut state = seed | 1;
        let input: Vec<f64> = (0..grid.len())
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                if state % 4 < sparsity { 0.0 } else { 1e8 * (state >> 11) as f64 / (1u64 << 53) as f64 }
            })
            .collect();
        let mut fft = FftInfluence::new(grid, &material).unwrap();
        let mut dense = DenseInfluence::new(grid, &material).unwrap();
        let close = |a: &[f64], b: &[f64]| {
            let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12 * scale)
        };
        let (mut a, mut b) = (vec![0.0; grid.len()], vec![0.0; grid.len()]);
        fft.apply(&input, &mut a);
        dense.apply(&input, &mut b);
        prop_assert!(close(&b, &a), "product {nx}x{ny}");
        DirectInfluence::new(grid, material).unwrap().apply(&input, &mut a);
        prop_assert!(close(&b, &a), "product against the direct sum {nx}x{ny}");
        fft.precondition(&input, &mut a);
        dense.precondition(&input, &mut b);
        prop_assert!(close(&b, &a), "preconditioner {nx}x{ny}");
    }
}

/// max |a − b| over the max |b| of two vector fields (x and y components together: one
/// component may vanish by symmetry, e.g. the y coupling on a single row).
fn relative_error((ax, ay): (&[f64], &[f64]), (bx, by): (&[f64], &[f64])) -> f64 {
    let (a, b) = ([ax, ay].concat(), [bx, by].concat());
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let err = a
        .iter()
        .zip(&b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    if scale > 0.0 { err / scale } else { err }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Every product of the FFT tangential operator against the direct sums of the
    /// closed-form coefficients, for all three kernels (the shifted and coupling kernels are
    /// not symmetric: the FFT's complex spectrum path), dissimilar bodies (K ≠ 0), grids
    /// down to 1 × 1. Agreement to 1e-12 of the largest value, as for the normal operator.
    #[test]
    fn fft_tangential_equals_direct_sums(
        nx in 1usize..9,
        ny in 1usize..9,
        dx in 1e-5f64..1e-3,
        aspect in 0.2f64..5.0,
        e2 in 1e8f64..1e12,
        nu2 in 0.0f64..0.49,
        shift in 0.05f64..2.0,
        seed in any::<u64>(),
    ) {
        let grid = Grid::new(nx, ny, dx, dx * aspect, 0.4 * dx, -1.3 * dx).unwrap();
        let material = Material::combine(
            Body::elastic(210e9, 0.3).unwrap(),
            Body::elastic(e2, nu2).unwrap(),
        ).unwrap();
        let n = grid.len();
        let mut state = seed | 1;
        let mut random = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.3
        };
        let px: Vec<f64> = (0..n).map(|_| 1e7 * random()).collect();
        let py: Vec<f64> = (0..n).map(|_| 1e7 * random()).collect();
        let pn: Vec<f64> = (0..n).map(|_| 1e8 * (random() + 0.3)).collect();
        let mut fast = FftTangentialInfluence::new(grid, &material).unwrap();
        let mut slow = DirectTangentialInfluence::new(grid, material).unwrap();
        for kernel in [
            TangentialKernel::Direct,
            TangentialKernel::Steady,
            TangentialKernel::Shifted(shift * dx),
        ] {
            fast.prepare(kernel);
            slow.prepare(kernel);
            let mut out = [vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]];
            for update in [Update::Set, Update::Subtract] {
                let [fx, fy, sx, sy] = &mut out;
                fast.traction_product(kernel, update, (&px, &py), (fx, fy));
                slow.traction_product(kernel, update, (&px, &py), (sx, sy));
                let err = relative_error((fx, fy), (sx, sy));
                prop_assert!(err <= 1e-12, "{kernel:?} {update:?} traction: {err:e}");
                fast.pressure_product(kernel, update, &pn, (fx, fy));
                slow.pressure_product(kernel, update, &pn, (sx, sy));
                let err = relative_error((fx, fy), (sx, sy));
                prop_assert!(err <= 1e-12, "{kernel:?} {update:?} pressure: {err:e}");
            }
            let (a, b) = (fast.own_coefficients(kernel), slow.own_coefficients(kernel));
            prop_assert!((a.0 - b.0).abs() <= 1e-12 * b.0.abs());
            prop_assert!((a.1 - b.1).abs() <= 1e-12 * b.1.abs());
            // One column over a box that excludes the first row and column when it can.
            let (jx, jy) = (nx / 2, ny / 2);
            let (cols, rows) = ((nx.min(2) - 1, nx - 1), (ny.min(2) - 1, ny - 1));
            let [fx, fy, sx, sy] = &mut out;
            for v in [&mut *fx, &mut *fy, &mut *sx, &mut *sy] {
                v.fill(0.0);
            }
            fast.add_column(kernel, (jx, jy), (2e6, -3e6), (fx, fy), cols, rows);
            slow.add_column(kernel, (jx, jy), (2e6, -3e6), (sx, sy), cols, rows);
            let err = relative_error((fx, fy), (sx, sy));
            prop_assert!(err <= 1e-12, "{kernel:?} column: {err:e}");
        }
        let (mut fast_n, mut slow_n) = (vec![0.0; n], vec![0.0; n]);
        fast.normal_from_traction((&px, &py), &mut fast_n);
        slow.normal_from_traction((&px, &py), &mut slow_n);
        let err = relative_error((&fast_n, &[]), (&slow_n, &[]));
        prop_assert!(err <= 1e-12, "normal from traction: {err:e}");
    }
}

//! The FFT influence operator against the direct O(n²) oracle from Love's formula on random
//! grids, materials and pressures.

use halfspace::{DirectInfluence, FftInfluence, Grid, InfluenceOperator, Material};
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

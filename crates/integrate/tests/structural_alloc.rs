//! The steppers preallocate their workspaces: stepping a linear problem allocates nothing.
//! Checked with a counting global allocator that counts the allocations of the test's own
//! thread only: the harness's main thread allocates at random moments (the likely cause of
//! the one failure seen, under load 12, when every thread was counted; `alloc_support`).

mod alloc_support;

use alloc_support::{CountingAllocator, allocations};

use faer::Mat;
use integrate::structural::{LinearStructure, StructuralMethod, StructuralStepper};

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

#[test]
fn stepping_a_linear_problem_does_not_allocate() {
    let n = 6;
    let m = Mat::from_fn(n, n, |i, j| if i == j { 1.0 + i as f64 } else { 0.0 });
    let k = Mat::from_fn(n, n, |i, j| match i.abs_diff(j) {
        0 => 4.0,
        1 => -1.5,
        _ => 0.0,
    });
    let c = Mat::from_fn(n, n, |i, j| 0.01 * k[(i, j)]);
    let mut problem = LinearStructure::new(m, Some(c), k, |t: f64, f: &mut [f64]| {
        f.fill(0.0);
        f[0] = t.sin();
    })
    .unwrap();
    for method in [
        StructuralMethod::average_acceleration(),
        StructuralMethod::hht(-0.2).unwrap(),
        StructuralMethod::generalized_alpha(0.6).unwrap(),
        StructuralMethod::BackwardEuler,
        StructuralMethod::StormerVerlet,
        StructuralMethod::Leapfrog,
        StructuralMethod::central_difference(),
    ] {
        let mut s =
            StructuralStepper::new(method, &mut problem, 0.0, &[0.1; 6], &[0.0; 6]).unwrap();
        // The first step builds the cached factorisations.
        s.step(&mut problem, 0.01).unwrap();
        let before = allocations();
        for _ in 0..100 {
            s.step(&mut problem, 0.01).unwrap();
        }
        let allocations = allocations() - before;
        assert_eq!(
            allocations, 0,
            "{method:?} allocated {allocations} times in 100 steps"
        );
    }
}

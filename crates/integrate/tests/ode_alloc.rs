//! No heap allocation inside the step loop: a counting global allocator records the
//! allocations of the test's own thread (the harness's threads allocate at random moments)
//! while every method takes 200 steps after its warm-up.

mod ode_support;

use integrate::ode::{Method, OdeOptions};
use ode_support::{Robertson, VanDerPol};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct CountingAllocator;

thread_local! {
    /// Allocations made by the current thread (const-initialised: no allocation on access).
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn count_allocation() {
    // `try_with`: the thread-local may already be destroyed while a thread exits.
    let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
}

fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

// SAFETY: forwards to the system allocator unchanged; only counts calls.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count_allocation();
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count_allocation();
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

#[test]
fn steps_do_not_allocate() {
    let fixed = |m: Method| (m, OdeOptions::fixed(1e-4));
    let adaptive = |m: Method| (m, OdeOptions::adaptive(1e-6, 1e-8));
    let mut cases: Vec<(Method, OdeOptions)> = [
        Method::Euler,
        Method::Rk4,
        Method::BackwardEuler,
        Method::Adams,
    ]
    .into_iter()
    .map(fixed)
    .collect();
    cases.extend(
        [Method::Dopri5, Method::Radau5, Method::Bdf, Method::Adams]
            .into_iter()
            .map(adaptive),
    );
    for (method, opts) in cases {
        // Van der Pol (finite-difference Jacobian) and Robertson (analytic Jacobian).
        let mut vdp = VanDerPol { eps: 1e-3 };
        let at_build = allocations();
        let mut stepper = method.build(2, &opts).unwrap();
        // The counter works: building the stepper preallocates its workspace.
        assert!(allocations() > at_build);
        stepper.set_state(&mut vdp, 0.0, &[2.0, 0.0]).unwrap();
        for _ in 0..10 {
            stepper.step(&mut vdp).unwrap();
        }
        let before = allocations();
        for _ in 0..200 {
            stepper.step(&mut vdp).unwrap();
        }
        let mut out = [0.0; 2];
        stepper
            .interpolate(0.5 * (stepper.t_prev() + stepper.t()), &mut out)
            .unwrap();
        let during = allocations() - before;
        assert_eq!(
            during,
            0,
            "{} allocated {during} times in 200 steps (Van der Pol)",
            method.name()
        );

        let mut stepper = method.build(3, &opts).unwrap();
        stepper
            .set_state(&mut Robertson, 0.0, &[1.0, 0.0, 0.0])
            .unwrap();
        for _ in 0..10 {
            stepper.step(&mut Robertson).unwrap();
        }
        let before = allocations();
        for _ in 0..200 {
            stepper.step(&mut Robertson).unwrap();
        }
        let during = allocations() - before;
        assert_eq!(
            during,
            0,
            "{} allocated {during} times in 200 steps (Robertson)",
            method.name()
        );
    }
}

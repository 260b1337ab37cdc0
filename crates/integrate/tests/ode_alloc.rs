//! No heap allocation inside the step loop: a counting global allocator records allocations
//! while every method takes 200 steps after its warm-up (one test only in this binary, so no
//! other thread allocates meanwhile).

mod ode_support;

use integrate::ode::{Method, OdeOptions};
use ode_support::{Robertson, VanDerPol};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct CountingAllocator;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to the system allocator unchanged; only counts calls.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

#[test]
fn steps_do_not_allocate() {
    for method in Method::ALL {
        let opts = match method {
            Method::Euler | Method::Rk4 | Method::BackwardEuler | Method::Adams => {
                OdeOptions::fixed(1e-4)
            }
            _ => OdeOptions::adaptive(1e-6, 1e-8),
        };
        // Van der Pol (finite-difference Jacobian) and Robertson (analytic Jacobian).
        let mut vdp = VanDerPol { eps: 1e-3 };
        let at_build = ALLOCATIONS.load(Ordering::Relaxed);
        let mut stepper = method.build(2, &opts).unwrap();
        // The counter works: building the stepper preallocates its workspace.
        assert!(ALLOCATIONS.load(Ordering::Relaxed) > at_build);
        stepper.set_state(&mut vdp, 0.0, &[2.0, 0.0]).unwrap();
        for _ in 0..10 {
            stepper.step(&mut vdp).unwrap();
        }
        let before = ALLOCATIONS.load(Ordering::Relaxed);
        for _ in 0..200 {
            stepper.step(&mut vdp).unwrap();
        }
        let mut out = [0.0; 2];
        stepper
            .interpolate(0.5 * (stepper.t_prev() + stepper.t()), &mut out)
            .unwrap();
        let during = ALLOCATIONS.load(Ordering::Relaxed) - before;
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
        let before = ALLOCATIONS.load(Ordering::Relaxed);
        for _ in 0..200 {
            stepper.step(&mut Robertson).unwrap();
        }
        let during = ALLOCATIONS.load(Ordering::Relaxed) - before;
        assert_eq!(
            during,
            0,
            "{} allocated {during} times in 200 steps (Robertson)",
            method.name()
        );
    }
}

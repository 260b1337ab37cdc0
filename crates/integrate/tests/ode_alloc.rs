//! No heap allocation inside the step loop: a counting global allocator records the
//! allocations of the test's own thread (the harness's threads allocate at random moments)
//! while every method takes 200 steps after its warm-up.

mod alloc_support;

use alloc_support::{CountingAllocator, allocations};

mod ode_support;

use integrate::ode::{Method, OdeOptions};
use ode_support::{Robertson, VanDerPol};

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

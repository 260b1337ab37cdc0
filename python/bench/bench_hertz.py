"""Benchmarks of the Python package (install it in release mode first: `pip install ./python`).

1. A 512 × 512 Hertz sphere (steel on steel, R = 10 mm, F = 1 kN, grid ±1.25 a) solved from
   Python with dyncontact, and with tamaas (a well-known FFT contact library) if it is
   installed: best of 3 wall times and the relative errors of p0 and F (or δ) against Hertz,
   side by side. tamaas is not a dependency; it is skipped when absent.
2. The per-call overhead of `solve_normal` on 32 × 32: the wall time of the Python call minus
   the Rust solve time the call reports (`solve_time_s`, measured inside Rust around the
   solver's set-up and solve), median of 2000 calls.

Run: python python/bench/bench_hertz.py
"""

import math
import statistics
import time

import numpy as np

import dyncontact

E, NU, R, F = 210e9, 0.3, 0.01, 1000.0
E_STAR = E / (2 * (1 - NU**2))
A = (3 * F * R / (4 * E_STAR)) ** (1 / 3)
P0 = 3 * F / (2 * math.pi * A * A)
DELTA = A * A / R


def sphere(n, half_width):
    dx = 2 * half_width / n
    x = -half_width + (np.arange(n) + 0.5) * dx
    xx, yy = np.meshgrid(x, x)
    return (xx**2 + yy**2) / (2 * R), dx


def best_of(k, f):
    best, out = math.inf, None
    for _ in range(k):
        t0 = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - t0)
    return best, out


def dyncontact_512():
    gap, dx = sphere(512, 1.25 * A)
    t, r = best_of(3, lambda: dyncontact.solve_normal(gap, dx, dx, {"E": E, "nu": NU}, force=F))
    return t, r.max_pressure / P0 - 1, r.approach / DELTA - 1, r.iterations


def tamaas_512():
    try:
        import tamaas as tm
    except ImportError:
        return None
    # tamaas solves a periodic problem: the domain is 4 × the Hertz patch so the periodic
    # images barely interact (the grid then resolves the patch 3.2 × more coarsely than
    # dyncontact's non-periodic ±1.25 a grid with the same 512 × 512 elements).
    n, width = 512, 8 * A
    dx = width / n
    x = (np.arange(n) + 0.5) * dx - width / 2
    xx, yy = np.meshgrid(x, x, indexing="ij")
    surface = -((xx**2 + yy**2) / (2 * R))

    def solve():
        # A new model each time: a cold start like dyncontact's (tamaas keeps the last traction).
        model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [width, width], [n, n])
        model.E = E / 2  # E_star = (E/2)/(1 - nu^2): the combined modulus of two steel bodies
        model.nu = NU
        solver = tm.PolonskyKeerRey(model, surface, 1e-12)
        solver.dump_freq = 10**9  # quiet (tamaas still prints its first and last iteration)
        solver.solve(F / (width * width))
        return model.traction.copy(), solver

    t, (p, _) = best_of(3, solve)
    force = p.sum() * dx * dx
    return t, p.max() / P0 - 1, force / F - 1


def overhead_32(calls=2000):
    gap, dx = sphere(32, 1.25 * A)
    mat = {"E": E, "nu": NU}
    for _ in range(50):
        dyncontact.solve_normal(gap, dx, dx, mat, force=F)
    extra, total, rust = [], [], []
    for _ in range(calls):
        t0 = time.perf_counter()
        r = dyncontact.solve_normal(gap, dx, dx, mat, force=F)
        wall = time.perf_counter() - t0
        extra.append(wall - r.solve_time_s)
        total.append(wall)
        rust.append(r.solve_time_s)
    return statistics.median(extra), statistics.median(total), statistics.median(rust)


def main():
    print(f"Hertz sphere, steel on steel, R = {R} m, F = {F} N: a = {A:.4e} m, p0 = {P0:.4e} Pa, delta = {DELTA:.4e} m")
    t, ep, ed, it = dyncontact_512()
    print(f"{'library':>12} {'grid':>9} {'time s':>8} {'err p0':>10} {'err F/delta':>12}")
    print(f"{'dyncontact':>12} {'512x512':>9} {t:8.3f} {ep:10.2e} {ed:12.2e}   ({it} NormCG iterations, delta error)")
    tm = tamaas_512()
    if tm is None:
        print(f"{'tamaas':>12} not installed (pip install tamaas to compare; not a dependency)")
    else:
        t, ep, ef = tm
        print(f"{'tamaas':>12} {'512x512':>9} {t:8.3f} {ep:10.2e} {ef:12.2e}   (periodic, 4x patch; force error)")
    extra, total, rust = overhead_32()
    print(
        f"solve_normal 32x32: median call {total * 1e6:.1f} us = Rust set-up and solve "
        f"{rust * 1e6:.1f} us + overhead {extra * 1e6:.1f} us (target <= 20 us)"
    )


if __name__ == "__main__":
    main()

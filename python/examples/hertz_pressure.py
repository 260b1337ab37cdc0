"""Example: a Hertz case from its TOML file and a rough surface from numpy, with a plot.

Run from the repository root after `pip install ./python`:
    python python/examples/hertz_pressure.py
Writes hertz_pressure.png when matplotlib is installed (it is not a dependency).
"""

import numpy as np

import dyncontact

# 1. The example case file, as `dyncontact contact examples/hertz_sphere.toml`.
r = dyncontact.contact("examples/hertz_sphere.toml")
print(f"sphere: F = {r.normal_force:.1f} N, p_max = {r.max_pressure / 1e9:.4f} GPa "
      f"(Hertz {r.hertz['max_pressure'] / 1e9:.4f} GPa), {r.iterations} iterations")

# 2. A user-made gap: the same sphere with 0.1 µm rms of uncorrelated per-element noise (an
#    illustration of a rough gap from numpy, not a model of a real surface).
n = 128
a = r.hertz["a"]
dx = 2.5 * a / n
x = -1.25 * a + (np.arange(n) + 0.5) * dx
xx, yy = np.meshgrid(x, x)
rng = np.random.default_rng(1)
gap = (xx**2 + yy**2) / (2 * 0.01) + 0.1e-6 * rng.standard_normal((n, n))
gap -= gap.min()
rough = dyncontact.solve_normal(gap, dx, dx, {"E": 210e9, "nu": 0.3}, force=1000.0)
print(f"rough: p_max = {rough.max_pressure / 1e9:.3f} GPa, contact area "
      f"{rough.contact_area * 1e6:.4f} mm^2 (smooth {r.contact_area * 1e6:.4f} mm^2)")

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("matplotlib is not installed: no plot")
else:
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for axis, res, title in ((ax[0], r, "smooth (Hertz)"), (ax[1], rough, "rough, 0.1 µm rms")):
        extent = [res.x[0] * 1e3, res.x[-1] * 1e3, res.y[0] * 1e3, res.y[-1] * 1e3]
        im = axis.imshow(res.pressure / 1e9, origin="lower", extent=extent, cmap="viridis")
        axis.set(title=title, xlabel="x [mm]", ylabel="y [mm]")
        fig.colorbar(im, ax=axis, label="p [GPa]")
    fig.tight_layout()
    fig.savefig("hertz_pressure.png", dpi=120)
    print("wrote hertz_pressure.png")

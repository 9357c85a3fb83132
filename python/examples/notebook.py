# %% [markdown]
# # vibrissa from Python: a notebook-style walk through
#
# Run it cell by cell in an editor that knows `# %%` cells (VS Code, Spyder, Jupyter via
# jupytext) or as a script: `.venv/bin/python python/examples/notebook.py`. It needs only the
# package (`sh python/setup.sh`); matplotlib, if installed, draws the curves.

# %%
import numpy as np

import vibrissa

# A tapered, pre-curved whisker on a compliant support, pressed on a surface at 0.85 L.
rod = vibrissa.Rod(taper=0.3, precurvature=-0.5, precurvature_slope=0.2, support_compliance=0.1)
surface = vibrissa.Surface(eta=0.85)
print(rod, surface)

# %% [markdown]
# ## One rod: the tip force for a given tip slope

# %%
shape = vibrissa.solve(rod, alpha=-0.2, phi1=0.4)
print(f"f = {shape['f']:.6f}, m(0) = {shape['m_base']:.6f}, flex points: {shape['flex']}")
print("tip at", shape["x1"], shape["y1"], "=", shape["shape"]["x"][-1], shape["shape"]["y"][-1])

# %% [markdown]
# ## The stiction scan: mu(d) while the foot is dragged by d

# %%
result = vibrissa.scan(rod, surface, points=101, shape_points=41)
print(result)
d, mu = result.points["d"], result.points["mu"]
print(f"measurable range: mu0 in [0, {result.mu_max:.4f}] for d in [0, {result.d_at_mu_max:.4f}]")
print("stopped:", result.stop)

# %% [markdown]
# ## From a slip displacement back to mu0

# %%
d0 = 0.5 * result.d_at_mu_max
print(vibrissa.infer(rod, surface, d0))

# %% [markdown]
# ## A sweep over the surface height and the taper, in parallel

# %%
sweep = vibrissa.sweep(vibrissa.grid(eta=np.linspace(0.7, 0.95, 6), taper=[0.3, 0.6, 1.0]), points=51)
print(sweep)
for eta, taper, mu_max, stop in zip(sweep["eta"], sweep["taper"], sweep["mu_max"], sweep["stop_reason"]):
    print(f"eta {eta:.2f} taper {taper:.1f}: mu_max {mu_max:.4f} ({stop})")

# %%
try:
    import matplotlib.pyplot as plt
except ImportError:
    plt = None
if plt is not None:
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    a.plot(d, mu)
    a.set_xlabel("foot displacement d (L)")
    a.set_ylabel("friction ratio mu")
    for i in range(0, len(result), 10):
        b.plot(result.shapes["x"][i] + d[i], result.shapes["y"][i])
    b.axhline(surface.eta, color="k")
    b.set_aspect("equal")
    b.set_xlabel("x (L)")
    b.set_ylabel("y (L)")
    plt.show()

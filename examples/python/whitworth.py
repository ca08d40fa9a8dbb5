# %% [markdown]
# # The Whitworth shaping machine in a notebook
#
# Cells in the `# %%` format (Jupyter, VS Code, `jupytext --to ipynb`). As a script, from
# the repository's root (needs `pip install "./python[study]" pandas matplotlib`):
#
#     python examples/python/whitworth.py [FOLDER]
#
# draws ψ, ψ′ and ψ″ into `FOLDER/whitworth_psi.png` (default: the current folder), then runs
# a tolerance Monte Carlo and a design grid on a Dask LocalCluster of two workers.

# %%
import math
import sys
from pathlib import Path

import numpy as np

import mechdiff
import mechdiff.study

# Dask's worker processes import this file to start: the cells that compute, draw or start a
# cluster run only as `__main__` (in the notebook, or as the script).
MAIN = __name__ == "__main__"
ROOT = Path(__file__).resolve().parents[2] if "__file__" in globals() else Path.cwd()
scene = mechdiff.load(ROOT / "scenes" / "whitworth.toml")
if MAIN:
    run = scene.run()
    print(run.plan)
    print({name: run.units[name] for name in run})

# %% [markdown]
# The rocker's angle against its closed form (reference 000: λ = l1/l0 = 0.375,
# tan ψ = λ sin φ / (1 − λ cos φ)), and the ram's dead positions (where x_C′ = 0), found by
# Newton on the exact derivatives: at cos φ = λ.

# %%
if MAIN:
    lam = 0.150 / 0.400
    phi = np.radians(run["phi"])
    closed = np.degrees(np.arctan2(lam * np.sin(phi), 1 - lam * np.cos(phi)))
    print(f"max |ψ − closed form| = {np.max(np.abs(run['psi'] - closed)):.1e} deg")
    print("dead positions of the ram (φ deg, x_C m):", run.dead_positions["x_C"])
    print(f"cos φ = λ at φ = {math.degrees(math.acos(lam)):.10f} deg")

# %% [markdown]
# ψ′ and ψ″ — the rocker's velocity and acceleration coefficients — over a turn of the crank:
# exact (dual numbers), no difference quotient. The ram's dead positions are marked.

# %%
if MAIN:
    import matplotlib

    if "ipykernel" not in sys.modules:
        matplotlib.use("Agg")  # a script draws into files; a notebook shows the figure inline
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(7, 6.5), constrained_layout=True)
    labels = ["ψ", "ψ′ = dψ/dφ", "ψ″ = d²ψ/dφ²"]
    for ax, name, label in zip(axes, ["psi", "psi'", "psi''"], labels):
        ax.plot(run["phi"], run[name], color="tab:blue")
        unit = run.units[name]
        ax.set_ylabel(f"{label} [{unit}]" if unit != "1" else label)
        for dead, _ in run.dead_positions["x_C"]:
            ax.axvline(dead, color="tab:red", lw=0.8, ls="--")
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel(f"φ [{run.units['phi']}]")
    axes[-1].set_xticks(range(0, 361, 45))
    axes[0].set_title(
        "Whitworth: the rocker's angle and its exact derivatives "
        "(dashed: the ram's dead positions)",
        fontsize=9,
    )
    script = len(sys.argv) > 1 and "ipykernel" not in sys.modules
    folder = Path(sys.argv[1]) if script else Path(".")
    folder.mkdir(parents=True, exist_ok=True)
    fig.savefig(folder / "whitworth_psi.png", dpi=110)
    print("ψ, ψ′, ψ″ drawn in", folder / "whitworth_psi.png")

# %% [markdown]
# A tolerance study: the crank pivot's height l0 and the crank l1 within ±0.1 mm. The scene
# writes them as numbers; read it again with them as `[parameters]` (every point that uses
# them follows), over a coarser sweep (every 5°). 20 480 variants on a LocalCluster of two
# workers, against the first-order prediction of the exact sensitivities: for a uniform
# ±t, σ = t/√3 · |dx_C/dp|, summed in squares.

# %%
from distributed import Client, LocalCluster

text = scene.text.replace("[points]", "[parameters]\nl0 = 0.400\nl1 = 0.150\n\n[points]", 1)
text = text.replace("A0 = [0.0, 0.400]", 'A0 = [0.0, "l0"]').replace("A = [0.0, 0.250]", 'A = [0.0, "l0 - l1"]')
text = text.replace("step = 0.5", "step = 5")
tolerant = mechdiff.parse(text, file="whitworth.toml (l0, l1 as parameters)")
tolerances = {"l0": 1e-4, "l1": 1e-4}  # ± m

if MAIN:
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None)
    client = Client(cluster)
    mc = mechdiff.study.monte_carlo(tolerant, tolerances, 20_480, columns=["x_C"], client=client)
    sens = tolerant.sensitivity(of="x_C", wrt=list(tolerances))
    predicted = np.sqrt(sum((sens[f"d(x_C)/d({p})"] * t) ** 2 for p, t in tolerances.items()) / 3)
    k = int(np.argmax(predicted))
    print(
        f"σ(x_C) at φ = {mc.drive[k]:g}°: sampled {mc.std['x_C'][k]:.4e} m, first order "
        f"{predicted[k]:.4e} m ({mc.samples} variants, {mc.chunks} chunks, {mc.failed} failed)"
    )

# %% [markdown]
# A design grid on the same cluster: the crank l1 from 0.10 m to 0.20 m, the ram's stroke
# from each variant's positions against the closed form 2hλ/√(1 − λ²) at the dead positions
# (the 5° sweep samples near them: slightly less). A DataFrame, one row per variant and
# position, units in `grid.attrs["units"]`.

# %%
if MAIN:
    grid = mechdiff.study.grid(
        tolerant, {"l1": np.linspace(0.10, 0.20, 5)}, columns=["x_C"], client=client
    )
    stroke = grid.groupby("l1").x_C.agg(lambda x: x.max() - x.min()).to_frame("sampled [m]")
    lam = stroke.index.to_numpy() / 0.400
    stroke["closed form [m]"] = 2 * 0.650 * lam / np.sqrt(1 - lam**2)
    print("the ram's stroke:")
    print(stroke)
    client.close()
    cluster.close()

# %% [markdown]
# # The Whitworth shaping machine in a notebook
#
# Cells in the `# %%` format (Jupyter, VS Code, `jupytext --to ipynb`). Run from the
# repository's root: `python python/examples/whitworth_notebook.py` (matplotlib optional).

# %%
from pathlib import Path

import numpy as np

import mechdiff
import mechdiff.study

ROOT = Path(__file__).resolve().parents[2] if "__file__" in globals() else Path.cwd()
scene = mechdiff.load(ROOT / "scenes" / "whitworth.toml")
run = scene.run()
print(run.plan)
print({name: run.units[name] for name in run})

# %% [markdown]
# ψ″ — the rocker's acceleration coefficient — over a turn of the crank, and the ram's dead
# positions (where x_C′ = 0), found by Newton on the exact derivatives.

# %%
print("dead positions of the ram:", run.dead_positions["x_C"])
try:
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.plot(run["phi"], run["psi''"])
    ax.set_xlabel(f"φ [{run.units['phi']}]")
    unit = run.units["psi''"]
    ax.set_ylabel(f"ψ″ [{unit}]")
    fig.savefig("whitworth_psi_pp.png")
    print("ψ″ drawn in whitworth_psi_pp.png")
except ImportError:
    print("(pip install matplotlib to draw ψ″)")

# %% [markdown]
# A tolerance study: the crank and the frame within ±0.1 mm, 20 000 variants on a
# LocalCluster of two workers, against the exact sensitivities' first-order prediction.

# %%
text = scene.text.replace("[points]", "[parameters]\nl0 = 0.400\nl1 = 0.150\n\n[points]", 1)
text = text.replace("A0 = [0.0, 0.400]", 'A0 = [0.0, "l0"]').replace("A = [0.0, 0.250]", 'A = [0.0, "l0 - l1"]')
tolerant = mechdiff.parse(text, file="whitworth (l0, l1 as parameters)")
tolerances = {"l0": 1e-4, "l1": 1e-4}
if __name__ == "__main__":
    mc = mechdiff.study.monte_carlo(tolerant, tolerances, 20_480, columns=["x_C"])
    sens = tolerant.sensitivity(of="x_C", wrt=list(tolerances))
    predicted = np.sqrt(sum((sens[f"d(x_C)/d({p})"] * t) ** 2 for p, t in tolerances.items()) / 3)
    k = int(np.argmax(predicted))
    print(f"σ(x_C) at φ = {mc.drive[k]}°: sampled {mc.std['x_C'][k]:.4e} m, "
          f"first order {predicted[k]:.4e} m; worker peaks (MB): "
          f"{[round(p / 2**20) for p in mc.peak_rss.values()]}")

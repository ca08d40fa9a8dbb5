"""Shared paths and reference formulas of the pytest suite."""

from pathlib import Path

import numpy as np
import pytest

#: The repository's root (the scenes are in scenes/).
ROOT = Path(__file__).resolve().parents[2]
SCENES = ROOT / "scenes"


def norton_psi(phi, b, a=0.86, c=0.86, d=2.22):
    """ψ (rad) of Norton's four-bar solved by hand from the triangle A–B–O4, B on the left of
    A → O4 (the open assembly of scenes/norton_four_bar.toml); the same closed form as the
    facade's doc-test in src/lib.rs. ``phi`` in rad, lengths in m."""
    phi = np.asarray(phi, dtype=float)
    ax, ay = a * np.cos(phi), a * np.sin(phi)
    length = np.hypot(d - ax, ay)
    ux, uy = (d - ax) / length, -ay / length
    x = (b * b - c * c + length * length) / (2 * length)
    h = np.sqrt(b * b - x * x)
    bx, by = ax + x * ux - h * uy, ay + x * uy + h * ux
    return np.arctan2(by, bx - d)


@pytest.fixture(scope="session")
def norton_psi_deg():
    """:func:`norton_psi` with ``phi`` and the result in degrees."""
    return lambda phi, **lengths: np.degrees(norton_psi(np.radians(phi), **lengths))


@pytest.fixture(scope="session")
def norton_path():
    return SCENES / "norton_four_bar.toml"


@pytest.fixture(scope="session")
def client():
    """A Dask client of a 2-worker LocalCluster (one thread each), shared by the studies'
    tests (starting one takes seconds)."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        yield client

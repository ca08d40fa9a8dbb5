"""A design grid of the Norton four-bar: on a 2-worker LocalCluster equal to the serial
library run bit for bit, a value against the closed form, failed variants as rows with their
reasons, the Parquet files equal to the DataFrame."""

import math
import re

import numpy as np
import pytest

import mechdiff
import mechdiff.study as study

pd = pytest.importorskip("pandas")

# a × b: 3 × 4 variants; b = 1.2 m is blocked inside the sweep, 5.0 m cannot be built at all.
VALUES = {"a": [0.85, 0.86, 0.87], "b": [1.2, 1.85, 1.9, 5.0]}


@pytest.fixture(scope="module")
def norton(norton_path):
    return mechdiff.load(norton_path)


@pytest.fixture(scope="module")
def serial(norton):
    return study.grid(norton, VALUES, chunk=5, client="serial")


@pytest.fixture(scope="module")
def on_cluster(norton, client):
    return study.grid(norton, VALUES, chunk=5, client=client)


def test_a_grid_on_a_2_worker_cluster_equals_the_serial_library_run_bit_for_bit(
    norton, serial, on_cluster
):
    # The serial library run: every variant of the full factorial (b fastest) in one call.
    a, b = np.meshgrid(VALUES["a"], VALUES["b"], indexing="ij")
    library = norton.run_variants({"a": a.ravel(), "b": b.ravel()}, ["phi", "psi", "psi'", "psi_dot"])
    failed = {index for index, _, _ in library.failures}
    assert failed == {0, 3, 4, 7, 8, 11}  # b = 1.2 and b = 5.0 for each a
    for variant in range(12):
        rows = on_cluster[on_cluster.variant == variant]
        assert (rows.a == a.ravel()[variant]).all() and (rows.b == b.ravel()[variant]).all()
        if variant in failed:
            assert len(rows) == 1 and rows.position.isna().all()
            continue
        assert rows.position.tolist() == list(range(11))
        for k, column in enumerate(library.columns):
            np.testing.assert_array_equal(rows[column].to_numpy(), library.values[variant, :, k])
    # Chunks of 5 (3 tasks) spread over two processes, put back in order: the same frame.
    pd.testing.assert_frame_equal(on_cluster, serial, check_exact=True)
    assert on_cluster.attrs["units"] == {"phi": "deg", "psi": "deg", "psi'": "1", "psi_dot": "rad/s"}


def test_a_grid_value_equals_the_closed_form_of_the_triangle(serial, norton_psi_deg):
    # ψ of (a, b) = (0.87, 1.9) m at every drive position against the hand solution of the
    # triangle A–B–O4 (conftest.norton_psi): the solver's closed form agrees to rounding,
    # 1e-12 deg (ψ ~ 70 deg, so ~1e-14 relative).
    rows = serial[(serial.a == 0.87) & (serial.b == 1.9)]
    expected = norton_psi_deg(rows.phi.to_numpy(), b=1.9, a=0.87)
    assert np.max(np.abs(rows.psi.to_numpy() - expected)) < 1e-12


def test_failed_variants_are_rows_with_their_reasons(serial):
    failed = serial[serial.reason.notna()]
    assert len(failed) == 6 and failed[["phi", "psi", "psi'", "psi_dot"]].isna().all().all()
    assert set(failed[failed.b == 5.0].kind) == {"Unconstructible"}
    assert set(failed[failed.b == 1.2].kind) == {"Blocked"}
    for _, row in failed[failed.b == 1.2].iterrows():
        # The loop A–B–O4 stops closing where |A O4| = b + c: cos φ = (d² + a² − (b + c)²)
        # / (2 a d), with c = 0.86, d = 2.22 m. The message gives it to 15 digits: 1e-9 deg.
        a, d, c = row.a, 2.22, 0.86
        limit = math.degrees(math.acos((d * d + a * a - (1.2 + c) ** 2) / (2 * a * d)))
        found = float(re.search(r"first fails at ([0-9.]+) deg", row.reason).group(1))
        assert abs(found - limit) < 1e-9, row.reason
        assert "norton_four_bar.toml" in row.reason
    # Every other variant has its 11 positions and no reason.
    assert len(serial) == 6 + 6 * 11 and serial[serial.reason.isna()].notna().drop(
        columns=["kind", "reason"]
    ).all().all()


def test_the_parquet_files_read_back_as_the_dataframe(norton, serial, tmp_path):
    pytest.importorskip("pyarrow")
    paths = study.grid(norton, VALUES, chunk=5, client="serial", out=tmp_path / "grid")
    assert [p.name for p in paths] == ["part-000000.parquet", "part-000001.parquet", "part-000002.parquet"]
    back = study.read_parquet(tmp_path / "grid")
    pd.testing.assert_frame_equal(back, serial, check_exact=True)
    assert back.attrs == serial.attrs
    # A folder that holds a study is never written over.
    with pytest.raises(mechdiff.ArgumentError, match="already holds"):
        study.grid(norton, VALUES, chunk=5, client="serial", out=tmp_path / "grid")


def test_the_measured_chunk_makes_a_task_of_at_least_task_seconds(norton):
    # The chunk is sized from the measured cost of a call (its nominal run) and of a
    # variant: chunk × per variant + per call ≥ TASK_SECONDS, unless one variant already is.
    rows = {"b": np.linspace(1.8, 1.9, 3)}
    grid = study.grid(norton, rows=rows, client="serial")
    attrs = grid.attrs
    assert attrs["seconds_per_variant"] > 0 and attrs["seconds_per_call"] >= 0
    assert (
        attrs["chunk"] * attrs["seconds_per_variant"] + attrs["seconds_per_call"]
        >= study.TASK_SECONDS
    )
    assert grid.b.unique().tolist() == rows["b"].tolist() and len(grid) == 3 * 11


def test_bad_designs_are_refused_before_work_starts(norton):
    with pytest.raises(mechdiff.SettingError, match="no parameter 'e'"):
        study.grid(norton, {"e": [1.0]}, client="serial")
    with pytest.raises(mechdiff.ArgumentError, match="parameter b of variant 1 is nan"):
        study.grid(norton, rows={"b": [1.9, float("nan")]}, client="serial")
    with pytest.raises(mechdiff.LimitError, match="100000000"):
        study.grid(norton, {"a": np.zeros(20_000), "b": np.zeros(20_000)}, client="serial")

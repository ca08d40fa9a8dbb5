"""Scenes read, run and differentiated through the Python API, against references that do
not use the method under test: closed forms, and the 30-digit values of reference 000."""

import json
import math
import pickle
from pathlib import Path

import numpy as np
import pytest

import mechdiff
from conftest import SCENES, norton_psi

WHITWORTH = json.loads((Path(__file__).parent / "whitworth_000.json").read_text())


def test_norton_psi_matches_the_closed_form_to_1e_12_rad(norton_path):
    scene = mechdiff.load(norton_path, b=1.9)
    assert scene.parameters == {"a": 0.86, "b": 1.9, "c": 0.86, "d": 2.22, "theta": 30.0}
    run = scene.run()
    assert list(run)[:2] == ["phi", "psi"]
    assert run.units["phi"] == "deg" and run.units["psi"] == "deg"
    # Degrees to radians and back: rounding, 1e-12 deg.
    np.testing.assert_allclose(run["phi"], np.arange(0.0, 101.0, 10.0), rtol=0, atol=1e-12)
    # The same to rounding: 1e-12 rad for lengths of order 1 (as the facade's doc-test).
    want = norton_psi(np.radians(run["phi"]), 1.9)
    assert np.max(np.abs(run.si("psi") - want)) < 1e-12


def test_run_at_positions_given_in_the_scenes_unit(norton_path):
    scene = mechdiff.load(norton_path)
    phi = np.linspace(-100.0, 100.0, 2001)  # deg, within the crank's ±116° rocking range
    run = scene.run(positions=phi)
    np.testing.assert_allclose(run["phi"], phi, rtol=0, atol=1e-12)  # deg → rad → deg
    assert np.max(np.abs(run.si("psi") - norton_psi(np.radians(phi), 1.85))) < 1e-12


def test_exact_sensitivity_matches_a_central_difference_of_the_closed_form(norton_path):
    scene = mechdiff.load(norton_path, b=1.9)
    sens = scene.sensitivity(of="psi", wrt="b")
    assert sens.methods["d(psi)/d(b)"].is_exact
    assert sens.units["d(psi)/d(b)"] == "deg per b"
    exact = sens.si("d(psi)/d(b)")  # rad per m
    phi = np.radians(sens["phi"])
    # Step 1e-5 m: truncation h²/6 ψ‴ and rounding ε/h both about 1e-11; 1e-8 leaves room.
    h = 1e-5
    difference = (norton_psi(phi, 1.9 + h) - norton_psi(phi, 1.9 - h)) / (2 * h)
    assert np.max(np.abs(exact - difference)) < 1e-8


def test_exact_sensitivity_matches_a_central_difference_of_two_runs(norton_path):
    scene = mechdiff.load(norton_path)
    sens = scene.sensitivity(columns=["d(psi)/d(a)"])
    # Runs at a ± 1e-4 m: truncation h²/6 |ψ‴| ≈ 1e-8·|ψ‴| (ψ‴ per m³ of order 10 here),
    # rounding 1e-16/1e-4: 1e-6 deg per m is ample and still 1e-6 of the column's size.
    h = 1e-4
    up = scene.with_parameters(a=0.86 + h).run()["psi"]
    down = scene.with_parameters(a=0.86 - h).run()["psi"]
    assert np.max(np.abs(sens["d(psi)/d(a)"] - (up - down) / (2 * h))) < 1e-6


def test_whitworth_coefficients_match_the_30_digit_reference_to_1e_12():
    run = mechdiff.load(SCENES / "whitworth.toml").run()
    phi = run["phi"]
    for row in WHITWORTH["rows"][:36]:  # 0, 10, ..., 350 deg
        i = int(np.argmin(np.abs(phi - float(row["phi_deg"]))))
        assert abs(phi[i] - float(row["phi_deg"])) < 1e-9
        # 1e-12 absolute: the quantities are of order 1 (rad, m); the Rust tests hold 1e-12
        # of each quantity's largest value.
        assert abs(run.si("psi")[i] - float(row["psi_rad"])) < 1e-12, row["phi_deg"]
        assert abs(run.si("psi'")[i] - float(row["psi_p"])) < 1e-12, row["phi_deg"]
        assert abs(run.si("psi''")[i] - float(row["psi_pp"])) < 1e-12, row["phi_deg"]
        assert abs(run.si("x_C")[i] - float(row["x_C_m"])) < 1e-12, row["phi_deg"]
        assert abs(run.si("x_C'")[i] - float(row["x_C_p_m"])) < 1e-12, row["phi_deg"]


def test_whitworth_dead_positions_and_stroke_match_the_reference():
    run = mechdiff.load(SCENES / "whitworth.toml").run()
    (phis, values) = zip(*run.dead_positions["x_C"])
    want = [float(p) for p in WHITWORTH["dead_positions_deg"]]
    # Roots refined by Newton on exact ψ″ to 1e-12 rad (tests/scenes.rs): 1e-10 deg.
    assert np.max(np.abs(np.array(phis) - want)) < 1e-10
    # The values are flat in φ there: the stroke to 1e-12 m.
    assert abs((max(values) - min(values)) - WHITWORTH["stroke_of_C_m"]) < 1e-12
    assert "dead position" in run.summary


def test_whitworth_inertial_forces_match_the_reference_table_to_1e_9():
    run = mechdiff.load(SCENES / "whitworth_forces.toml").run()
    names = {
        "Fx_crank": "F_x1_N",
        "Fy_crank": "F_y1_N",
        "Fx_rocker": "F_x2_N",
        "Fy_rocker": "F_y2_N",
        "Fx_ram": "F_x3_N",
        "SumF_x": "SumF_x_N",
        "SumF_y": "SumF_y_N",
    }
    table = sorted(WHITWORTH["inertial_forces"], key=lambda r: r["phi_deg"])
    for column, key in names.items():
        got = run.si(column)
        for i, row in enumerate(table):
            # 1e-9 relative; exact zeros to 1e-9 of the table's largest force (1923.7 N), as
            # tests/dynamics_scenes.rs holds the same scene.
            scale = abs(row[key]) or 1923.6870803851873
            assert abs(got[i] - row[key]) <= 1e-9 * scale, (column, row["phi_deg"])


def test_a_scene_pickles_as_its_text_and_settings(norton_path):
    scene = mechdiff.load(norton_path, b="2*a + 0.1")
    again = pickle.loads(pickle.dumps(scene))
    assert again.parameters["b"] == scene.parameters["b"] == 2 * 0.86 + 0.1
    np.testing.assert_array_equal(again.run()["psi"], scene.run()["psi"])


def test_variants_equal_single_runs_and_a_failed_variant_is_a_row_with_its_reason(norton_path):
    scene = mechdiff.load(norton_path)
    b = np.array([1.80, 1.85, 0.2, 1.90])  # b = 0.2 m cannot close the loop at φ = 0
    variants = scene.run_variants({"b": b}, columns=["psi"])
    assert variants.columns == ["psi"] and variants.values.shape == (4, 11, 1)
    for k in (0, 1, 3):
        want = scene.with_parameters(b=float(b[k])).run()["psi"]
        np.testing.assert_array_equal(variants.values[k, :, 0], want)
    assert np.all(np.isnan(variants.values[2]))
    ((index, kind, message),) = variants.failures
    assert index == 2 and kind in ("Unconstructible", "Unassemblable"), (kind, message)
    assert "norton_four_bar.toml" in message


def test_to_dict_and_to_numpy_hold_the_same_columns(norton_path):
    run = mechdiff.load(norton_path).run()
    table = run.to_numpy()
    for k, (name, values) in enumerate(run.to_dict().items()):
        np.testing.assert_array_equal(table[:, k], values)
    assert "<table>" in run._repr_html_() and "psi [deg]" in run._repr_html_()


def test_repr_html_shows_the_drawing_and_the_diagram_inline(norton_path):
    run = mechdiff.load(norton_path).run()
    page = run._repr_html_()
    # The mechanism's drawing and the diagram, each an inline SVG, then the table.
    assert page.count("<svg") == 2 and "psi [deg]" in page
    assert run.drawing_svg() in page and run.diagram_svg() in page
    # Nothing is fetched: no script, stylesheet or image from elsewhere.
    for fetched in ('src="http', "src='http", 'href="http', "@import", "<script src"):
        assert fetched not in page


def test_metrics_are_those_of_the_four_bar_by_its_lengths(norton_path):
    run = mechdiff.load(norton_path).run()
    (four_bar,) = run.metrics["linkage"]["four_bars"]
    grashof = four_bar["grashof"]
    # Norton's four-bar: a = c = 0.86 m, b = 1.85 m, d = 2.22 m. s + l = 0.86 + 2.22 = 3.08 m
    # against p + q = 0.86 + 1.85 = 2.71 m: not Grashof (no link turns fully).
    assert abs(grashof["s_plus_l"] - 3.08) < 1e-12 and abs(grashof["p_plus_q"] - 2.71) < 1e-12
    assert "non-Grashof" in grashof["class"]
    assert any("Grashof" in line or "grashof" in line for line in run.metrics_lines)


def test_a_sweep_that_reaches_a_limit_position_lists_it_in_the_drives_unit(norton_path):
    # The crank rocks between the limits at ±φ_max where the coupler and the rocker are in
    # line: |A O4| = b + c, so a² + d² − 2 a d cos φ = (b + c)², φ_max = 116.3...°.
    a, b, c, d = 0.86, 1.85, 0.86, 2.22
    limit = np.degrees(np.arccos((a * a + d * d - (b + c) ** 2) / (2 * a * d)))
    scene = mechdiff.parse(
        (SCENES / "norton_four_bar.toml").read_text().replace("to = 100", f"to = {limit - 0.01:.6f}"),
        file="norton.toml",
    )
    run = scene.run()
    kinds = {round(l.position, 6): l.kind for l in run.limits}
    # `check` walks the same range from the sketch both ways: ±φ_max.
    lower, upper = scene.check()["motion_range"]
    assert abs(lower[0] + limit) < 1e-6 and abs(upper[0] - limit) < 1e-6
    assert upper[1] == "limit position" and set(upper[2]) == {"A", "B", "O4"}
    # Walked from the sketch to 1e-9 rad: 1e-6 deg.
    assert any(abs(p - limit) < 1e-6 and k == "limit position" for p, k in kinds.items()), kinds

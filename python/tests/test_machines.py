"""Cams, rotors and reaction forces through the Python API, against closed forms and the
reference documents' values (/work/shared/reference/, copied here with their source)."""

import numpy as np
import pytest

import mechdiff
from conftest import SCENES

#: Reference 002 (cams_balancing_002.json, "simple_harmonic_motion"): y = 40 − 40 cos x mm
#: over one turn, at x = kπ/8: (x in deg, y mm, y′ mm/rad, y″ mm/rad²), the first eight rows.
SHM_TABLE = [
    (0.0, 0.0, 0.0, 40.0),
    (22.5, 3.0448186995485296, 15.307337294603592, 36.95518130045147),
    (45.0, 11.7157287525381, 28.284271247461902, 28.284271247461902),
    (67.5, 24.69266270539641, 36.95518130045147, 15.307337294603592),
    (90.0, 40.0, 40.0, 0.0),
    (112.5, 55.30733729460359, 36.95518130045147, -15.307337294603592),
    (135.0, 68.2842712474619, 28.284271247461902, -28.284271247461902),
]

#: Reference 001 (rack_slotted_link_001.json, `dynamics.unknowns`), with the scene's column
#: and sign for each, as tests/dynamics_scenes.rs maps them: (H_C, V_C) is minus the force
#: on the rod at C, N_A and T_A minus the slot's force on the pin.
RACK_REACTIONS = [
    ("M_motor", 1, 0.9981773363503413),
    ("Fx_B", 1, -268.8517356872072),
    ("Fy_B", 1, 471.08699787976),
    ("Fx_C", -1, -369.30708370188097),
    ("Fy_C", -1, -199.1017823427619),
    ("Fx_D", 1, 369.30708370188097),
    ("Fy_D", 1, 199.1017823427619),
    ("N_A", -1, -665.3467565761739),
    ("T_A", -1, 99.80201348642608),
    ("N_incline", 1, 279.13842511199397),
    ("T_incline", 1, -55.827685022398796),
    ("M_incline", 1, -9.766892599104049),
]


def test_rack_and_slotted_link_reactions_match_reference_001():
    run = mechdiff.load(SCENES / "rack_slotted_link_dynamics.toml").run()
    for column, sign, want in RACK_REACTIONS:
        got = sign * run.si(column)[0]
        # The reference solves the same linear system in 30-digit arithmetic; the Rust test
        # of this scene measured ≤ 1e-14 relative. 1e-9 leaves room for other libms.
        assert abs(got - want) <= 1e-9 * abs(want), (column, got, want)
    assert run.units["Fx_B"] == "N"


def test_simple_harmonic_cam_table_matches_reference_002():
    cam = mechdiff.Cam.load(SCENES / "cams" / "reference_002_simple_harmonic.toml")
    table = cam.svaj()
    assert table.units["s"] == "mm" and table.units["s''"] == "mm/rad^2"
    assert table.units["theta"] == "deg"
    for x, y, y1, y2 in SHM_TABLE:
        (i,) = np.flatnonzero(np.abs(table["theta"] - x) < 1e-9)
        # Printed to 17 digits from the closed form; dual numbers through the law agree to
        # rounding: 1e-12 mm on values up to 80 mm.
        assert abs(table["s"][i] - y) < 1e-12, x
        assert abs(table["s'"][i] - y1) < 1e-12, x
        assert abs(table["s''"][i] - y2) < 1e-12, x
    # The law has no jump anywhere: one row per angle, none marked with a side.
    assert set(table.side) == {""}


def test_cam_svaj_is_the_closed_form_of_the_harmonic_law_at_random_angles():
    cam = mechdiff.Cam.load(SCENES / "cams" / "reference_002_simple_harmonic.toml")
    x = np.random.default_rng(27).uniform(0.0, 2 * np.pi, 1000)
    got = cam.svaj_at(x)  # SI: m, m/rad, m/rad², m/rad³
    want = np.stack([0.04 - 0.04 * np.cos(x), 0.04 * np.sin(x), 0.04 * np.cos(x), -0.04 * np.sin(x)], axis=-1)
    # Exact derivatives of the same law: rounding of a few operations on 0.04 m, 1e-15 m
    # (2.5e-14 of the amplitude) with room to spare.
    assert got.shape == (1000, 4)
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-15)
    summary = cam.summary
    assert summary["units"]["length"] == "mm" and summary["fundamental_law_met"] is True


def test_rotor_balance_matches_the_closed_form_of_the_polygons():
    rotor = mechdiff.Rotor.load(SCENES / "rotor_balancing.toml")
    # scenes/rotor_balancing.toml: 0.5 kg at 150 mm, 0°/120°/240°, planes 300/0/−200 mm;
    # corrections in the planes at −400 and 400 mm, at 100 mm.
    angles = np.radians([0.0, 120.0, 240.0])
    u = 0.5 * 0.150 * np.stack([np.cos(angles), np.sin(angles)], axis=-1)  # kg m
    z = np.array([0.300, 0.0, -0.200])
    left, right = -0.400, 0.400
    np.testing.assert_allclose(rotor.masses, u, rtol=0, atol=1e-15)
    # Static: −Σ U; the cranks at 120° spacing close their polygon, so it is zero to
    # rounding of three terms of 0.075 kg m (1e-15 kg m).
    np.testing.assert_allclose(rotor.static_correction, -u.sum(axis=0), rtol=0, atol=1e-15)
    assert np.hypot(*rotor.static_correction) < 1e-15
    # Two planes: ΣU + U_L + U_R = 0 and ΣU(z − z_L) + U_R(z_R − z_L) = 0.
    u_right = -(u * (z - left)[:, None]).sum(axis=0) / (right - left)
    u_left = -(u * (z - right)[:, None]).sum(axis=0) / (left - right)
    # Answers of about 0.03 kg m from a handful of operations: 1e-15 kg m.
    np.testing.assert_allclose(rotor.two_plane, [u_left, u_right], rtol=0, atol=1e-15)
    table = rotor.table()
    masses = np.asarray(table["mass [kg]"])[np.asarray(table["row"]) == "two_plane"]
    # m = |m r| / r at the correction radius of 0.1 m (the table in the scene's mm).
    np.testing.assert_allclose(masses, np.hypot(*np.array([u_left, u_right]).T) / 0.1, rtol=1e-12)
    # The couple polygon's gap: Σ U z (kg m²).
    np.testing.assert_allclose(rotor.resultant[1], (u * z[:, None]).sum(axis=0), rtol=0, atol=1e-15)


def test_whitworth_crank_counterweight_is_the_least_squares_closed_form():
    run = mechdiff.load(SCENES / "whitworth_balancing.toml").run()
    (weight,) = run.counterweights
    assert weight.link == "crank" and run.balancing
    # m r = m · 0.1 m (the scene's radius): the two attributes are one answer.
    assert abs(weight.mass_radius - weight.mass * 0.1) <= 1e-12 * weight.mass_radius
    # The counterweight U = m (centre − A0) at the sketch (φ = 0) turns with the crank and
    # adds m ω² ρ(φ) = ω² R(φ) U to the shaking force (α = 0). Least squares over the turn
    # of F₀(φ) + ω² R(φ) U (R orthogonal): U = −Σ R(φ)ᵀ F₀(φ) / (N ω²), F₀ the run's
    # shaking force without it.
    u = weight.mass * (weight.center - np.array([0.0, 0.400]))
    phi = np.radians(run["phi"])
    fx, fy = run.si("SumF_x"), run.si("SumF_y")
    omega = 100 * 2 * np.pi / 60
    back = np.stack([np.cos(phi) * fx + np.sin(phi) * fy, -np.sin(phi) * fx + np.cos(phi) * fy])
    want = -back.sum(axis=1) / (len(phi) * omega**2)
    # Sums of 72 forces computed to about 1e-13 relative: 1e-10 of |U|.
    assert np.hypot(*(u - want)) <= 1e-10 * np.hypot(*want), (u, want)

"""Formula derivatives, generated code and the accuracy report through the Python API,
against hand derivatives and the extended-precision reference."""

import numpy as np
import pytest

import mechdiff
from mechdiff import errors
from conftest import SCENES


def by_hand(phi, l):
    """ψ = atan2(l sin φ, 1 − l cos φ) and ψ′, ψ″, ψ‴ derived by hand: with D = 1 − 2l cos φ
    + l², ψ′ = l (cos φ − l)/D, ψ″ = −l (1 − l²) sin φ / D², ψ‴ = −l (1 − l²)(cos φ D
    − 4 l sin² φ)/D³."""
    s, c = np.sin(phi), np.cos(phi)
    d = 1 - 2 * l * c + l * l
    k = l * (1 - l * l)
    return np.stack([
        np.arctan2(l * s, 1 - l * c),
        l * (c - l) / d,
        -k * s / d**2,
        -k * (c * d - 4 * l * s * s) / d**3,
    ])


def test_derive_matches_the_hand_derivatives_at_random_points_to_1e_13():
    d = mechdiff.derive("atan2(l*sin(phi), 1-l*cos(phi))", wrt="phi", order=3)
    assert d.parameters == ["phi", "l"] and len(d.expressions) == 4
    rng = np.random.default_rng(27)
    phi = rng.uniform(-np.pi, np.pi, 2000)
    l = rng.uniform(0.1, 0.6, 2000)  # D ≥ (1 − l)² ≥ 0.16: well conditioned
    got = d(phi=phi, l=l)
    want = by_hand(phi, l)
    assert got.shape == (4, 2000)
    for k in range(4):
        # 1e-13 of the order's largest magnitude over the sample (pointwise relative error
        # is undefined where a derivative crosses zero): two exact formulas in f64 differ by
        # rounding, a few ε times the terms' size.
        scale = np.max(np.abs(want[k]))
        assert np.max(np.abs(got[k] - want[k])) <= 1e-13 * scale, k
    # Scalars and arrays broadcast: one l for every φ.
    np.testing.assert_array_equal(d(phi=phi[:5], l=0.375)[:, 2], d(phi=phi[2], l=0.375))


def test_derive_refuses_bad_formulas_and_points_with_what_to_do():
    with pytest.raises(errors.FormulaError) as caught:
        mechdiff.derive("sin(phi", wrt="phi")
    assert caught.value.kind == "Codegen" and caught.value.file == "mechdiff.derive"
    d = mechdiff.derive("sin(x)/x", wrt="x", order=1)
    with pytest.raises(errors.FormulaError, match="at point 1"):
        d(x=np.array([1.0, 0.0]))  # 0/0: an error naming the point, never a NaN
    with pytest.raises(errors.ArgumentError, match="missing: l"):
        mechdiff.derive("l*phi", wrt="phi")(phi=1.0)


def test_codegen_of_a_scene_is_the_rust_module_of_its_outputs():
    scene = mechdiff.load(SCENES / "norton_four_bar.toml")
    text = mechdiff.codegen(scene)
    assert text == mechdiff.codegen(SCENES / "norton_four_bar.toml")
    assert "pub fn pose(phi: f64)" in text and '"psi"' in text


def test_accuracy_report_is_a_table_whose_exact_methods_are_exact():
    frame = mechdiff.accuracy(SCENES / "four_bar.toml", repeats=1, positions=12, frame=False)
    assert list(frame)[:4] == ["method", "kind", "step", "order"]
    assert {"max_value", "max_d1", "max_d2", "max_d3", "digits_lost", "time_median_s"} <= set(frame)
    exact = frame["kind"] == "exact"
    assert exact.sum() >= 2
    # Against the double-double reference, the exact methods' scaled error of value, ′, ″
    # and ‴ is at most 1e-14 (the bound of tests/accuracy_scenes.rs for this scene; measured
    # 1.4e-15), 1e4 below the best central difference.
    for order in ("max_value", "max_d1", "max_d2", "max_d3"):
        assert np.nanmax(frame[order][exact]) <= 1e-14, order
    differences = frame["kind"] == "difference"
    assert np.nanmin(frame["max_d1"][differences]) > 1e-13
    pd = pytest.importorskip("pandas")
    table = mechdiff.accuracy(SCENES / "four_bar.toml", repeats=1, positions=12)
    assert isinstance(table, pd.DataFrame) and list(table.columns) == list(frame)

"""A tolerance Monte Carlo of the Norton four-bar on a 2-worker LocalCluster: the same as
the serial study bit for bit, the same as one plain run of all variants to 1e-12, and its
spread as the exact sensitivities predict."""

import numpy as np
import pytest

import mechdiff
import mechdiff.study as study

TOLERANCES = {"a": 5e-4, "b": 5e-4, "c": 5e-4, "d": 5e-4}  # ± m
SAMPLES = 4_096  # 4 chunks of 1024 (a debug build in CI: ~3 ms a variant)


@pytest.fixture(scope="module")
def norton(norton_path):
    return mechdiff.load(norton_path)


@pytest.fixture(scope="module")
def serial(norton):
    return study.monte_carlo(norton, TOLERANCES, SAMPLES, chunk=1024, seed=7, client="serial")


def test_the_serial_study_equals_one_run_of_all_variants_to_1e_12(norton, serial):
    names = list(TOLERANCES)
    half = np.array([TOLERANCES[n] for n in names])
    values = np.array([norton.parameters[n] for n in names]) + study.draw(7, 0, SAMPLES, half) * half
    everything = norton.run_variants(dict(zip(names, values.T)), columns=serial.columns)
    assert not everything.failures and serial.failed == 0 and serial.samples == SAMPLES
    for k, column in enumerate(serial.columns):
        y = everything.values[:, :, k]
        scale = np.max(np.abs(y))
        # Sums of 4·10³ terms in another order: rounding of 1e-16 × 10⁴ at most, relative.
        assert np.max(np.abs(serial.mean[column] - y.mean(axis=0))) <= 1e-12 * scale
        np.testing.assert_array_equal(serial.low[column], y.min(axis=0))
        np.testing.assert_array_equal(serial.high[column], y.max(axis=0))
        # Standard deviations about 1e-4 of the values: 1e-9 relative to the spread.
        spread = y.std(axis=0, ddof=1)
        assert np.max(np.abs(serial.std[column] - spread)) <= 1e-9 * np.max(spread)


def test_the_spread_of_psi_is_what_the_exact_sensitivities_predict(norton, serial):
    # To first order ψ − ψ₀ = Σ ∂ψ/∂pᵢ δᵢ with δᵢ uniform on ±tᵢ: σ² = Σ (∂ψ/∂pᵢ tᵢ)² / 3.
    sens = norton.sensitivity(of="psi", wrt=list(TOLERANCES))
    predicted = np.sqrt(
        sum((sens[f"d(psi)/d({p})"] * t) ** 2 for p, t in TOLERANCES.items()) / 3
    )
    # The sample σ of n = 4096 draws is within 1/√(2n) ≈ 1.1 % of the true one (1σ; the
    # seed is fixed); the second-order remainder is O(t) = 1e-3 relative. 5 % is 4.5
    # standard errors.
    relative = np.abs(serial.std["psi"] - predicted) / predicted
    assert np.max(relative) < 0.05, relative
    # The uniform box bounds the deviation by the first-order worst case (plus 1 %).
    worst = sum(np.abs(sens[f"d(psi)/d({p})"]) * t for p, t in TOLERANCES.items())
    assert np.all(serial.max_deviation["psi"] <= 1.01 * worst)


def test_a_study_on_a_2_worker_local_cluster_equals_the_serial_one_bit_for_bit(norton, serial):
    pytest.importorskip("distributed")
    cluster = study.monte_carlo(norton, TOLERANCES, SAMPLES, chunk=1024, seed=7, workers=2)
    assert cluster.chunks == 4 and cluster.failed == 0
    for what in ("mean", "std", "low", "high", "max_deviation"):
        for column in serial.columns:
            np.testing.assert_array_equal(
                getattr(cluster, what)[column], getattr(serial, what)[column], err_msg=what
            )
    # Two worker processes ran the chunks (each reports its peak memory).
    assert len(cluster.peak_rss) == 2


def test_failed_variants_are_counted_with_their_reasons(norton):
    # The loop closes over the sweep (φ from 0° to 100°) iff L_max − c ≤ b ≤ L_min + c,
    # L(φ) = |A O4| growing with φ: b in [1.656, 2.22] m. Drawn from 1.85 ± 1.2 m, a
    # fraction 1 − 0.564/2.4 = 0.765 of the variants cannot run.
    a, c, d = 0.86, 0.86, 2.22
    length = lambda phi: np.hypot(d - a * np.cos(phi), a * np.sin(phi))  # noqa: E731
    lo, hi = length(np.radians(100)) - c, length(0.0) + c
    samples = 2048
    mc = study.monte_carlo(norton, {"b": 1.2}, samples, chunk=1024, client="serial", columns=["psi"])
    expected = 1 - (hi - lo) / 2.4
    # Binomial: σ = √(p(1−p)/n) ≈ 0.0094; five σ.
    assert abs(mc.failed / samples - expected) < 5 * np.sqrt(expected * (1 - expected) / samples)
    assert len(mc.failures) == study.KEPT_FAILURES
    for index, kind, message, moved in mc.failures:
        # Every failure is outside the interval (to the loop's closure tolerance, 1e-9 m).
        assert moved["b"] < lo + 1e-9 or moved["b"] > hi - 1e-9, (index, moved, message)
        assert "norton_four_bar.toml" in message and kind
    # The mean is of the variants that ran: within the values sampled.
    assert np.all(mc.low["psi"] <= mc.mean["psi"]) and np.all(mc.mean["psi"] <= mc.high["psi"])

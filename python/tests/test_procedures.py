"""The GJB 2426A procedures on numpy arrays: known answers, and the CLI's JSON on the same file."""

import numpy as np
import pytest

import inertest
from conftest import cli_error, cli_json


def test_scale_factor_of_an_exact_line():
    # Static runs at 1.0 either side; F = 5 * rate + 1 exactly: F_r = 1 (eq. 2), so after eq. (3)
    # K = 5 (eq. 5), F0 = 0 (eq. 6) and no nonlinearity or asymmetry (eqs. 8-11).
    rates = np.array([0, 0, 1, 2, 5, 10, -1, -2, -5, -10, 0, 0], dtype=float)
    outputs = np.where(rates == 0, 1.0, 5.0 * rates + 1.0)
    result = inertest.scale_factor(rates, outputs, output_unit="pulse/s")
    assert result.scale_factor.value == pytest.approx(5.0, rel=1e-14)
    assert result.scale_factor.unit == "pulse/s/(deg/s)"
    assert result.zero_offset.value == pytest.approx(0.0, abs=1e-12)
    assert result.nonlinearity.value == pytest.approx(0.0, abs=1e-9)
    assert result.asymmetry.value == pytest.approx(0.0, abs=1e-9)
    assert result.nonlinearity.unit == "ppm"
    assert len(result.nonlinearity_curve) == 8
    assert result.warnings  # 4 rates each way, fewer than the 11 of 5.8.1.3


def test_scale_factor_equals_the_cli_on_the_example(source_dir):
    path = source_dir / "examples" / "scale_factor" / "points.csv"
    table = inertest.read_text_table(str(path), columns=["rate", "output"], header=True)
    result = inertest.scale_factor(table["rate"], table["output"], output_unit="pulse/s", source=table.source)
    assert result.to_dict() == cli_json("scale-factor", path, "--output-unit", "pulse/s")
    assert result.report().startswith("Scale factor (GJB 2426A-2004 5.8.1-5.8.3)")


def test_scale_factor_error_is_the_cli_message(tmp_path):
    path = tmp_path / "points.csv"
    path.write_text("rate,output\n0,1\n1,2\n2,3\n-1,0\n-2,-1\n")
    table = inertest.read_text_table(str(path), columns=["rate", "output"], header=True)
    with pytest.raises(ValueError) as raised:
        inertest.scale_factor(table["rate"], table["output"], source=table.source)
    assert str(raised.value) == cli_error("scale-factor", path)


def test_arrays_of_unequal_length_are_an_error():
    with pytest.raises(inertest.Error, match="equal lengths"):
        inertest.scale_factor([0.0, 1.0], [0.0])
    with pytest.raises(inertest.Error, match="one-dimensional"):
        inertest.scale_factor(np.zeros((2, 2)), np.zeros((2, 2)))


def test_bias_of_a_constant_record():
    # B0 = F / K (eq. 19): a constant output of 0.01 per sample with K = 1 output per deg/s is 36 deg/h,
    # and a constant record has no bias stability (eq. 20).
    output = np.full(4000, 0.01)
    result = inertest.bias(output, sample_rate_hz=10.0, scale_factor=1.0, smoothing_s=[1.0, 10.0])
    assert result.bias.value == pytest.approx(36.0, rel=1e-12)
    assert result.bias.unit == "deg/h"
    assert [entry.value for entry in result.bias_stability] == pytest.approx([0.0, 0.0], abs=1e-9)

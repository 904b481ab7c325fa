"""Centrifuge drift calibration (the centrifuge paper, inertest.CITATIONS["centrifuge"]): the CLI's JSON on Table 3, and a
synthetic record whose coefficients are known because the first-order model made it."""

import numpy as np
import pytest

import inertest
from conftest import cli_error, cli_json


def test_calibration_equals_the_cli_on_table_3(source_dir):
    path = source_dir / "data" / "centrifuge" / "table3_harmonics.csv"
    record = inertest.read_centrifuge_record(str(path))
    assert record.kind == "harmonics"
    result = inertest.calibrate_drift_coefficients(record.runs(), latitude_deg=45.75, radius_m=1.0)
    assert result.to_dict() == cli_json("centrifuge", path, "--latitude", "45.75", "--radius", "1")
    assert set(result.coefficients.keys()) == set(inertest.DRIFT_TERMS)
    estimated = inertest.calibrate_drift_coefficients(record.runs(), latitude_deg=45.75, estimate_errors=True)
    assert estimated.to_dict() == cli_json("centrifuge", path, "--latitude", "45.75", "--estimate-errors")


def test_calibration_recovers_the_coefficients_of_model_samples():
    truth = [0.5, 0.2, -0.1, 0.05, 0.01, -0.02, 0.003, 0.004, -0.005, 0.006]
    gamma = np.arange(64) * (2 * np.pi / 64)
    runs = []
    for accel_g in (10.0, 20.0):
        omega = np.sqrt(accel_g * 9.80665 / 1.5)
        for beta_deg in (0.0, 90.0, 180.0, 270.0):
            beta = np.radians(beta_deg)
            output = inertest.centrifuge_model_output(truth, omega, beta, gamma, radius_m=1.5, latitude_deg=45.75)
            runs.append(inertest.CentrifugeRun.from_samples(accel_g, beta, gamma, output))
    assert runs[0].harmonic_fit.method == "dft"
    result = inertest.calibrate_drift_coefficients(runs, latitude_deg=45.75, radius_m=1.5)
    values = [result.coefficients[name].value for name in inertest.DRIFT_TERMS]
    np.testing.assert_allclose(values, truth, rtol=1e-7, atol=1e-9)


def test_platform_angles_that_differ_between_g_levels_are_judged_by_the_rank(tmp_path):
    # 20 g without beta = 270 deg: the design keeps full rank, so the runs are accepted.
    full = tmp_path / "full.csv"
    full.write_text(
        "accel_g,beta_deg,k0,k1c,k1s,k2c,k2s\n"
        "10,0,1,0,0,0,0\n10,90,1,0,0,0,0\n10,180,1,0,0,0,0\n10,270,1,0,0,0,0\n"
        "20,0,1,0,0,0,0\n20,90,1,0,0,0,0\n20,180,1,0,0,0,0\n"
    )
    result = inertest.calibrate_drift_coefficients(inertest.read_centrifuge_record(str(full)).runs(), latitude_deg=45.0)
    assert len(result.runs) == 7
    # 20 g at beta = 0 alone beside 10 g at 0 and 90 deg: the rank check refuses, as the CLI does.
    deficient = tmp_path / "deficient.csv"
    deficient.write_text("accel_g,beta_deg,k0,k1c,k1s,k2c,k2s\n10,0,1,0,0,0,0\n10,90,1,0,0,0,0\n20,0,1,0,0,0,0\n")
    record = inertest.read_centrifuge_record(str(deficient))
    with pytest.raises(ValueError) as raised:
        inertest.calibrate_drift_coefficients(record.runs(), latitude_deg=45.0)
    assert "cannot identify" in str(raised.value)
    # The CLI's message is the same, after the file it names.
    assert cli_error("centrifuge", deficient, "--latitude", "45") == f"{deficient}: {raised.value}"


def test_latitude_is_required_while_compensating():
    run = inertest.CentrifugeRun(10.0, 0.0, [1.0, 0.0, 0.0, 0.0, 0.0])
    with pytest.raises(inertest.Error, match="latitude_deg is required"):
        inertest.calibrate_drift_coefficients([run])


def test_model_output_refuses_inputs_that_are_not_finite():
    """A NaN coefficient or rate made every output NaN, silently."""
    gamma = np.linspace(0.0, 6.0, 10)
    coefficients = [0.0] * len(inertest.DRIFT_TERMS)
    with pytest.raises(inertest.Error, match="omega_rad_s must be a finite number"):
        inertest.centrifuge_model_output(coefficients, float("nan"), 0.0, gamma)
    coefficients[0] = float("nan")
    with pytest.raises(inertest.Error, match=f"coefficients: {inertest.DRIFT_TERMS[0]} is not a finite number"):
        inertest.centrifuge_model_output(coefficients, 1.0, 0.0, gamma)

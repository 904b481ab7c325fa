"""Misalignment separation (the misalignment paper, inertest.CITATIONS["misalignment"]): the CLI's JSON on
the paper's tables, and errors."""

import numpy as np
import pytest

import inertest
from conftest import cli_error, cli_json


def test_gyro_misalignment_equals_the_cli_on_table_1(source_dir):
    path = source_dir / "data" / "misalignment" / "gyro_table1.csv"
    rows = inertest.read_gyro_misalignment_positions(str(path))
    result = inertest.gyro_misalignment(**rows, scale_factor=-2.9222, output_unit="V")
    expected = cli_json("misalignment", "gyro", path, "--scale-factor", "-2.9222", "--output-unit", "V")
    assert result.to_dict() == expected
    assert result.misalignment.unit == "arcsec"


def test_positions_in_radians_are_refused(source_dir):
    """Read as degrees they gave gamma = 20 820 arcsec with no word."""
    path = source_dir / "data" / "misalignment" / "gyro_table1.csv"
    rows = inertest.read_gyro_misalignment_positions(str(path))
    rows["alpha_deg"] = np.radians(rows["alpha_deg"])
    rows["beta_deg"] = np.radians(rows["beta_deg"])
    with pytest.raises(inertest.Error, match="alpha_deg 3.14159.*radians"):
        inertest.gyro_misalignment(**rows, scale_factor=-2.9222)
    beta = np.radians([0.0, 90.0, 180.0, 270.0])
    with pytest.raises(inertest.Error, match="beta_deg 1.5707.*radians"):
        inertest.accelerometer_misalignment(beta, np.array([-1.8e-3, 4e-4, 1.9e-3, -3e-4]), scale_factor=1.3)


def test_papers_are_cited_by_title_not_by_file_name():
    assert "《惯性元件的失准角分离技术研究》" in inertest.CITATIONS["misalignment"]
    assert "Harbin Institute of Technology" in inertest.CITATIONS["misalignment"]
    assert "counter-rotating platform" in inertest.CITATIONS["centrifuge"]
    docs = [inertest.gyro_misalignment.__doc__, inertest.GyroMisalignmentResult.__doc__,
            inertest.calibrate_drift_coefficients.__doc__, inertest.DriftCalibrationResult.__doc__]
    for doc in docs:
        assert "000_" not in doc and "paper 001" not in doc and "seed" not in doc


def test_accelerometer_misalignment_equals_the_cli_on_table_2(source_dir):
    path = source_dir / "data" / "misalignment" / "accelerometer_table2.csv"
    rows = inertest.read_accelerometer_misalignment_positions(str(path))
    result = inertest.accelerometer_misalignment(**rows, scale_factor=1.299)
    assert result.to_dict() == cli_json("misalignment", "accelerometer", path, "--scale-factor", "1.299")


def test_accelerometer_misalignment_of_known_angles():
    # V = V0 + kI (dz2 sin b - dy2 cos b) with dy2 = 20", dz2 = -10": the closed forms and the fit agree.
    arcsec = np.pi / 180 / 3600
    beta = np.array([0.0, 90.0, 180.0, 270.0])
    k_i = 1.3
    output = 0.2 + k_i * (-10 * arcsec * np.sin(np.radians(beta)) - 20 * arcsec * np.cos(np.radians(beta)))
    result = inertest.accelerometer_misalignment(beta, output, scale_factor=k_i)
    assert result.delta_theta_y2.value == pytest.approx(20.0, rel=1e-9)
    assert result.delta_theta_z2.value == pytest.approx(-10.0, rel=1e-9)
    dy2, dz2 = inertest.four_position_misalignment(*output, k_i)
    assert (dy2 / arcsec, dz2 / arcsec) == pytest.approx((20.0, -10.0), rel=1e-9)


def test_gyro_misalignment_error_is_the_cli_message(tmp_path):
    path = tmp_path / "positions.csv"
    path.write_text("alpha_deg,beta_deg,rate_dps,output\n0,0,10,1\n0,0,-10,2\n0,0,0,3\n")
    rows = inertest.read_gyro_misalignment_positions(str(path))
    with pytest.raises(ValueError) as raised:
        inertest.gyro_misalignment(**rows, scale_factor=1.0)
    assert str(raised.value) == cli_error("misalignment", "gyro", path, "--scale-factor", "1")
    assert raised.value.line == 4


def test_whole_revolution_mean_reads_the_arrays_in_place():
    angle = np.arange(0.0, 725.0, 5.0)  # two whole turns and a bit
    output = 1.0 + np.sin(np.radians(angle))
    mean = inertest.whole_revolution_mean_by_angle(angle, output)
    assert mean.revolutions == 2
    assert mean.samples_used == 144
    assert mean.mean == pytest.approx(1.0, abs=1e-12)


def test_runs_and_lines_must_be_whole_numbers():
    """numpy's cast took run 1.5 for 1, a NaN run for -2**63 and a line -1 for 2**64 - 1, silently."""
    beta = np.arange(0.0, 360.0, 45.0)
    output = np.cos(np.radians(beta))
    for run, message in [(np.full(8, 1.5), r"run: value 1 \(1.5\) is not a whole number"),
                         (np.array([1.0] * 7 + [np.nan]), r"run\[7\] \(nan\) is not a finite number")]:
        with pytest.raises(inertest.Error, match=message):
            inertest.accelerometer_misalignment(beta, output, scale_factor=1.0, run=run)
    with pytest.raises(inertest.Error, match=r"line: value 1 \(-1\) is not a whole number of at least 0"):
        inertest.accelerometer_misalignment(beta, output, scale_factor=1.0, line=np.full(8, -1))
    whole = inertest.accelerometer_misalignment(beta, output, scale_factor=1.0, run=np.ones(8, dtype=np.int64))
    assert whole.to_dict() == inertest.accelerometer_misalignment(beta, output, scale_factor=1.0).to_dict()


def test_closed_forms_refuse_an_output_that_is_not_finite():
    """A NaN output gave a NaN angle."""
    with pytest.raises(inertest.Error, match="the output at 0 deg is not a finite number"):
        inertest.four_position_misalignment(float("nan"), 2.0, 3.0, 4.0, 1.0)
    with pytest.raises(inertest.Error, match="an output at position 3 is not a finite number"):
        inertest.five_position_misalignment([1, 2, float("inf"), 4, 5], [1, 2, 3, 4, 5], 1.0, 10.0)


def test_gyro_records_of_pulse_counts_are_read_per_second(tmp_path):
    # One whole revolution at +-20 deg/s, 50 Hz: counts per interval are the rates / 50.
    listing = "alpha_deg,beta_deg,rate_dps,file\n"
    for index, rate in enumerate((20.0, -20.0)):
        times = np.arange(1000) * 0.02
        record = tmp_path / f"r{index}.csv"
        record.write_text("time_s,output\n" + "".join(f"{t!r},{(100.0 * rate + 0.3) / 50.0!r}\n" for t in times))
        listing += f"0,0,{rate},{record.name}\n"
    (tmp_path / "listing.csv").write_text(listing)
    counts = inertest.read_gyro_misalignment_records(tmp_path / "listing.csv")
    rates = inertest.read_gyro_misalignment_records(tmp_path / "listing.csv", pulse_counts=True)
    assert rates["output"] == pytest.approx([2000.3, -1999.7], rel=1e-12)
    assert rates["output"] == pytest.approx(counts["output"] * 50.0, rel=1e-12)

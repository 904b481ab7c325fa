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
    assert result.report().startswith("Scale factor (GJB 2426A-2004 5.8.1-5.8.3")


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
    # and a constant record (a stuck channel) measures no bias stability (eq. 20): its rows are not
    # measured, with the reason.
    output = np.full(4000, 0.01)
    result = inertest.bias(output, sample_rate_hz=10.0, scale_factor=1.0, smoothing_s=[1.0, 10.0])
    assert result.bias.value == pytest.approx(36.0, rel=1e-12)
    assert result.bias.unit == "deg/h"
    assert [entry.value for entry in result.bias_stability] == [None, None]
    assert all("stuck channel" in entry.reason for entry in result.bias_stability)


def test_bias_takes_a_scale_factor_or_a_record_in_deg_h_as_the_cli_does():
    """Both at once ran and ignored K (the CLI refuses them); neither was not refused either."""
    output = np.full(100, 0.01)
    with pytest.raises(inertest.Error, match="the scale factor K and records in deg/h .* exclude each other"):
        inertest.bias(output, sample_rate_hz=10.0, scale_factor=10.0, input_in_deg_h=True)
    with pytest.raises(inertest.Error, match="missing the scale factor K"):
        inertest.bias(output, sample_rate_hz=10.0)
    assert inertest.bias(output, sample_rate_hz=10.0, input_in_deg_h=True).bias.value == pytest.approx(0.01)


def test_bias_output_unit_must_be_a_unit_as_on_the_cli():
    with pytest.raises(inertest.Error, match="unknown unit 'banana'"):
        inertest.bias(np.full(10, 0.01), sample_rate_hz=1.0, scale_factor=1.0, output_unit="banana")


def test_bias_removes_the_earth_rate_only_when_asked_as_the_cli_does(tmp_path):
    """A latitude alone removed the Earth rate here and nothing on the command line (10.8 deg/h apart)."""
    output = np.full(100, 0.01)
    for alone in ({"latitude_deg": 45.75}, {"heading_deg": 90.0}, {"elevation_deg": 10.0}):
        with pytest.raises(inertest.Error, match="are used only with remove_earth_rate=True"):
            inertest.bias(output, sample_rate_hz=10.0, input_in_deg_h=True, **alone)
    removed = inertest.bias(output, sample_rate_hz=10.0, input_in_deg_h=True, remove_earth_rate=True,
                            latitude_deg=45.75)
    # IRA north, horizontal: the Earth rate's north component, 15.041 deg/h cos(latitude).
    assert removed.earth_rate_removed.value == pytest.approx(15.041067 * np.cos(np.radians(45.75)), rel=1e-6)
    assert removed.bias.value == pytest.approx(0.01 - removed.earth_rate_removed.value, rel=1e-12)
    record = tmp_path / "rest.txt"
    record.write_text("\n".join(["0.01"] * 100) + "\n")
    assert removed.to_dict() == cli_json("bias", record, "--rate", "10", "--input-deg-h", "--remove-earth-rate",
                                         "--latitude", "45.75")
    with pytest.raises(inertest.Error, match="latitude"):
        inertest.bias(output, sample_rate_hz=10.0, input_in_deg_h=True, remove_earth_rate=True)


def test_bandwidth_of_a_first_order_lag_with_delay_equals_the_cli(source_dir):
    # G = 1/sqrt(1 + (w T)^2), P = -atan(w T) - w Td: the fit returns T and Td exactly (eqs. 37-46).
    bandwidth_hz, delay_s = 300.0, 2e-4
    t = 1.0 / (2 * np.pi * bandwidth_hz)
    f = np.logspace(0, np.log10(500.0), 12)
    w = 2 * np.pi * f
    gain = 1.0 / np.sqrt(1.0 + (w * t) ** 2)
    phase = np.degrees(-np.arctan(w * t) - w * delay_s)
    result = inertest.bandwidth_and_delay(f, gain, phase)
    assert result.bandwidth.value == pytest.approx(bandwidth_hz, rel=1e-9)
    assert result.delay.value == pytest.approx(delay_s, rel=1e-7)
    assert result.bandwidth.unit == "Hz" and result.delay.unit == "s"
    path = source_dir / "examples" / "bandwidth" / "gains.csv"
    table = inertest.read_text_table(str(path), columns=["freq_hz", "gain", "phase_deg"], header=True)
    from_arrays = inertest.bandwidth_and_delay(table["freq_hz"], table["gain"], table["phase_deg"])
    assert from_arrays.to_dict() == cli_json("bandwidth", path)


def test_repeatabilities_by_hand():
    # Eq. (21): biases 1, 2, 3 deg/h have sample standard deviation 1.
    assert inertest.bias_repeatability(np.array([1.0, 2.0, 3.0])).bias_repeatability.value == pytest.approx(1.0)
    # Eq. (12): scale factors 99, 100, 101 x2 have standard deviation sqrt(0.8) around 100 -> ppm.
    factors = np.array([99.0, 100.0, 101.0, 99.0, 100.0, 101.0])
    kr = inertest.scale_factor_repeatability(factors).scale_factor_repeatability
    assert kr.value == pytest.approx(np.std(factors, ddof=1) / 100.0 * 1e6, rel=1e-12)
    assert kr.unit == "ppm"
    with pytest.raises(ValueError):
        inertest.scale_factor_repeatability(factors[:3])  # fewer than the 6 runs of 5.8.4.3


def test_bias_temperature_sensitivity_by_hand():
    # Eq. (22): room run 20 degC at 1.0 deg/h; 1.5 deg/h at 70 degC -> 0.01, 0.8 deg/h at -20 degC -> 0.005.
    result = inertest.bias_temperature_sensitivity(np.array([20.0, 70.0, -20.0]), np.array([1.0, 1.5, 0.8]))
    assert result.bias_temperature_sensitivity.value == pytest.approx(0.01, rel=1e-12)


def test_maximum_input_rate_of_a_saturating_gyro():
    # F = 10 * rate exactly up to 10 deg/s, 1 % short at 20 deg/s: Kn = 0 for |rate| <= 10 and far
    # above 100 ppm with 20, so the maximum input rate is 10 deg/s (GJB 2426A-2004 5.9). The result
    # is written by the procedure's spec: the same keys and report as the CLI.
    rates = np.array([0, 1, -1, 2, -2, 5, -5, 10, -10, 20, -20, 0], dtype=float)
    outputs = np.where(np.abs(rates) == 20, 0.99, 1.0) * 10.0 * rates
    result = inertest.maximum_input_rate(rates, outputs, nonlinearity_limit_ppm=100)
    assert result.maximum_input_rate.value == 10.0
    assert result.maximum_input_rate.unit == "deg/s"
    assert [r["meets_requirement"] for r in result.ranges] == [True, True, True, False]
    assert result.report().startswith("Maximum input rate (GJB 2426A-2004 5.9")


def test_input_axis_misalignment_two_positions_by_hand():
    # delta = (F+ - F-) / (2 K rate): 2e-4 and -1e-4 rad -> alpha = asin(sqrt(5e-8)) in arcsec.
    k, rate = 1000.0, 10.0
    positive = np.array([2e-4 * 2 * k * rate / 2, -1e-4 * 2 * k * rate / 2])
    result = inertest.input_axis_misalignment(positive, -positive, scale_factor=k, rate=rate)
    expected = np.degrees(np.arcsin(np.sqrt(5e-8))) * 3600
    assert result.misalignment.value == pytest.approx(expected, rel=1e-9)
    assert result.misalignment.unit == "arcsec"


def test_maximum_input_rate_of_a_saturating_gyro():
    # Linear up to 100 deg/s, then 2 % compressed at 200 deg/s: a 100 ppm requirement holds to 100.
    magnitudes = np.array([1, 2, 5, 10, 20, 50, 100, 200], dtype=float)
    outputs = np.where(magnitudes > 150, 0.98 * magnitudes, magnitudes)
    rate = np.concatenate([[0.0], magnitudes, -magnitudes, [0.0]])
    output = np.concatenate([[0.0], outputs, -outputs, [0.0]])
    result = inertest.maximum_input_rate(rate, output, nonlinearity_limit_ppm=100.0)
    assert result.maximum_input_rate.value == pytest.approx(100.0)


def test_threshold_criterion_denominator_keyword_matches_the_cli(tmp_path):
    # 60 % of the expected output at 2 deg/h (K = 3600 output units per deg/s, so 1 deg/h gives 1):
    # passes the default criterion relative to the expected output (IEEE Std 952-1997), fails GJB
    # eq. (15) as printed, relative to the measured output (|2 - 1.2| / 1.2 = 0.67).
    rate = np.array([0, 4, 2, 1, -4, -2, -1], dtype=float)
    output = np.array([0, 4, 1.2, 0.45, -4, -2, -0.45])
    expected = inertest.threshold_rate_table(rate, output, scale_factor=3600.0, rate_unit="deg/h")
    assert expected.criterion_denominator == "expected"
    assert expected.threshold.value == pytest.approx(2.0, rel=1e-14)
    measured = inertest.threshold_rate_table(
        rate, output, scale_factor=3600.0, rate_unit="deg/h", criterion_denominator="measured"
    )
    assert measured.criterion_denominator == "measured"
    assert measured.threshold.value == pytest.approx(4.0, rel=1e-14)
    path = tmp_path / "th.csv"
    path.write_text("rate,output\n" + "".join(f"{r},{f}\n" for r, f in zip(rate, output)))
    cli = cli_json("threshold", path, "--method", "1", "--scale-factor", "3600", "--rate-unit", "deg/h",
                   "--criterion-denominator", "measured")
    assert measured.to_dict() == cli
    with pytest.raises(inertest.Error, match="neither 'expected'"):
        inertest.threshold_rate_table(rate, output, scale_factor=3600.0, criterion_denominator="theoretical")


def test_a_nan_in_an_array_is_an_error_naming_its_place():
    # As a record's NaN is: never a result of None, nor a misleading complaint about the fit.
    output = np.array([1.0, np.nan, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0])
    with pytest.raises(inertest.Error, match=r"output\[1\] \(nan\) is not a finite number"):
        inertest.bias(output, sample_rate_hz=1.0, scale_factor=1.0)
    with pytest.raises(inertest.Error, match=r"scale_factors\[2\] \(inf\) is not a finite number"):
        inertest.scale_factor_repeatability(np.array([1000.0, 1001.0, np.inf, 1000.0, 1000.0, 1000.0]))
    # With the source named, as the procedure's own errors are.
    with pytest.raises(inertest.Error, match=r"^run7.csv: output\[1\] \(nan\)") as raised:
        inertest.bias(output, sample_rate_hz=1.0, scale_factor=1.0, source="run7.csv")
    assert raised.value.file == "run7.csv"
    with pytest.raises(inertest.Error, match=r"^points.csv: output has 3 values but rate has 2"):
        inertest.scale_factor(np.array([0.0, 1.0]), np.array([0.0, 1.0, 2.0]), source="points.csv")


@pytest.mark.parametrize("values, dtype", [
    (np.arange(10) + 5j, "complex128"),                 # numpy's cast dropped the imaginary part
    (np.arange(10).astype("datetime64[s]"), "datetime64"),  # read as rates: a bias of 358200 deg/h
    (np.arange(10).astype("timedelta64[ms]"), "timedelta64"),
    (np.array([str(v) for v in range(10)]), "<U1"),
    (np.arange(10) > 4, "bool"),                         # a mask read as rates of 0 and 1
])
def test_an_array_of_no_real_numbers_is_refused_naming_its_dtype(values, dtype):
    with pytest.raises(TypeError, match="an array of real numbers is expected, not of dtype " + dtype):
        inertest.bias(values, sample_rate_hz=1.0, scale_factor=1.0)


def test_integers_and_single_precision_convert_to_the_same_figures():
    rate = np.array([0, 0, 1, 2, -1, -2, 0, 0])
    output = np.array([1, 1, 11, 21, -9, -19, 1, 1])
    expected = inertest.scale_factor(rate.astype(float), output.astype(float)).to_dict()
    assert inertest.scale_factor(rate.astype(np.int16), output.astype(np.float32)).to_dict() == expected
    assert inertest.scale_factor(list(rate), list(output)).to_dict() == expected


def test_pulse_counts_per_sample_interval_are_rates_as_on_the_cli():
    """output_unit pulse: a counter read once an interval, counts x the sample rate (pulse/s); a
    table's mean outputs are taken per second and named so; records in deg/h are no counts."""
    rates = np.linspace(0.99, 1.01, 4000)  # pulse/s, K = 1 per deg/s
    of_rates = inertest.bias(rates, sample_rate_hz=10.0, scale_factor=1.0, output_unit="pulse/s", smoothing_s=[1.0])
    of_counts = inertest.bias(rates / 10.0, sample_rate_hz=10.0, scale_factor=1.0, output_unit="pulse", smoothing_s=[1.0])
    assert of_counts.bias.value == pytest.approx(of_rates.bias.value, rel=1e-12)
    assert of_counts.bias_stability[0].value == pytest.approx(of_rates.bias_stability[0].value, rel=1e-9)
    points = np.array([0, 1, -1, 2, -2, 0], dtype=float)
    per_second = inertest.scale_factor(points, 5.0 * points + 0.1, output_unit="pulse/s").to_dict()
    assert inertest.scale_factor(points, 5.0 * points + 0.1, output_unit="pulse").to_dict() == per_second
    assert per_second["scale_factor"]["unit"] == "pulse/s/(deg/s)"
    with pytest.raises(inertest.Error, match="records in deg/h .* are no pulse counts"):
        inertest.bias(rates, sample_rate_hz=10.0, input_in_deg_h=True, output_unit="pulse")

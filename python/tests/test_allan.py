"""Allan analysis on simulated noise whose terms are known, and the CLI's JSON on the same file."""

import numpy as np
import pytest

import inertest
from conftest import cli_json

SAMPLE_RATE_HZ = 100.0
# N = 0.02 deg/sqrt(h) in rad/sqrt(s): the simulator's SI unit (IEEE Std 952-1997 C.1).
ANGLE_RANDOM_WALK = 0.02 * (np.pi / 180) / 60


def white_noise_deg_h(seed=7, samples=200_000):
    rate = inertest.gyro_noise(samples, SAMPLE_RATE_HZ, angle_random_walk=ANGLE_RANDOM_WALK, seed=seed)
    return inertest.convert(rate, "rad/s", "deg/h")


def test_angle_random_walk_of_white_noise_is_found():
    result = inertest.allan_variance(white_noise_deg_h(), sample_rate_hz=SAMPLE_RATE_HZ)
    arw = result.noise.angle_random_walk
    assert arw.unit == "deg/sqrt(h)"
    # Within 4 of its own 1-sigma uncertainties of the truth the simulator was made with.
    assert abs(arw.value - 0.02) < 4 * arw.uncertainty
    oadev = result.oadev
    assert isinstance(result.tau, np.ndarray) and isinstance(oadev.values, np.ndarray)
    # White rate noise: sigma(tau) = N / sqrt(tau), N in deg/sqrt(h) -> deg/h at tau in s: N * 60 / sqrt(tau).
    expected = 0.02 * 60 / np.sqrt(result.tau[:8])
    np.testing.assert_array_less(np.abs(oadev.values[:8] / expected - 1), 4 / np.sqrt(2 * oadev.edf[:8]))  # 4 sigma: sd(sigma)/sigma = 1/sqrt(2 edf)


def test_allan_equals_the_cli_on_the_same_file(tmp_path):
    path = tmp_path / "rate.csv"
    samples = white_noise_deg_h(seed=3, samples=20_000)
    np.savetxt(path, samples, fmt="%.17g", header="rate", comments="")
    from_file = inertest.allan_variance_of_file(str(path), sample_rate_hz=SAMPLE_RATE_HZ, taus="decade")
    assert from_file.to_dict() == cli_json("allan", path, "--rate", SAMPLE_RATE_HZ, "--taus", "decade")
    in_memory = inertest.allan_variance(samples, sample_rate_hz=SAMPLE_RATE_HZ, taus="decade")
    np.testing.assert_allclose(in_memory.adev.values, from_file.adev.values, rtol=1e-12)
    np.testing.assert_array_equal(inertest.read_rate_record(str(path)), samples)


def test_taus_as_a_list_or_an_array_of_seconds():
    # As allantools takes them: taus in s, each a whole number of sample intervals (0.01 s here).
    samples = white_noise_deg_h(seed=5, samples=5_000)
    as_text = inertest.allan_variance(samples, sample_rate_hz=SAMPLE_RATE_HZ, taus="0.01,0.1,1,10")
    for taus in ([0.01, 0.1, 1.0, 10.0], np.array([0.01, 0.1, 1.0, 10.0]), np.array([10.0, 1.0, 0.1, 0.01])):
        result = inertest.allan_variance(samples, sample_rate_hz=SAMPLE_RATE_HZ, taus=taus)
        np.testing.assert_array_equal(result.averaging_factor, [1, 10, 100, 1000])
        np.testing.assert_allclose(result.tau, [0.01, 0.1, 1.0, 10.0], rtol=1e-15)
        np.testing.assert_array_equal(result.oadev.values, as_text.oadev.values)
    with pytest.raises(inertest.Error, match="whole number of sample intervals"):
        inertest.allan_variance(samples, sample_rate_hz=SAMPLE_RATE_HZ, taus=[0.015])
    with pytest.raises(inertest.Error, match="positive"):
        inertest.allan_variance(samples, sample_rate_hz=SAMPLE_RATE_HZ, taus=np.array([-1.0]))


def test_bad_allan_options_are_errors():
    with pytest.raises(inertest.Error, match="estimator"):
        inertest.allan_variance(np.ones(100), sample_rate_hz=1.0, estimators="bogus")
    imu = np.random.default_rng(3).normal(0.0, 1.0, (2000, 3))
    # A second channel of a name would hide the first one's result.
    with pytest.raises(inertest.Error, match="channel 'a' is asked for twice"):
        inertest.allan_variance(imu, sample_rate_hz=100.0, channels=["a", "a", "b"])
    with pytest.raises(inertest.Error, match="the channels are the columns"):
        inertest.allan_variance(np.ascontiguousarray(imu.T), sample_rate_hz=100.0)


def test_the_spec_function_takes_numpy_numbers_and_names_a_bad_type(tmp_path):
    path = tmp_path / "rate.csv"
    np.savetxt(path, white_noise_deg_h(seed=9, samples=5_000), fmt="%.17g", header="rate", comments="")
    plain = inertest.allan(file=str(path), sample_rate_hz=100.0, threads=2, taus="decade")
    from_numpy = inertest.allan(file=str(path), sample_rate_hz=np.int64(100), threads=np.int64(2), taus="decade")
    assert from_numpy.to_dict() == plain.to_dict()
    with pytest.raises(inertest.Error, match="columns must be a list of strings"):
        inertest.allan(file=str(path), sample_rate_hz=100.0, columns=[2, 3])
    with pytest.raises(inertest.Error, match="fit_range must be a list of numbers"):
        inertest.allan(file=str(path), sample_rate_hz=100.0, fit_range=["a", "b"])
    with pytest.raises(inertest.Error, match="sample_rate_hz must be a number"):
        inertest.allan(file=str(path), sample_rate_hz=True)


def test_gyro_noise_is_reproducible_by_seed():
    first = inertest.gyro_noise(1000, 10.0, angle_random_walk=1e-4, seed=5)
    np.testing.assert_array_equal(first, inertest.gyro_noise(1000, 10.0, angle_random_walk=1e-4, seed=5))
    assert not np.array_equal(first, inertest.gyro_noise(1000, 10.0, angle_random_walk=1e-4, seed=6))
    assert not first.flags.owndata  # owns the simulator's vector through a capsule


def test_fit_range_keyword_and_unidentified_terms():
    samples = white_noise_deg_h(seed=11, samples=50_000)
    result = inertest.allan_variance(samples, sample_rate_hz=SAMPLE_RATE_HZ, estimators="oadev", fit_range=(0.02, 50.0))
    fit = result.noise.fit
    assert fit.fit_range.chosen_by == "user"
    assert fit.fit_range.tau_min_s == pytest.approx(0.02)
    assert fit.verdict in ("consistent", "inconsistent")
    # White noise only: the fit holds B at zero, reported as not identified with an upper bound.
    # A Figure, as the stubs say (it was a Record): value NaN, so that float() never reads it as 0.
    bias_instability = result.noise.bias_instability
    assert isinstance(bias_instability, inertest.Figure)
    assert bias_instability.identified is False
    assert bias_instability.upper_bound > 0.0
    assert np.isnan(bias_instability.value)
    assert bias_instability.unit == "deg/h"
    # Q is left free but within 2 sigma of zero: still a Figure, with its significance and bound.
    quantization = result.noise.quantization
    assert isinstance(quantization, inertest.Figure)
    assert quantization.significant is False
    assert quantization.upper_bound > float(quantization) > 0.0
    assert quantization.to("deg/h*s").unit == "deg/h*s"
    assert not hasattr(result.noise.angle_random_walk, "significant")
    # The same fit from the curve alone, with the record's size and interval.
    direct = inertest.fit_noise_terms(result.tau, result.oadev.values**2, result.oadev.edf, fit_range=(0.02, 50.0),
                                      sample_count=50_000, sample_interval_s=1 / SAMPLE_RATE_HZ)
    assert direct.angle_random_walk.value == pytest.approx(result.noise.angle_random_walk.value, rel=1e-12)
    with pytest.raises(inertest.Error, match="fit range"):
        inertest.allan_variance(samples, sample_rate_hz=SAMPLE_RATE_HZ, fit_range=(5.0, 1.0))


def test_noise_type_per_tau_and_estimator():
    # White rate noise is white FM (alpha = 0); where 30 averages or more remain the lag-1
    # autocorrelation is the method, and with 300 or more (r1 scattering by 0.06) it names white FM
    # for every estimator.
    result = inertest.allan_variance(white_noise_deg_h(), sample_rate_hz=SAMPLE_RATE_HZ)
    assert isinstance(result.alpha, np.ndarray) and len(result.alpha) == len(result.tau)
    assert result.noise_type[0] == "white_fm" and result.alpha[0] == 0
    for name in ("adev", "oadev", "mdev", "hdev", "ohdev", "totdev"):
        curve = getattr(result, name)
        averages = result.sample_count // result.averaging_factor
        lag1 = [method == "lag1_autocorrelation" for method in curve.noise_identification]
        assert lag1 == list(averages >= 30)
        many = averages >= 300
        assert many.sum() >= 8
        assert all(curve.alpha[many] == 0) and all(np.array(curve.noise_type)[many] == "white_fm")


def test_a_two_dimensional_array_is_one_channel_per_column_as_the_cli_columns(tmp_path):
    """Channels in columns (issue 19): each channel's Record is the 1-D result of that column, the
    accelerometer's terms come with an acceleration unit, and the export is written as by --export."""
    rng = np.random.default_rng(11)
    samples = 20_000
    imu = np.column_stack([rng.normal(0.0, 1.0, samples), rng.normal(0.0, 0.01, samples)])
    export = tmp_path / "imu.yaml"
    both = inertest.allan_variance(imu, sample_rate_hz=SAMPLE_RATE_HZ, channels=["gx", "ax"],
                                   input_unit="gx=deg/s,ax=m/s^2", taus="decade", export=("kalibr", str(export)))
    assert isinstance(both, inertest.AllanChannelsResult)
    gx = inertest.allan_variance(np.ascontiguousarray(imu[:, 0]), sample_rate_hz=SAMPLE_RATE_HZ, input_unit="deg/s",
                                 taus="decade")
    assert both.to_dict()["channels"]["gx"] == gx.to_dict()
    ax = both.channels.ax.noise
    assert ax.velocity_random_walk.unit == "m/s/sqrt(h)"
    # White noise of 0.01 m/s^2 at 100 Hz: N = 0.01 / sqrt(100) m/s^2*sqrt(s) = 0.001 * 60 m/s/sqrt(h).
    assert abs(ax.velocity_random_walk.value - 0.06) < 4 * ax.velocity_random_walk.uncertainty
    text = export.read_text()
    assert "accelerometer_noise_density: " in text and "gyroscope_noise_density: " in text
    # The same file through the CLI, several columns in one pass.
    record = tmp_path / "imu.csv"
    np.savetxt(record, imu, delimiter=",", header="gx,ax", comments="", fmt="%.17g")
    from_cli = cli_json("allan", str(record), "--rate", "100", "--columns", "gx,ax", "--input-unit",
                        "gx=deg/s,ax=m/s^2", "--taus", "decade")
    from_file = inertest.allan_variance_of_file(str(record), sample_rate_hz=SAMPLE_RATE_HZ, columns=["gx", "ax"],
                                                input_unit="gx=deg/s,ax=m/s^2", taus="decade")
    assert from_file.to_dict() == from_cli
    # The PSD beside it: white noise of 1 deg/s at 100 Hz has N = 0.1 deg/sqrt(s) = 6 deg/sqrt(h) in both fits.
    spectral = inertest.allan_variance(imu, sample_rate_hz=SAMPLE_RATE_HZ, channels=["gx", "ax"],
                                       input_unit="gx=deg/s,ax=m/s^2", taus="decade", psd=("hann", 0))
    arw = spectral.channels.gx.psd.noise_terms.angle_random_walk
    assert arw.unit == "deg/sqrt(h)" and abs(arw.value - 6.0) < 4 * arw.uncertainty
    assert spectral.channels.ax.psd.noise_terms.velocity_random_walk.unit == "m/s/sqrt(h)"
    with pytest.raises(inertest.Error, match="channels names 1 channels but rate has 2 columns"):
        inertest.allan_variance(imu, sample_rate_hz=SAMPLE_RATE_HZ, channels=["gx"])


def test_an_array_in_any_layout_gives_the_same_channels_and_stays_as_it_was():
    """A Fortran-ordered array (pandas' to_numpy() of float columns) is read in place, a C-ordered or
    strided one copied once: the figures are the same, the caller's array is not written."""
    rng = np.random.default_rng(12)
    imu = np.column_stack([rng.normal(0.0, 1.0, 5_000), rng.normal(0.0, 0.5, 5_000), rng.normal(0.0, 2.0, 5_000)])
    fortran = np.asfortranarray(imu)
    kept = fortran.copy(order="F")
    every_other = np.repeat(imu, 2, axis=1)[:, ::2]  # neither C- nor Fortran-contiguous
    assert fortran.flags.f_contiguous and not every_other.flags.c_contiguous and not every_other.flags.f_contiguous
    results = [inertest.allan_variance(a, sample_rate_hz=SAMPLE_RATE_HZ, taus="octave").to_dict()["channels"]
               for a in (imu, fortran, every_other)]
    assert results[0] == results[1] == results[2]
    np.testing.assert_array_equal(fortran, kept)
    # One column of it, a strided 1-D view, is the same channel.
    column = inertest.allan_variance(imu[:, 1], sample_rate_hz=SAMPLE_RATE_HZ, taus="octave")
    assert column.to_dict() == results[0]["2"]


def test_the_noise_fit_needs_increasing_taus():
    """The same curve in reverse order was fitted to other figures (the range drops the shortest taus first)."""
    tau = np.array([0.1, 0.2, 0.4, 0.8, 1.6])
    variance = 1e-4 / tau
    edf = np.full(5, 50.0)
    inertest.fit_noise_terms(tau, variance, edf)
    with pytest.raises(inertest.Error, match=r"needs increasing taus \(point 2: 0.8 s after 1.6 s\)"):
        inertest.fit_noise_terms(tau[::-1], variance[::-1], edf[::-1])

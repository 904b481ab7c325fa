"""Records as labs save them (issue 21): .mat written by scipy.io (v5, v7 compressed) and HDF5
written by h5py, each with known values, read through the module and the CLI."""

import h5py
import numpy as np
import pytest
import scipy.io

import inertest
from conftest import cli_error, cli_json

RATE = 0.001 * np.arange(4000) - 2.0            # known values, exact in binary64 to the printed digits
GYRO = ((np.arange(4000) % 7) - 3).astype(np.float32) * 0.5


@pytest.fixture(params=[False, True], ids=["v5", "v7"])
def mat_file(tmp_path, request):
    path = tmp_path / "record.mat"
    scipy.io.savemat(path, {"rate": RATE.reshape(-1, 1), "imu": {"gyro_x": GYRO}}, do_compression=request.param)
    return path


@pytest.fixture
def hdf5_file(tmp_path):
    path = tmp_path / "record.h5"
    with h5py.File(path, "w") as f:
        gyro = f.create_dataset("imu/gyro_x", data=RATE, chunks=(512,), compression="gzip")
        gyro.attrs["units"] = "deg/h"
        gyro.attrs["sample_rate_hz"] = 100.0
    return path


def test_mat_variables_and_struct_fields(mat_file):
    np.testing.assert_array_equal(inertest.read_rate_record(str(mat_file), column="rate"), RATE)
    np.testing.assert_array_equal(inertest.read_rate_record(str(mat_file), column="imu.gyro_x"), GYRO)


def test_hdf5_dataset_by_path(hdf5_file):
    np.testing.assert_array_equal(inertest.read_rate_record(str(hdf5_file), column="/imu/gyro_x"), RATE)
    np.testing.assert_array_equal(inertest.read_rate_record(str(hdf5_file), format="hdf5"), RATE)


def test_allan_of_hdf5_equals_allan_of_the_same_samples(hdf5_file, tmp_path):
    raw = tmp_path / "record.f64"
    RATE.astype("<f8").tofile(raw)
    from_hdf5 = inertest.allan_variance_of_file(str(hdf5_file), sample_rate_hz=100.0)
    from_raw = inertest.allan_variance_of_file(str(raw), sample_rate_hz=100.0, format="f64")
    np.testing.assert_array_equal(from_hdf5.oadev.values, from_raw.oadev.values)
    with pytest.raises(inertest.Error, match="the sample rate given, 50 Hz, contradicts the 100 Hz stored"):
        inertest.allan_variance_of_file(str(hdf5_file), sample_rate_hz=50.0)


def test_cli_uses_the_stored_rate_and_lists_channels(hdf5_file, mat_file, tmp_path):
    raw = tmp_path / "same.f64"
    RATE.astype("<f8").tofile(raw)
    from_hdf5 = cli_json("allan", hdf5_file)
    assert from_hdf5["sample_rate_hz"] == 100.0
    assert from_hdf5 == cli_json("allan", raw, "--format", "f64", "--rate", "100")
    listing = cli_json("inspect", hdf5_file)
    assert listing["format"] == "hdf5"
    (gyro,) = listing["columns"]
    assert (gyro["name"], gyro["type"], gyro["count"], gyro["unit"], gyro["sample_rate_hz"]) == (
        "imu/gyro_x", "f64", 4000, "deg/h", 100.0)
    assert gyro["min"] == RATE.min() and gyro["max"] == RATE.max()
    names = [c["name"] for c in cli_json("inspect", mat_file)["columns"]]
    assert names == ["rate", "imu.gyro_x"]
    assert "no channel 'imu.gyro_y' in the record (channels: rate, imu.gyro_x)" in cli_error(
        "allan", mat_file, "--column", "imu.gyro_y", "--rate", "100")
    assert "the sample rate given, 10 Hz, contradicts the 100 Hz stored for channel 'imu/gyro_x'" in cli_error(
        "allan", hdf5_file, "--rate", "10")


def test_a_stored_rate_that_is_no_rate_is_said_with_the_file_and_channel(tmp_path):
    """A sample_rate_hz attribute of 0 or NaN names the file and the channel, and a given rate stands."""
    for stored in (0.0, float("nan")):
        path = tmp_path / "zero.h5"
        with h5py.File(path, "w") as f:
            f.create_dataset("g", data=RATE).attrs["sample_rate_hz"] = stored
        message = cli_error("allan", path)
        assert message.startswith(f"{path}: channel 'g' stores the sample rate {stored:g} Hz, which is no rate: give it")
        assert cli_json("allan", path, "--rate", "100")["sample_rate_hz"] == 100.0


def test_several_channels_at_their_stored_rates_and_units(tmp_path):
    """--columns on an HDF5 record: each channel at its stored rate and in its stored unit."""
    path = tmp_path / "imu.h5"
    with h5py.File(path, "w") as f:
        for name, unit, rate in (("gx", "deg/s", 100.0), ("ax", "m/s^2", 50.0)):
            d = f.create_dataset("imu/" + name, data=RATE)
            d.attrs["units"], d.attrs["sample_rate_hz"] = unit, rate
    channels = cli_json("allan", path, "--columns", "imu/gx,imu/ax")["channels"]
    assert (channels["imu/gx"]["input_unit"], channels["imu/gx"]["sample_rate_hz"]) == ("deg/s", 100.0)
    assert (channels["imu/ax"]["input_unit"], channels["imu/ax"]["sample_rate_hz"]) == ("m/s^2", 50.0)
    assert "velocity_random_walk" in channels["imu/ax"]["noise"]

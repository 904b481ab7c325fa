"""Writes the small records of data/lab_formats/ with the libraries labs use, so that inertest's
readers are checked against files written by another implementation:

    /usr/bin/python3 data/lab_formats/make_records.py data/lab_formats

record_v5.mat   scipy.io.savemat, MAT level 5 (v5), uncompressed
record_v7.mat   scipy.io.savemat(do_compression=True), v7 (zlib-compressed variables)
record.h5       h5py: a chunked, gzip-compressed dataset with `units` and `sample_rate_hz`
rate_deg_s.h5   h5py: one gyro channel logged in deg/s, as IMUs log (`units` deg/s, 100 Hz)

The values follow from the formulas below (known_values), which the tests repeat.
"""

import sys

import h5py
import numpy as np
import scipy.io


def known_values():
    i = np.arange(1000)
    rate = 0.001 * i - 0.25                               # f64
    gyro_x = ((i % 7) - 3).astype(np.float32) * 0.5       # f32
    temperature = (i % 100).astype(np.int16)              # i16
    return rate, gyro_x, temperature


def main(out):
    rate, gyro_x, temperature = known_values()
    variables = {
        "rate": rate.reshape(-1, 1),                       # a column vector, as MATLAB saves one
        "imu": {"gyro_x": gyro_x, "temperature": temperature},
        "fs": 200.0,
        "matrix": np.arange(6.0).reshape(2, 3),
    }
    scipy.io.savemat(f"{out}/record_v5.mat", variables, format="5")
    scipy.io.savemat(f"{out}/record_v7.mat", variables, format="5", do_compression=True)
    with h5py.File(f"{out}/record.h5", "w") as f:
        gyro = f.create_dataset("imu/gyro_x", data=np.repeat(rate, 10), chunks=(1000,), compression="gzip")
        gyro.attrs["units"] = "deg/h"
        gyro.attrs["sample_rate_hz"] = 200.0
        f.create_dataset("imu/temperature", data=np.repeat(temperature, 10))
        f.create_dataset("matrix", data=np.arange(6.0).reshape(2, 3))
    with h5py.File(f"{out}/rate_deg_s.h5", "w") as f:
        gyro = f.create_dataset("gyro_z", data=rate)
        gyro.attrs["units"] = "deg/s"
        gyro.attrs["sample_rate_hz"] = 100.0


if __name__ == "__main__":
    main(sys.argv[1])

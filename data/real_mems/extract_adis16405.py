#!/usr/bin/python3
"""Extracts one gyro axis of SMAC-Group/imudata's data/adis_16405_imu1.rda as int16 counts.

Usage: extract_adis16405.py ADIS_16405_IMU1.RDA OUTPUT.I16

The .rda is an xz-compressed R save (format RDX2, XDR) holding one object: a REAL matrix of
1e6 rows x 6 columns (Gyro. X/Y/Z in deg/s, Accel. X/Y/Z), stored column by column as big-endian
doubles. The gyro samples are whole multiples of the ADIS16405 LSB, 0.05 deg/s; the output is the
chosen column divided by 0.05, as little-endian int16 (checked exact).
"""
import lzma
import sys

import numpy as np

QUANTUM_DEG_PER_S = 0.05
COLUMN = 2  # Gyro. Z


def main(source, output):
    raw = lzma.open(source).read()
    assert raw[:5] == b"RDX2\n" and raw[5:7] == b"X\n", "not an XDR R save"
    # Header: version (3 ints), then the pairlist of saved objects: pairlist flags, the tag
    # (symbol flags, CHARSXP flags, name length, name), then the value's flags and length.
    name_length = int.from_bytes(raw[31:35], "big")
    offset = 35 + name_length
    flags = int.from_bytes(raw[offset:offset + 4], "big")
    assert flags & 0xFF == 14, "not a REAL vector"  # REALSXP
    length = int.from_bytes(raw[offset + 4:offset + 8], "big")
    assert length == 6_000_000, length
    values = np.frombuffer(raw[offset + 8:offset + 8 + 8 * length], dtype=">f8").reshape(6, length // 6)
    counts = np.round(values[COLUMN] / QUANTUM_DEG_PER_S)
    assert np.all(np.abs(values[COLUMN] - counts * QUANTUM_DEG_PER_S) < 1e-9), "not on the 0.05 deg/s grid"
    assert counts.min() >= -32768 and counts.max() <= 32767
    counts.astype("<i2").tofile(output)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])

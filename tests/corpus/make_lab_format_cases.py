"""Writes the bad-input corpus entries of the lab record formats (issue 21), from files written by
h5py and scipy.io and from LabVIEW's Digital_Input.tdms (data/tdms/):

    /usr/bin/python3 tests/corpus/make_lab_format_cases.py

channels.h5           h5py: imu/gyro_x (f64, 100 samples, units deg/h, sample_rate_hz 200), imu/temperature (i16)
truncated.h5          channels.h5 cut after 1000 bytes
corrupt_variable.mat  scipy.io.savemat(do_compression=True) with bytes of the compressed variable overwritten
truncated.tdms        Digital_Input.tdms cut inside its second segment
bad_lead_in.tdms      Digital_Input.tdms with the second segment's lead-in "TDSm" overwritten by "TDSx"
and the fuzz seed fuzz/corpus/tdms_record/first_segment.tdms: Digital_Input.tdms's first segment.
"""

import os
import struct

import h5py
import numpy as np
import scipy.io

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def main():
    channels = os.path.join(HERE, "channels.h5")
    with h5py.File(channels, "w") as f:
        gyro = f.create_dataset("imu/gyro_x", data=0.01 * np.arange(100) - 0.5)
        gyro.attrs["units"] = "deg/h"
        gyro.attrs["sample_rate_hz"] = 200.0
        f.create_dataset("imu/temperature", data=np.arange(100, dtype=np.int16))
    with open(channels, "rb") as f:
        hdf5 = f.read()
    with open(os.path.join(HERE, "truncated.h5"), "wb") as f:
        f.write(hdf5[:1000])

    corrupt = os.path.join(HERE, "corrupt_variable.mat")
    scipy.io.savemat(corrupt, {"rate": 0.01 * np.arange(500) - 0.5}, do_compression=True)
    with open(corrupt, "rb") as f:
        mat = bytearray(f.read())
    # 128-byte header, then the miCOMPRESSED tag (8 bytes) and the zlib stream: spoil its middle.
    middle = 136 + (len(mat) - 136) // 2
    mat[middle:middle + 16] = b"\xff" * 16
    with open(corrupt, "wb") as f:
        f.write(mat)

    with open(os.path.join(ROOT, "data", "tdms", "Digital_Input.tdms"), "rb") as f:
        tdms = f.read()
    (next_offset,) = struct.unpack_from("<Q", tdms, 12)
    second = 28 + next_offset
    with open(os.path.join(ROOT, "fuzz", "corpus", "tdms_record", "first_segment.tdms"), "wb") as f:
        f.write(tdms[:second])
    with open(os.path.join(HERE, "truncated.tdms"), "wb") as f:
        f.write(tdms[:second + 200])
    (second_next,) = struct.unpack_from("<Q", tdms, second + 12)
    third = second + 28 + second_next
    spoilt = bytearray(tdms[:third])
    spoilt[second:second + 4] = b"TDSx"
    with open(os.path.join(HERE, "bad_lead_in.tdms"), "wb") as f:
        f.write(spoilt)


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""A whole IMU in one pass (issue 19): `inertest allan FILE --columns gx,gy,gz,ax,ay,az` against the
same command on one channel of the same file, and against six one-channel runs (what a user without
--columns would do).

Writes a seven-column CSV record (time, three gyro and three accelerometer channels of white noise)
of --rows rows; each command runs --repeat times in a fresh process, the best wall time counts.
Target: six channels in at most 1.5x the time of one.
Run with Debian's Python: /usr/bin/python3 bench/imu_compare.py --inertest build/bin/inertest.
"""
import argparse
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import csv_compare  # noqa: E402

CHANNELS = ("gx", "gy", "gz", "ax", "ay", "az")
UNITS = "deg/s,ax=m/s^2,ay=m/s^2,az=m/s^2"


def write_record(path, rows):
    rng = np.random.default_rng(19)
    data = np.column_stack([np.arange(rows) * 0.01] + [rng.normal(0.0, 1.0, rows) for _ in CHANNELS])
    np.savetxt(path, data, fmt="%.6f", delimiter=",", header="time_s," + ",".join(CHANNELS), comments="")


def measure(inertest, rows, repeat, path):
    """Writes the record to `path` (left for the caller to delete). Returns ({case: best seconds},
    megabytes of the file)."""
    write_record(path, rows)
    common = [inertest, "allan", path, "--rate", "100", "--json"]
    six = csv_compare.best(common + ["--columns", ",".join(CHANNELS), "--input-unit", UNITS], repeat)[0]
    one = csv_compare.best(common + ["--column", "gx", "--input-unit", "deg/s"], repeat)[0]
    return {"six": six, "one": one}, os.path.getsize(path) / 1e6


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--inertest", default="build/bin/inertest")
    parser.add_argument("--rows", type=int, default=2_000_000)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        times, megabytes = measure(args.inertest, args.rows, args.repeat, os.path.join(scratch, "imu.csv"))
    print(f"{args.rows} rows, {megabytes:.0f} MB: six channels {times['six']:.3f} s, one {times['one']:.3f} s, "
          f"{times['six'] / times['one']:.2f}x (target <= 1.5x); six one-channel runs would take "
          f"{6 * times['one']:.3f} s")


if __name__ == "__main__":
    main()

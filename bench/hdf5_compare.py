#!/usr/bin/python3
"""Allan on an HDF5 dataset against the raw f64 path (issue 21): the same samples, written once as
a raw little-endian f64 record and once by h5py as a chunked dataset (1 Mi samples a chunk, with a
sample_rate_hz attribute), each analysed by `inertest allan` (all six estimators, octave taus) in
its own process, best of --runs; the peak resident memory of each child (wait4) beside the dataset's
size. Targets: HDF5 at most 1.3x the time of raw f64, its peak memory at most 1.5x the dataset.

Run alone: /usr/bin/python3 bench/hdf5_compare.py --build-dir build [--samples 100000000]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from allan_compare import best_of  # noqa: E402

WRITE_RECORDS = r"""
import sys, h5py, numpy as np
raw, hdf5, samples = sys.argv[1], sys.argv[2], int(sys.argv[3])
rng = np.random.default_rng(17)
block = 10_000_000
with open(raw, "wb") as out, h5py.File(hdf5, "w") as f:
    dataset = f.create_dataset("imu/rate", shape=(samples,), dtype="<f8", chunks=(1 << 20,))
    dataset.attrs["units"] = "deg/h"
    dataset.attrs["sample_rate_hz"] = 100.0
    for start in range(0, samples, block):
        values = rng.normal(10.0, 1.0, min(block, samples - start))
        values.astype("<f8").tofile(out)
        dataset[start:start + values.size] = values
"""


def measure(inertest, samples, runs, directory):
    """Writes both records under `directory` and times inertest on each; the files are removed.
    Returns a dict: dataset size (MB), (seconds, peak MB) of the raw and the HDF5 runs, and whether
    both gave the same JSON."""
    raw = os.path.join(directory, "record.f64")
    hdf5 = os.path.join(directory, "record.h5")
    try:
        subprocess.run([sys.executable, "-c", WRITE_RECORDS, raw, hdf5, str(samples)], check=True)
        t_raw, m_raw, out_raw = best_of(runs, [inertest, "allan", raw, "--rate", "100", "--format", "f64",
                                               "--taus", "octave", "--json"])
        t_hdf5, m_hdf5, out_hdf5 = best_of(runs, [inertest, "allan", hdf5, "--column", "imu/rate",
                                                  "--taus", "octave", "--json"])
    finally:
        for path in (raw, hdf5):
            if os.path.exists(path):
                os.remove(path)
    return {"size_mb": 8 * samples / 1e6, "raw": (t_raw, m_raw), "hdf5": (t_hdf5, m_hdf5),
            "same_result": json.loads(out_raw) == json.loads(out_hdf5)}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", default="build")
    parser.add_argument("--samples", type=int, default=10**8)
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        m = measure(os.path.join(args.build_dir, "bin", "inertest"), args.samples, args.runs, tmp)
    (t_raw, m_raw), (t_hdf5, m_hdf5) = m["raw"], m["hdf5"]
    print(f"{args.samples:.0e} f64 samples ({m['size_mb']:.0f} MB), best of {args.runs}; same result: {m['same_result']}")
    print(f"raw f64: {t_raw:.3f} s, peak RSS {m_raw:.0f} MB ({m_raw / m['size_mb']:.2f}x the dataset)")
    print(f"HDF5:    {t_hdf5:.3f} s, peak RSS {m_hdf5:.0f} MB ({m_hdf5 / m['size_mb']:.2f}x the dataset)")
    print(f"HDF5 / raw time: {t_hdf5 / t_raw:.2f}x (target <= 1.3x); peak / dataset {m_hdf5 / m['size_mb']:.2f}x "
          f"(target <= 1.5x)")


if __name__ == "__main__":
    main()

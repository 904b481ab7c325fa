#!/usr/bin/python3
"""`make bench`: one table of inertest against numpy, pandas and the allantools algorithm, all
measured in this run on this machine, with the machine's read bandwidth beside them.

Rows (each program in its own process, run --runs times back to back, the fastest kept: the
machine may be shared, so only ratios within the run mean anything):
  - OADEV at octave taus of a --samples f64 record (allan_compare.py): inertest against the
    allantools algorithm written in numpy (phase by cumsum, then one vectorised pass per tau);
  - all six estimators with bounds and the noise fit against the same algorithm's five (no TOTDEV
    there), and against inertest's own OADEV alone (the issue's bound: at most 2x);
  - CSV ingestion of --csv-rows rows (csv_compare.py): inertest inspect against pandas.read_csv
    and numpy.loadtxt; the row parser alone on the same bytes in memory against pandas.read_csv
    on them (the issue's bound: at least 1 GB/s on 2 cores); and the same record end to end to its
    OADEV: `inertest allan` against numpy.loadtxt + the allantools algorithm (at least 5x);
  - Allan on --hdf5-samples f64 samples (10^8) from an HDF5 dataset written by h5py against the
    same samples as raw f64 (hdf5_compare.py): time at most 1.3x, peak memory at most 1.5x the dataset;
  - a whole IMU (imu_compare.py): `allan --columns` on six channels of a --imu-rows CSV against one
    channel of the same file (the issue's bound: at most 1.5x);
  - with --huge: 10^9 f32 samples (4 GB, written to --huge-dir and deleted after), all six
    estimators, its time and peak resident memory;
  - inertest serve under load (the ServeLoad test of inertest_tests, when the tests are built): the
    second batch of 10 000 requests over 8 connections, its throughput and p99 latency, its errors
    and the resident size's growth between the batches.
The read bandwidth: one pass over 1 GiB in memory on 1 and 2 threads (memory_read_benchmark) and
one read(2) of the f64 record from the page cache. The GB/s column is the record's raw size over
inertest's time: how close the engine runs to those.
Run: /usr/bin/python3 bench/bench.py --build-dir build
"""
import argparse
import datetime
import json
import os
import platform
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import allan_compare  # noqa: E402
import csv_compare  # noqa: E402
import hdf5_compare  # noqa: E402
import imu_compare  # noqa: E402

WRITE_F32 = r"""
import sys, numpy as np
path, samples = sys.argv[1], int(sys.argv[2])
rng = np.random.default_rng(11)
with open(path, "wb") as out:
    for start in range(0, samples, 20_000_000):
        rng.normal(10.0, 1.0, min(20_000_000, samples - start)).astype("<f4").tofile(out)
"""


def memory_bandwidth(build_dir):
    """GB/s of one pass over 1 GiB on 1 and 2 threads, from the Google Benchmark program."""
    program = os.path.join(build_dir, "bin", "memory_read_benchmark")
    if not os.path.exists(program):
        program = os.path.join(build_dir, "bench", "memory_read_benchmark")
    out = subprocess.run([program, "--benchmark_format=json", "--benchmark_repetitions=3",
                          "--benchmark_report_aggregates_only=false"],
                         check=True, capture_output=True, text=True).stdout
    best = {}
    for b in json.loads(out)["benchmarks"]:
        if b.get("run_type") == "iteration":
            threads = b["name"].split("/")[1]
            best[threads] = max(best.get(threads, 0.0), b["bytes_per_second"] / 1e9)
    return best


def file_read_bandwidth(path, runs):
    """GB/s of reading the file with read(2) into one buffer (page cache), best of `runs`."""
    size = os.path.getsize(path)
    buffer = bytearray(8 << 20)
    view = memoryview(buffer)
    best = float("inf")
    for _ in range(runs):
        start = time.perf_counter()
        with open(path, "rb", buffering=0) as f:
            while f.readinto(view):
                pass
        best = min(best, time.perf_counter() - start)
    return size / best / 1e9


def machine():
    model = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    memory = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
    return f"{model}, {os.cpu_count()} cores, {memory:.0f} GiB"


def serve_load(build_dir):
    """The second batch of the serve load test (src/serve/server_load_test.cc: 10 000 requests over 8
    keep-alive connections on loopback): its seconds, requests/s, p99 ms, errors and the resident size's
    growth between the batches (MiB); None when the tests are not built (configure with
    -DINERTEST_BUILD_TESTS=ON, as make test does)."""
    tests = os.path.join(build_dir, "bin", "inertest_tests")
    if not os.path.exists(tests):
        return None
    run = subprocess.run([tests, "--gtest_filter=ServeLoad.*"], capture_output=True, text=True, check=False)
    batch = re.search(r"batch 2: .* in ([0-9.]+) s: ([0-9.]+) requests/s, .* p99 ([0-9.]+) ms, .*; (\d+) errors", run.stdout)
    growth = re.search(r"resident size ([-+0-9.]+) MiB", run.stdout)
    if run.returncode != 0 or not batch or not growth:
        return {"failed": run.stdout[-2000:]}
    return {"seconds": float(batch.group(1)), "rate": float(batch.group(2)), "p99_ms": float(batch.group(3)),
            "errors": int(batch.group(4)), "growth_mib": float(growth.group(1))}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", default="build")
    parser.add_argument("--samples", type=int, default=30_000_000, help="f64 samples of the Allan record")
    parser.add_argument("--csv-rows", type=int, default=5_000_000)
    parser.add_argument("--imu-rows", type=int, default=2_000_000, help="rows of the six-channel IMU CSV")
    parser.add_argument("--runs", type=int, default=3, help="runs of each program, fastest kept")
    parser.add_argument("--hdf5-samples", type=int, default=10**8,
                        help="f64 samples of the HDF5 record (written twice, HDF5 and raw, deleted after)")
    parser.add_argument("--huge", action="store_true", help="also 1e9 f32 samples (4 GB on disk, deleted after)")
    parser.add_argument("--huge-dir", default=None, help="where the 4 GB file goes (default: the temp dir)")
    parser.add_argument("--huge-samples", type=int, default=10**9, help="f32 samples of the --huge record")
    args = parser.parse_args()
    inertest = os.path.join(args.build_dir, "bin", "inertest")
    if not os.path.exists(inertest):
        sys.exit(f"{inertest} not found: build first (make bench builds it)")

    load_before = os.getloadavg()
    bandwidth = memory_bandwidth(args.build_dir)
    with tempfile.TemporaryDirectory() as tmp:
        record = os.path.join(tmp, "record.f64")
        allan = allan_compare.measure(inertest, args.samples, args.runs, record)
        file_bandwidth = file_read_bandwidth(record, args.runs)
        os.remove(record)
        csv_path = os.path.join(tmp, "record.csv")
        csv, csv_mb = csv_compare.measure(inertest, args.csv_rows, args.runs, True, csv_path)
        parser = csv_compare.parser_in_memory(inertest, csv_path, args.runs)
        hdf5 = hdf5_compare.measure(inertest, args.hdf5_samples, args.runs, tmp)
        imu, imu_mb = imu_compare.measure(inertest, args.imu_rows, args.runs, os.path.join(tmp, "imu.csv"))
    huge = None
    if args.huge:
        with tempfile.TemporaryDirectory(dir=args.huge_dir) as tmp:
            path = os.path.join(tmp, "huge.f32")
            subprocess.run([sys.executable, "-c", WRITE_F32, path, str(args.huge_samples)], check=True)
            try:
                seconds, peak_mb, _ = allan_compare.run_child(
                    [inertest, "allan", path, "--rate", "100", "--format", "f32", "--taus", "octave", "--json"])
            finally:
                os.remove(path)
            huge = (seconds, peak_mb)
    serve = serve_load(args.build_dir)
    load_after = os.getloadavg()

    size_mb = allan["size_mb"]
    rows = []  # (work, inertest s, reference, reference s, ratio text, target, inertest GB/s)
    t_oadev, t_all = allan["oadev"][0], allan["all"][0]
    record_text = f"{args.samples:.0e} f64 samples ({size_mb:.0f} MB), {allan['taus']} octave taus"
    rows.append((f"OADEV, {record_text}", t_oadev, "allantools algorithm (numpy)", allan["numpy_oadev"][0],
                 f"{allan['numpy_oadev'][0] / t_oadev:.1f}x faster", ">= 30x", size_mb / 1e3 / t_oadev))
    rows.append(("all six + bounds + fit, same record", t_all, "allantools algorithm, 5 (no TOTDEV)",
                 allan["numpy_five"][0], f"{allan['numpy_five'][0] / t_all:.1f}x faster", "", size_mb / 1e3 / t_all))
    rows.append(("all six + bounds + fit vs OADEV alone", t_all, "inertest, OADEV alone", t_oadev,
                 f"{t_all / t_oadev:.2f}x the time", "<= 2x", None))
    base = csv["inertest"][0]
    for reader in ("pandas.read_csv", "numpy.loadtxt"):
        rows.append((f"CSV ingestion, {args.csv_rows:.0e} rows ({csv_mb:.0f} MB)", base, reader, csv[reader][0],
                     f"{csv[reader][0] / base:.1f}x faster", "", csv_mb / 1e3 / base))
    rows.append(("row parser alone, the same CSV in memory", parser[0], "pandas.read_csv from memory", parser[1],
                 f"{parser[1] / parser[0]:.1f}x faster", ">= 1 GB/s", csv_mb / 1e3 / parser[0]))
    ours, theirs = (csv[name][0] for name in csv_compare.END_TO_END)
    rows.append((f"CSV {args.csv_rows:.0e} rows ({csv_mb:.0f} MB) to OADEV", ours, "numpy.loadtxt + allantools algorithm",
                 theirs, f"{theirs / ours:.1f}x faster", ">= 5x", csv_mb / 1e3 / ours))
    hdf5_text = f"{args.hdf5_samples:.0e} f64 ({hdf5['size_mb']:.0f} MB)"
    rows.append((f"all six + bounds + fit, {hdf5_text} from HDF5", hdf5["hdf5"][0], "inertest, the same as raw f64",
                 hdf5["raw"][0], f"{hdf5['hdf5'][0] / hdf5['raw'][0]:.2f}x the time", "<= 1.3x",
                 hdf5["size_mb"] / 1e3 / hdf5["hdf5"][0]))
    rows.append(("peak RSS of the same from HDF5", hdf5["hdf5"][0], f"the dataset, {hdf5['size_mb']:.0f} MB", None,
                 f"{hdf5['hdf5'][1] / hdf5['size_mb']:.2f}x the dataset", "<= 1.5x", None))
    rows.append((f"allan, 6 channels of a {args.imu_rows:.0e}-row CSV ({imu_mb:.0f} MB)", imu["six"],
                 "inertest, one channel of it", imu["one"], f"{imu['six'] / imu['one']:.2f}x the time", "<= 1.5x",
                 imu_mb / 1e3 / imu["six"]))
    if huge:
        huge_gb = 4 * args.huge_samples / 1e9
        rows.append((f"all six + bounds + fit, {args.huge_samples:.0e} f32 ({huge_gb:.2g} GB)", huge[0],
                     f"peak RSS {huge[1] / 1024:.1f} GiB", None, "", "within 24 GiB", huge_gb / huge[0]))

    if serve and "failed" not in serve:
        rows.append(("inertest serve: 10 000 requests over 8 connections", serve["seconds"],
                     f"{serve['errors']} errors, RSS {serve['growth_mib']:+.2f} MiB", None,
                     f"{serve['rate']:.0f} req/s, p99 {serve['p99_ms']:.1f} ms", "no error, flat", None))

    print(f"inertest bench, {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, {machine()}")
    print(f"load average {load_before[0]:.2f} before, {load_after[0]:.2f} after (a shared machine slows every column)")
    print(f"read bandwidth: memory {bandwidth.get('1', float('nan')):.1f} GB/s on 1 thread, "
          f"{bandwidth.get('2', float('nan')):.1f} GB/s on 2; file (page cache, read(2)) {file_bandwidth:.1f} GB/s")
    print(f"agreement with the allantools algorithm, max relative difference: OADEV {allan['worst_oadev']:.1e}, "
          f"ADEV..OHDEV {allan['worst_five']:.1e}; each program best of {args.runs}")
    print()
    header = ("work", "inertest s", "against", "its s", "ratio", "target", "inertest GB/s")
    widths = (48, 11, 37, 8, 18, 14, 14)
    print("| " + " | ".join(h.ljust(w) for h, w in zip(header, widths)) + " |")
    print("|" + "|".join("-" * (w + 2) for w in widths) + "|")
    for work, ours, against, theirs, ratio, target, gbps in rows:
        cells = (work, f"{ours:.3f}", against, "" if theirs is None else f"{theirs:.3f}", ratio, target,
                 "" if gbps is None else f"{gbps:.2f}")
        print("| " + " | ".join(c.ljust(w) for c, w in zip(cells, widths)) + " |")
    if serve is None:
        print("\ninertest serve's load test: not built (configure with -DINERTEST_BUILD_TESTS=ON, as make test does)")
    elif "failed" in serve:
        print("\ninertest serve's load test FAILED:\n" + serve["failed"])


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Text-record ingestion: inertest against pandas.read_csv and numpy.loadtxt on the same file.

Writes a two-column CSV record (time, output) of --rows rows, then times, in this run on this
machine, each reader turning it into numeric columns:
  - inertest: `inertest inspect FILE --json` (memory-mapped, fast_float; also computes per-column
    statistics, which only adds to its time);
  - pandas.read_csv (C engine) and numpy.loadtxt, as a user's script would read it;
and, end to end, the record to its OADEV at octave taus: `inertest allan` against numpy.loadtxt
followed by the allantools algorithm (allan_compare.py's numpy program).
Each is run --repeat times in a fresh process; the best wall time counts. Prints MB/s, peak RSS
and the ratios. Then the row parser alone (parser_in_memory): the same bytes already in memory,
inertest's text_table_benchmark against pandas.read_csv on an io.BytesIO, each best of --repeat.
Run with Debian's Python: /usr/bin/python3 bench/csv_compare.py.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import allan_compare  # noqa: E402


END_TO_END = ("inertest allan, OADEV", "numpy.loadtxt + OADEV")  # the record to its OADEV, not ingestion alone


def write_record(path, rows):
    rng = np.random.default_rng(7)
    data = np.column_stack([np.arange(rows) * 0.01, rng.normal(100.0, 0.5, rows)])
    np.savetxt(path, data, fmt="%.6f", delimiter=",", header="time_s,output", comments="")


def timed(command):
    """Runs command in a child process; returns (wall seconds, peak RSS in MiB)."""
    before = time.perf_counter()
    child = subprocess.Popen(command, stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(child.pid, 0)
    elapsed = time.perf_counter() - before
    if status != 0:
        sys.exit(f"failed: {' '.join(command)}")
    return elapsed, usage.ru_maxrss / 1024.0


def best(command, repeat):
    runs = [timed(command) for _ in range(repeat)]
    return min(r[0] for r in runs), max(r[1] for r in runs)


def measure(inertest, rows, repeat, with_loadtxt, path):
    """Writes the CSV record to `path` (left for the caller to delete) and times each reader on it.
    Returns ({reader: (best seconds, peak MiB)}, megabytes of the file)."""
    write_record(path, rows)
    megabytes = os.path.getsize(path) / 1e6
    python = sys.executable
    readers = {
        "inertest": [inertest, "inspect", path, "--json"],
        "pandas.read_csv": [python, "-c", f"import pandas; pandas.read_csv({path!r})"],
    }
    if with_loadtxt:
        readers["numpy.loadtxt"] = [python, "-c", f"import numpy; numpy.loadtxt({path!r}, delimiter=',', skiprows=1)"]
        # End to end, the record to its OADEV at octave taus: inertest allan against numpy.loadtxt
        # followed by the allantools algorithm (allan_compare.py).
        readers[END_TO_END[0]] = [inertest, "allan", path, "--rate", "100", "--column", "output",
                                  "--taus", "octave", "--estimators", "oadev", "--json"]
        readers[END_TO_END[1]] = [python, "-c", allan_compare.ALLANTOOLS, path, "100", "oadev"]
    return {name: best(command, repeat) for name, command in readers.items()}, megabytes


PANDAS_IN_MEMORY = r"""
import io, sys, time, pandas
data = open(sys.argv[1], "rb").read()
best = float("inf")
for _ in range(int(sys.argv[2])):
    start = time.perf_counter()
    pandas.read_csv(io.BytesIO(data))
    best = min(best, time.perf_counter() - start)
print(best)
"""


def parser_in_memory(inertest, path, repeat):
    """The row parser alone on the record at `path`, already in memory, columns allocated included:
    (inertest seconds, pandas.read_csv seconds), each the best of `repeat`. inertest's is the
    parse_record case of text_table_benchmark (built beside inertest by make bench), on 2 threads
    as inertest runs it; pandas' C parser runs on one."""
    program = os.path.join(os.path.dirname(inertest), "text_table_benchmark")
    out = subprocess.run([program, f"--record={path}", "--benchmark_filter=parse_record", "--benchmark_format=json",
                          f"--benchmark_repetitions={repeat}"], check=True, capture_output=True, text=True).stdout
    runs = [b for b in json.loads(out)["benchmarks"] if b.get("run_type") == "iteration"]
    ours = min(b["real_time"] for b in runs) / 1e3  # reported in ms
    theirs = float(subprocess.run([sys.executable, "-c", PANDAS_IN_MEMORY, path, str(repeat)], check=True,
                                  capture_output=True, text=True).stdout)
    return ours, theirs


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", default="build")
    parser.add_argument("--rows", type=int, default=10_000_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--skip-loadtxt", action="store_true", help="numpy.loadtxt is slow on large files")
    args = parser.parse_args()

    inertest = os.path.join(args.build_dir, "bin", "inertest")
    with tempfile.TemporaryDirectory() as scratch:
        path = os.path.join(scratch, "record.csv")
        results, megabytes = measure(inertest, args.rows, args.repeat, not args.skip_loadtxt, path)
        parser_ours, parser_pandas = parser_in_memory(inertest, path, args.repeat)

    print(f"CSV ingestion: {args.rows} rows x 2 columns, {megabytes:.0f} MB, best of {args.repeat}")
    print(f"{'reader':<18}{'time s':>10}{'MB/s':>10}{'peak MiB':>10}{'inertest faster':>17}")
    end_to_end = {name: results.pop(name) for name in END_TO_END if name in results}
    base_time = results["inertest"][0]
    for name, (seconds, peak) in results.items():
        print(f"{name:<18}{seconds:>10.3f}{megabytes / seconds:>10.0f}{peak:>10.0f}{seconds / base_time:>16.1f}x")
    if end_to_end:
        ours, theirs = (end_to_end[name][0] for name in END_TO_END)
        print(f"to OADEV at octave taus: {END_TO_END[0]} {ours:.3f} s, {END_TO_END[1]} {theirs:.3f} s, "
              f"{theirs / ours:.1f}x faster")
    print(f"row parser, in memory: inertest {parser_ours:.3f} s ({megabytes / 1e3 / parser_ours:.2f} GB/s), "
          f"pandas.read_csv {parser_pandas:.3f} s, {parser_pandas / parser_ours:.1f}x faster")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""inertest allan against the allantools algorithm on one 1e8-sample f64 record.

Writes a white + random-walk rate record (raw little-endian float64) to a temporary file, then
times, each in its own process with its peak resident memory (ru_maxrss of the child), each run
--runs times back to back (best time kept: the machine is shared):
  - inertest allan FILE --rate 100 --format f64 --taus octave --json --estimators oadev
  - the allantools algorithm for OADEV, written here: load the record, phase = cumsum(y) * tau0 with a
    leading 0, then for each octave m one vectorised numpy pass, as allantools.oadev does
    (allantools is not installed; this is its calc_adev_phase with stride 1);
  - inertest with all six estimators, bounds and the noise fit;
  - the allantools algorithm for ADEV, OADEV, MDEV, HDEV and OHDEV, one numpy pass per tau per
    estimator (calc_adev_phase, calc_hdev_phase with stride m or 1, and the cumsum form of mdev).
    TOTDEV is left out there (allantools builds the reflected record per tau).
It checks that the values agree and prints times, peak memory and the ratios.
Run: /usr/bin/python3 bench/allan_compare.py [--samples N] [--build-dir build]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

WRITE_RECORD = r"""
import sys, numpy as np
path, samples = sys.argv[1], int(sys.argv[2])
rng = np.random.default_rng(20240601)
walk = 0.0
with open(path, "wb") as out:
    for start in range(0, samples, 10_000_000):
        count = min(10_000_000, samples - start)
        steps = np.cumsum(rng.normal(0.0, 1e-3, count)) + walk
        walk = steps[-1]
        (10.0 + rng.normal(0.0, 1.0, count) + steps).astype("<f8").tofile(out)
"""

ALLANTOOLS = r"""
import sys, json, numpy as np
path, rate, which = sys.argv[1], float(sys.argv[2]), sys.argv[3].split(",")
if path.endswith(".csv"):                           # a text record's `output` column, as a script reads it
    y = np.loadtxt(path, delimiter=",", skiprows=1, usecols=1)
else:
    y = np.fromfile(path, dtype='<f8')
tau0 = 1.0 / rate
x = np.concatenate(([0.0], np.cumsum(y) * tau0))   # allantools frequency2phase
del y
n = len(x)
out = {"tau": []}
for name in which:
    out[name] = []
m = 1
while m <= (n - 1) // 3:                             # the octave grid inertest reports with all six
    tau = m * tau0
    out["tau"].append(tau)
    for name in which:
        if name in ("adev", "oadev"):                # allantools calc_adev_phase, stride m or 1
            stride = m if name == "adev" else 1
            d2, d1, d0 = x[2 * m::stride], x[m::stride], x[::stride]
            k = min(len(d0), len(d1), len(d2))
            v = d2[:k] - 2.0 * d1[:k] + d0[:k]
            out[name].append(float(np.sqrt(np.sum(v * v) / (2.0 * k)) / tau))
        elif name in ("hdev", "ohdev"):              # allantools calc_hdev_phase, stride m or 1
            stride = m if name == "hdev" else 1
            d3, d2, d1, d0 = x[3 * m::stride], x[2 * m::stride], x[m::stride], x[::stride]
            k = min(len(d0), len(d1), len(d2), len(d3))
            v = d3[:k] - 3.0 * d2[:k] + 3.0 * d1[:k] - d0[:k]
            out[name].append(float(np.sqrt(np.sum(v * v) / (6.0 * k)) / tau))
        elif name == "mdev":                          # allantools mdev: first window, then a cumsum
            v = np.sum(x[2 * m:3 * m] - 2.0 * x[m:2 * m] + x[0:m])
            s = v * v
            k = n - 3 * m
            w = v + np.cumsum(x[3 * m:] - 3.0 * x[2 * m:2 * m + k] + 3.0 * x[m:m + k] - x[:k])
            s += np.sum(w * w)
            out[name].append(float(np.sqrt(s / (2.0 * m * m * tau * tau * (k + 1)))))
    m *= 2
print(json.dumps(out))
"""


class _Child(subprocess.Popen):
    """Popen that keeps the resource usage of the child from wait4()."""

    peak_rss_kb = 0

    def _try_wait(self, wait_flags):
        pid, status, usage = os.wait4(self.pid, wait_flags)
        if pid == self.pid:
            self.peak_rss_kb = usage.ru_maxrss
        return (pid, status)


def run_child(command):
    """Runs a command; returns (seconds, peak RSS in MB of that child, stdout).

    The peak comes from wait4() on this very child, after exec: the parent stays small (the record
    is written by a separate process), so the forked copy does not inflate it.
    """
    start = time.perf_counter()
    child = _Child(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    out, err = child.communicate()
    seconds = time.perf_counter() - start
    if child.returncode != 0:
        sys.exit(f"failed: {' '.join(command)}\n{err.decode()}")
    return seconds, child.peak_rss_kb / 1024.0, out.decode()


def best_of(runs, command):
    """Runs a command `runs` times back to back; returns the fastest (seconds, MB, stdout) and the peak MB."""
    results = [run_child(command) for _ in range(runs)]
    fastest = min(results, key=lambda r: r[0])
    return fastest[0], max(r[1] for r in results), fastest[2]


def worst_difference(ours, theirs, names):
    worst = 0.0
    for name in names:
        for tau, dev in zip(theirs["tau"], theirs[name]):
            i = ours["tau"].index(tau)
            worst = max(worst, abs(ours[name]["values"][i] - dev) / dev)
    return worst


def measure(inertest, samples, runs, path):
    """Writes the record to `path` and times inertest and the allantools algorithm on it (the file is
    left for the caller, who deletes it). Returns a dict of times (s), peak RSS (MB) and agreement."""
    five = ["adev", "oadev", "mdev", "hdev", "ohdev"]
    subprocess.run([sys.executable, "-c", WRITE_RECORD, path, str(samples)], check=True)
    base = [inertest, "allan", path, "--rate", "100", "--format", "f64", "--taus", "octave", "--json"]
    numpy = [sys.executable, "-c", ALLANTOOLS, path, "100"]
    t_oadev, m_oadev, out_oadev = best_of(runs, base + ["--estimators", "oadev"])
    t_py1, m_py1, out_py1 = best_of(runs, numpy + ["oadev"])
    t_all, m_all, out_all = best_of(runs, base)
    t_py5, m_py5, out_py5 = best_of(runs, numpy + [",".join(five)])
    ours = json.loads(out_all)
    return {
        "size_mb": os.path.getsize(path) / 1e6,
        "taus": len(json.loads(out_py1)["tau"]),
        "oadev": (t_oadev, m_oadev), "numpy_oadev": (t_py1, m_py1),
        "all": (t_all, m_all), "numpy_five": (t_py5, m_py5),
        "worst_oadev": worst_difference(json.loads(out_oadev), json.loads(out_py1), ["oadev"]),
        "worst_five": worst_difference(ours, json.loads(out_py5), five),
    }


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--samples", type=int, default=100_000_000)
    parser.add_argument("--build-dir", default="build")
    parser.add_argument("--runs", type=int, default=2, help="runs of each program, best kept (shared machine)")
    args = parser.parse_args()
    inertest = os.path.join(args.build_dir, "bin", "inertest")
    if not os.path.exists(inertest):
        sys.exit(f"{inertest} not found: build first (make build)")

    with tempfile.TemporaryDirectory() as tmp:
        r = measure(inertest, args.samples, args.runs, os.path.join(tmp, "record.f64"))
    size_mb = r["size_mb"]
    print(f"record: {args.samples:.3g} samples, {size_mb:.0f} MB raw f64, white 1 deg/h + rate random walk, 100 Hz")
    print(f"each program run {args.runs} times back to back, fastest kept, peak RSS the largest")
    (t_oadev, m_oadev), (t_py1, m_py1) = r["oadev"], r["numpy_oadev"]
    (t_all, m_all), (t_py5, m_py5) = r["all"], r["numpy_five"]
    print(f"agreement over {r['taus']} octave taus, max relative difference: "
          f"OADEV {r['worst_oadev']:.1e}, ADEV..OHDEV {r['worst_five']:.1e}")
    print()
    print(f"{'run':<64} {'time (s)':>9} {'peak RSS (MB)':>14}")
    print(f"{'inertest, OADEV only':<64} {t_oadev:9.2f} {m_oadev:14.0f}")
    print(f"{'allantools algorithm (numpy), OADEV only':<64} {t_py1:9.2f} {m_py1:14.0f}")
    print(f"{'inertest, ADEV OADEV MDEV HDEV OHDEV TOTDEV + bounds + noise fit':<64} {t_all:9.2f} {m_all:14.0f}")
    print(f"{'allantools algorithm (numpy), ADEV OADEV MDEV HDEV OHDEV':<64} {t_py5:9.2f} {m_py5:14.0f}")
    print("  (TOTDEV left out on the numpy side: allantools reflects the whole record per tau, O(N) memory")
    print("   and time per tau; inertest computes it in the same pass as the others)")
    print()
    print(f"OADEV vs OADEV:              {t_py1 / t_oadev:6.1f}x faster, {m_py1 / m_oadev:5.2f}x less memory")
    print(f"all six vs the same five:    {t_py5 / t_all:6.1f}x faster, {m_py5 / m_all:5.2f}x less memory")
    print(f"inertest peak RSS / raw size: {m_all / size_mb:.2f} (all six), {m_oadev / size_mb:.2f} (OADEV)")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""inertest allan against the allantools algorithm on one 1e8-sample f64 record.

Writes a white + random-walk rate record (raw little-endian float64) to a temporary file, then
times, each in its own process with its peak resident memory (ru_maxrss of the child):
  - inertest allan FILE --rate 100 --format f64 --taus octave --json   (all six estimators + noise fit)
  - the same with --estimators oadev                                   (the fair one-to-one comparison)
  - the allantools algorithm for OADEV, written here: load the record, phase = cumsum(y) * tau0 with a
    leading 0, then for each octave m one vectorised numpy pass
    sum((x[2m:] - 2 x[m:-m] + x[:-2m])^2) / (2 tau^2 (N - 2m)), as allantools.oadev does
    (allantools is not installed; this is its calc_adev_phase with stride 1).
It checks that the OADEV values agree and prints times, peak memory and the ratios.
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

ALLANTOOLS_OADEV = r"""
import sys, json, numpy as np
path, rate = sys.argv[1], float(sys.argv[2])
y = np.fromfile(path, dtype='<f8')
tau0 = 1.0 / rate
x = np.concatenate(([0.0], np.cumsum(y) * tau0))   # allantools frequency2phase
n = len(x)
taus, devs = [], []
m = 1
while m <= (n - 1) // 2 and m <= (len(y)) // 3:      # the octave grid inertest reports with all six
    d = x[2 * m:] - 2.0 * x[m:-m] + x[:-2 * m]
    tau = m * tau0
    devs.append(float(np.sqrt(np.sum(d * d) / (2.0 * tau * tau * (n - 2 * m)))))
    taus.append(tau)
    m *= 2
print(json.dumps({"tau": taus, "oadev": devs}))
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


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--samples", type=int, default=100_000_000)
    parser.add_argument("--build-dir", default="build")
    parser.add_argument("--keep", action="store_true", help="keep the record file")
    args = parser.parse_args()
    inertest = os.path.join(args.build_dir, "bin", "inertest")
    if not os.path.exists(inertest):
        sys.exit(f"{inertest} not found: build first (make build)")

    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "record.f64")
        subprocess.run([sys.executable, "-c", WRITE_RECORD, path, str(args.samples)], check=True)
        size_mb = os.path.getsize(path) / 1e6
        print(f"record: {args.samples:.3g} samples, {size_mb:.0f} MB raw f64, white 1 deg/h + rate random walk, 100 Hz")

        base = [inertest, "allan", path, "--rate", "100", "--format", "f64", "--taus", "octave", "--json"]
        t_oadev, m_oadev, out_oadev = run_child(base + ["--estimators", "oadev"])
        t_all, m_all, out_all = run_child(base)
        t_py, m_py, out_py = run_child([sys.executable, "-c", ALLANTOOLS_OADEV, path, "100"])

    ours = json.loads(out_all)
    theirs = json.loads(out_py)
    worst = 0.0
    for tau, dev in zip(theirs["tau"], theirs["oadev"]):
        i = ours["tau"].index(tau)
        worst = max(worst, abs(ours["oadev"]["values"][i] - dev) / dev)
    print(f"OADEV agreement over {len(theirs['tau'])} octave taus: max relative difference {worst:.2e}")
    print()
    print(f"{'run':<58} {'time (s)':>9} {'peak RSS (MB)':>14}")
    print(f"{'inertest, OADEV only':<58} {t_oadev:9.2f} {m_oadev:14.0f}")
    print(f"{'inertest, ADEV OADEV MDEV HDEV OHDEV TOTDEV + noise fit':<58} {t_all:9.2f} {m_all:14.0f}")
    print(f"{'allantools algorithm (numpy), OADEV only':<58} {t_py:9.2f} {m_py:14.0f}")
    print()
    print(f"speed-up, OADEV vs OADEV:          {t_py / t_oadev:6.1f}x   (memory ratio {m_py / m_oadev:.2f})")
    print(f"speed-up, all six vs OADEV only:   {t_py / t_all:6.1f}x   (memory ratio {m_py / m_all:.2f})")
    print(f"inertest peak RSS / raw size:      {m_all / size_mb:.2f} (all six), {m_oadev / size_mb:.2f} (OADEV)")


if __name__ == "__main__":
    main()

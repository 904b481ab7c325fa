#!/usr/bin/env python3
"""Loads the pages of `inertest serve` in headless Chromium and checks the rendered DOM (issue 17).

Builds an archive of the golden demo campaign (FOG-SIM-NAV) and three scale factor tests of two
more gyros, starts `inertest serve --port 0` on it, then with `chromium --headless --dump-dom`:
  * the instrument list at /?q=FOG-3: its script ran, so only FOG-3's row is shown ("1 / 3");
  * the list in Chinese (/?lang=zh): its headings are GJB's words;
  * FOG-SIM-NAV's history page and its latest campaign's report: plots (<svg> with markers);
and fails on any console message or failed load. Exits 77 (ctest SKIP) without chromium.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import urllib.request

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from chromium import chromium_command, console_problems, run_chromium  # noqa: E402

SKIP = 77


def dump_dom(browser, work, url):
    with tempfile.TemporaryDirectory(dir=work) as profile:
        run = run_chromium(browser, profile, ["--dump-dom"], url)
    return run.stdout, console_problems(run.stderr)


def scale_factor_campaign(instrument, tested_on, value):
    return {
        "results_schema_version": 1, "inertest_version": "0.1.0", "tested_on": tested_on,
        "processed_at": tested_on + "T12:00:00Z", "plan": {"title": "acceptance " + instrument},
        "instrument": {"id": instrument, "type": "gyro"}, "site": {},
        "procedures": [{"name": "scale_factor", "kind": "scale_factor", "result": {
            "scale_factor": {"value": value, "unit": "pulse/s/(deg/s)", "uncertainty": 0.03}}}],
        "verdicts": [{"procedure": "scale_factor", "figure": "scale_factor", "value": value,
                      "unit": "pulse/s/(deg/s)", "pass": True, "min": 35999.0, "max": 36001.0}],
        "verdict": "PASS",
    }


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--inertest", required=True)
    parser.add_argument("--source", required=True, help="the source tree (for tests/golden/demo_results.json)")
    parser.add_argument("--out", required=True)
    options = parser.parse_args()
    browser = chromium_command()
    if browser is None:
        print("SKIP: chromium is not installed (apt-get install chromium; `make test` installs it)")
        return SKIP
    os.makedirs(options.out, exist_ok=True)
    work = tempfile.mkdtemp(dir=options.out)
    failures = []
    try:
        with open(os.path.join(options.source, "tests/golden/demo_results.json")) as f:
            demo = json.load(f)
        demo["tested_on"], demo["processed_at"] = "2026-03-02", "2026-03-02T08:00:00Z"
        files = []
        for name, results in [("demo", demo), ("fog2", scale_factor_campaign("FOG-2", "2026-03-01", 36000.4)),
                              ("fog3a", scale_factor_campaign("FOG-3", "2026-03-01", 35999.8)),
                              ("fog3b", scale_factor_campaign("FOG-3", "2026-03-03", 35999.9))]:
            files.append(os.path.join(work, name + ".json"))
            with open(files[-1], "w") as f:
                json.dump(results, f)
        db = os.path.join(work, "archive.sqlite")
        subprocess.run([options.inertest, "archive", "add", *files, "--db", db], check=True, capture_output=True)

        server = subprocess.Popen([options.inertest, "serve", "--db", db, "--port", "0"], stdout=subprocess.PIPE,
                                  text=True)
        try:
            first = server.stdout.readline()
            match = re.search(r"(http://127\.0\.0\.1:\d+/)", first)
            if not match:
                print(f"FAIL: the server did not print its URL: {first!r}")
                return 1
            url = match.group(1)

            dom, problems = dump_dom(browser, work, url + "?q=FOG-3")
            failures += [f"/?q=FOG-3: console: {p}" for p in problems]
            rows = re.findall(r'<tr data-instrument="([^"]+)"( hidden="")?', dom)
            shown = [row for row, hidden in rows if not hidden]
            if [row for row, _ in rows] != ["FOG-2", "FOG-3", "FOG-SIM-NAV"] or shown != ["FOG-3"]:
                failures.append(f"/?q=FOG-3: rows {rows}, expected only FOG-3 shown")
            if '<span id="shown">1 / 3</span>' not in dom:
                failures.append("/?q=FOG-3: the count does not say 1 / 3")

            dom, problems = dump_dom(browser, work, url + "?lang=zh")
            failures += [f"/?lang=zh: console: {p}" for p in problems]
            if "<th>产品编号</th>" not in dom or '<span id="shown">3 / 3</span>' not in dom:
                failures.append("/?lang=zh: no Chinese headings or not every row shown")

            campaigns = json.load(urllib.request.urlopen(url + "api/campaigns"))["campaigns"]
            demo_id = [c["id"] for c in campaigns if c["instrument"] == "FOG-SIM-NAV"][0]
            for page in ["instruments/FOG-SIM-NAV", f"campaigns/{demo_id}", "fleet"]:
                dom, problems = dump_dom(browser, work, url + page)
                failures += [f"/{page}: console: {p}" for p in problems]
                plots = dom.count("<svg")
                markers = dom.count("<circle")
                if plots == 0 or markers == 0:
                    failures.append(f"/{page}: {plots} plots, {markers} markers")
                else:
                    print(f"/{page}: {plots} plots, {markers} markers")
        finally:
            server.terminate()
            server.wait(timeout=30)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    for failure in failures:
        print("FAIL:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

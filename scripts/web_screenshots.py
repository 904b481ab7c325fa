#!/usr/bin/env python3
"""Retakes the web view's screenshots in docs/ (README, "The web view"), from `make demo`'s archive:

    make demo && /usr/bin/python3 scripts/web_screenshots.py [--inertest build/bin/inertest]

starts `inertest serve --db demo/archive.sqlite --port 0` and, in headless Chromium at 1200x900
(tests/chromium.py, DevTools protocol), saves
  docs/web-instruments.png  the instrument list (/),
  docs/web-history.png      the history page of the fleet's first gyro (/instruments/FOG-B01),
  docs/web-allan-zoom.png   the demo campaign's Allan deviation zoomed to tau 10..1000 s (#zoom=),
                            the pointer on a point showing its value and interval.
"""
import argparse
import base64
import json
import os
import re
import subprocess
import sys
import tempfile
import urllib.request

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from chromium import DevTools, chromium_command  # noqa: E402

# The Allan deviation: the log-log plot with confidence intervals.
ALLAN = ("window.inertestPlots.plots.findIndex(function (p) { var q = p.data.panels[0]; return q.x.scale === 'log' && "
         "q.y.scale === 'log' && q.series.some(function (s) { return s.y_low.length; }); })")


def capture(tools, path):
    shot = tools.call("Page.captureScreenshot", {"format": "png"}, session=True)
    with open(path, "wb") as f:
        f.write(base64.b64decode(shot["data"]))
    print(f"{path}: {os.path.getsize(path) // 1024} kB")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--inertest", default=os.path.join(ROOT, "build/bin/inertest"))
    parser.add_argument("--db", default=os.path.join(ROOT, "demo/archive.sqlite"))
    parser.add_argument("--out", default=os.path.join(ROOT, "docs"))
    options = parser.parse_args()
    browser = chromium_command()
    if browser is None or not os.path.exists(options.db):
        sys.exit("needs chromium and the demo archive (make demo)")
    server = subprocess.Popen([options.inertest, "serve", "--db", options.db, "--port", "0"], stdout=subprocess.PIPE,
                              text=True)
    try:
        url = re.search(r"(http://127\.0\.0\.1:\d+/)", server.stdout.readline()).group(1)
        campaigns = json.load(urllib.request.urlopen(url + "api/campaigns"))["campaigns"]
        demo = [c["id"] for c in campaigns if c["instrument"] == "FOG-SIM-NAV"][0]
        with tempfile.TemporaryDirectory() as profile, DevTools(browser, profile, 1200, 900) as tools:
            tools.open(url)
            capture(tools, os.path.join(options.out, "web-instruments.png"))
            tools.open(url + "instruments/FOG-B01")
            capture(tools, os.path.join(options.out, "web-history.png"))
            tools.open(url + f"campaigns/{demo}")
            n = tools.evaluate(ALLAN)
            tools.open(url + f"campaigns/{demo}?lang=en#zoom={n}:10:1000")
            x, y = tools.evaluate(f"""(function () {{
              var plot = window.inertestPlots.plots[{n}];
              plot.box.scrollIntoView({{block: 'center'}});
              var marker = plot.svg.querySelectorAll('circle[data-index]');
              var r = marker[Math.floor(marker.length / 2)].getBoundingClientRect();
              return [r.left + r.width / 2, r.top + r.height / 2];
            }})()""")
            tools.mouse("moved", x, y)
            capture(tools, os.path.join(options.out, "web-allan-zoom.png"))
            if tools.problems:
                sys.exit("console: " + "; ".join(tools.problems))
    finally:
        server.terminate()
        server.wait(timeout=30)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Loads the pages of `inertest serve` in headless Chromium and checks the rendered DOM (issue 17).

Builds an archive of the golden demo campaign (FOG-SIM-NAV) and three scale factor tests of two
more gyros, starts `inertest serve --port 0` on it, then with `chromium --headless --dump-dom`:
  * the instrument list at /?q=FOG-3: its script ran, so only FOG-3's row is shown ("1 / 3");
  * the list in Chinese (/?lang=zh): its headings are GJB's words;
  * FOG-SIM-NAV's history page and its latest campaign's report: plots (<svg> with markers);
then, driving Chromium over the DevTools protocol (tests/chromium.py DevTools), the interactive plots
(src/serve/assets/plots.js) with real mouse events:
  * FOG-3's history: the markers are the data's points where the axes put them; hovering one shows
    "value ± uncertainty unit"; the instrument and figure <select>s go to the chosen history;
  * the demo report's Allan deviation (log-log, with confidence intervals): the curve's vertices are
    its data; a dragged zoom shows fewer points, new ticks inside the new range; the tooltip of a
    zoomed point reads its value and interval; the wheel zooms, Reset restores, Pan moves the view by
    the distance dragged, #zoom=N:x0:x1 opens
    zoomed; the CSV downloaded by its button holds exactly the plotted data, the SVG the plot shown;
    in print the buttons are hidden;
  * with --allow-add, the list page's form adds a results.json with the token typed in (and shows a
    wrong token's 403);
and fails on any console message or failed load. Exits 77 (ctest SKIP) without chromium.
"""
import argparse
import csv
import io
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import urllib.request
import xml.etree.ElementTree as ElementTree

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from chromium import DevTools, chromium_command, console_problems, run_chromium  # noqa: E402

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


# The geometry of plot n as drawn: per panel its area, ranges and scales; per series how many points it
# shows, its markers' and its lines' pixels with the data indices they stand for.
GEOMETRY = """(function (n) {
  var plot = window.inertestPlots.plots[n];
  return Array.prototype.map.call(plot.svg.querySelectorAll('g.panel'), function (g, p) {
    var panel = plot.data.panels[p];
    return {
      area: g.getAttribute('data-area').split(' ').map(Number),
      x: g.getAttribute('data-x-range').split(' ').map(Number),
      y: g.getAttribute('data-y-range').split(' ').map(Number),
      x_scale: panel.x.scale, y_scale: panel.y.scale,
      x_ticks: Array.prototype.map.call(g.querySelectorAll('text.tick.x'), function (t) { return +t.getAttribute('data-value'); }),
      series: Array.prototype.map.call(g.querySelectorAll('g.series'), function (s) {
        return {
          shown: +s.getAttribute('data-shown'),
          markers: Array.prototype.map.call(s.querySelectorAll('[data-index]:not(polyline)'), function (m) {
            var b = m.getBBox();
            return [+m.getAttribute('data-index'), b.x + b.width / 2, b.y + b.height / 2];
          }),
          lines: Array.prototype.map.call(s.querySelectorAll('polyline'), function (l) {
            var index = l.getAttribute('data-index').split(' ').map(Number);
            return l.getAttribute('points').split(' ').map(function (q, i) {
              var xy = q.split(',').map(Number);
              return [index[i], xy[0], xy[1]];
            });
          })
        };
      })
    };
  });
})(%d)"""

# The client (CSS pixel) position of svg point (x, y) of plot n, after scrolling it into view.
CLIENT = """(function (n, x, y) {
  var plot = window.inertestPlots.plots[n];
  plot.box.scrollIntoView();
  var r = plot.svg.getBoundingClientRect(), box = plot.svg.viewBox.baseVal;
  return [r.left + x * r.width / box.width, r.top + y * r.height / box.height];
})(%d, %r, %r)"""


def to_pixel(value, lo, hi, scale, pixel_lo, pixel_hi):
    if scale == "log":
        value, lo, hi = math.log10(value), math.log10(lo), math.log10(hi)
    return pixel_lo + (value - lo) / (hi - lo) * (pixel_hi - pixel_lo)


def placed(panel, x, y):
    """The pixel of data point (x, y) in a panel's geometry, or None when it lies outside the area."""
    left, top, right, bottom = panel["area"]
    if x is None or y is None or (panel["x_scale"] == "log" and x <= 0) or (panel["y_scale"] == "log" and y <= 0):
        return None
    px = to_pixel(x, panel["x"][0], panel["x"][1], panel["x_scale"], left, right)
    py = to_pixel(y, panel["y"][0], panel["y"][1], panel["y_scale"], bottom, top)
    inside = left - 0.01 <= px <= right + 0.01 and top - 0.01 <= py <= bottom + 0.01
    return (px, py) if inside else None


def check_drawn(data, geometry, where):
    """Every series shows exactly the data points inside its panel, each where the axes put it (to the
    0.1 px the drawing rounds to); a line's vertices are data points too. Returns the failures."""
    failures = []
    for p, (panel, drawn) in enumerate(zip(data["panels"], geometry)):
        for k, (series, shown) in enumerate(zip(panel["series"], drawn["series"])):
            expected = {i: placed(drawn, x, y) for i, (x, y) in enumerate(zip(series["x"], series["y"]))}
            inside = {i for i, q in expected.items() if q is not None}
            if shown["shown"] != len(inside):
                failures.append(f"{where}: panel {p} series {k} shows {shown['shown']} points, {len(inside)} are in view")
            if series["marker"] != "none" and sorted(m[0] for m in shown["markers"]) != sorted(inside):
                failures.append(f"{where}: panel {p} series {k}: markers at points {[m[0] for m in shown['markers']]}")
            vertices = shown["markers"] + [v for line in shown["lines"] for v in line]
            for i, x, y in vertices:
                series_x, series_y = series["x"][i], series["y"][i]
                left, top, right, bottom = drawn["area"]
                ex = to_pixel(series_x, drawn["x"][0], drawn["x"][1], drawn["x_scale"], left, right)
                ey = to_pixel(series_y, drawn["y"][0], drawn["y"][1], drawn["y_scale"], bottom, top)
                if abs(ex - x) > 0.06 or abs(ey - y) > 0.06:
                    failures.append(f"{where}: panel {p} series {k} point {i} drawn at ({x}, {y}), expected ({ex:.2f}, {ey:.2f})")
                    break
    return failures


TIP = re.compile(r"^(?P<value>[-+0-9.e]+)(?: ± (?P<u>[0-9.e+-]+)| \(\+(?P<up>[0-9.e+-]+) / −(?P<down>[0-9.e+-]+)\))? (?P<unit>.+)$")


def check_tip(tools, n, panel_data, geometry, where):
    """Hovers the first marker in view of plot n's first series with error bars; the tooltip must read
    that point's value and uncertainty (or interval) with the axis unit, as rounded to the uncertainty's
    second significant digit. Returns the failures."""
    for k, series in enumerate(panel_data["series"]):
        markers = geometry[0]["series"][k]["markers"]
        if series["y_low"] and markers:
            break
    else:
        return [f"{where}: no marker with an error bar to hover"]
    i, x, y = markers[len(markers) // 2]
    cx, cy = tools.evaluate(CLIENT % (n, x, y))
    tools.mouse("moved", cx, cy)
    tip = tools.evaluate(f"(function () {{ var t = window.inertestPlots.plots[{n}].tip; return t.hidden ? null : "
                         "[t.querySelector('.tip-value').textContent, +t.getAttribute('data-series'), "
                         "+t.getAttribute('data-index')]; })()")
    if tip is None:
        return [f"{where}: no tooltip over point {i}"]
    text, tip_series, tip_index = tip
    match = TIP.match(text)
    value, low, high = series["y"][i], series["y_low"][i], series["y_high"][i]
    up, down = high - value, value - low
    u = max(up, down)
    step = 10 ** (math.floor(math.log10(u)) - 1)  # the last digit shown
    failures = []
    if (tip_series, tip_index) != (k, i) or not match or match.group("unit") != panel_data["y"]["unit"]:
        failures.append(f"{where}: tooltip {text!r} for series {tip_series} point {tip_index}, expected series {k} point {i}")
    elif abs(float(match.group("value")) - value) > step:
        failures.append(f"{where}: tooltip {text!r}: value {value}")
    elif match.group("u") is not None and abs(float(match.group("u")) - u) > step:
        failures.append(f"{where}: tooltip {text!r}: uncertainty {u}")
    elif match.group("up") is not None and (abs(float(match.group("up")) - up) > step or abs(float(match.group("down")) - down) > step):
        failures.append(f"{where}: tooltip {text!r}: interval +{up} / -{down}")
    elif match.group("u") is None and match.group("up") is None:
        failures.append(f"{where}: tooltip {text!r} has no uncertainty")
    else:
        print(f"{where}: tooltip over point {i}: {text}")
    tools.mouse("moved", 1, 1)
    return failures


def downloaded(tools, directory, button):
    """Clicks the button (a CSS selector) and returns the text of the file it downloads."""
    before = set(os.listdir(directory))
    tools.evaluate(f"document.querySelector({button!r}).click()")
    while True:
        progress = tools.wait_for("Browser.downloadProgress", 60)
        if progress["state"] in ("completed", "canceled"):
            break
    new = [name for name in set(os.listdir(directory)) - before if not name.endswith(".crdownload")]
    if progress["state"] != "completed" or len(new) != 1:
        raise RuntimeError(f"download by {button}: {progress['state']}, files {new}")
    with open(os.path.join(directory, new[0]), encoding="utf-8") as f:
        return f.read()


def check_history_page(tools, url):
    """FOG-3's history: its scale factor's two points as drawn, their tooltip, and the switchers."""
    failures = []
    tools.open(url + "instruments/FOG-3")
    data = tools.evaluate("window.inertestPlots.plots[0].data")
    geometry = tools.evaluate(GEOMETRY % 0)
    failures += check_drawn(data, geometry, "/instruments/FOG-3")
    if [s["shown"] for s in geometry[0]["series"]] != [2]:
        failures.append(f"/instruments/FOG-3: {[s['shown'] for s in geometry[0]['series']]} points shown, expected [2]")
    failures += check_tip(tools, 0, data["panels"][0], geometry, "/instruments/FOG-3")
    options = tools.evaluate("[Array.prototype.map.call(document.querySelectorAll('#instrument-switch option'), "
                             "function (o) { return o.textContent; }), Array.prototype.map.call("
                             "document.querySelectorAll('#figure-switch option'), function (o) { return o.textContent; })]")
    if options[0] != ["FOG-2", "FOG-3", "FOG-SIM-NAV"] or "scale_factor/scale_factor" not in options[1]:
        failures.append(f"/instruments/FOG-3: switch options {options}")
    tools.evaluate("(function () { var s = document.getElementById('instrument-switch'); s.selectedIndex = 0; "
                   "s.dispatchEvent(new Event('change')); })()")
    tools.wait_for("Page.loadEventFired")
    location = tools.evaluate("window.location.pathname + window.location.search")
    if location != "/instruments/FOG-2":
        failures.append(f"choosing FOG-2 went to {location}")
    tools.evaluate("(function () { var s = document.getElementById('figure-switch'); s.value = Array.prototype.filter.call("
                   "s.options, function (o) { return o.textContent === 'scale_factor/scale_factor'; })[0].value; "
                   "s.dispatchEvent(new Event('change')); })()")
    tools.wait_for("Page.loadEventFired")
    location = tools.evaluate("window.location.pathname + window.location.search")
    sections = tools.evaluate("document.querySelectorAll('section.procedure').length")
    if location != "/instruments/FOG-2?figure=scale_factor/scale_factor" or sections != 1:
        failures.append(f"choosing the figure went to {location}, {sections} sections")
    return failures


def check_allan_plot(tools, url, page, downloads):
    """The demo report's Allan deviation: drawing, zoom, tooltip, reset, wheel, #zoom=, downloads, print."""
    failures = []
    tools.open(url + page)
    n = tools.evaluate("window.inertestPlots.plots.findIndex(function (p) { var q = p.data.panels[0]; return "
                       "q.x.scale === 'log' && q.y.scale === 'log' && q.series.some(function (s) { return s.y_low.length; }); })")
    if n is None or n < 0:
        return [f"/{page}: no log-log plot with error bars"]
    where = f"/{page} plot {n}"
    data = tools.evaluate(f"window.inertestPlots.plots[{n}].data")
    before = tools.evaluate(GEOMETRY % n)
    failures += check_drawn(data, before, where)
    # Drawn by the script, the plot keeps its name for a screen reader (the report's caption).
    title = tools.evaluate(f"(window.inertestPlots.plots[{n}].svg.querySelector('title') || {{}}).textContent || ''")
    if "Allan" not in title:
        failures.append(f"{where}: the drawn plot's <title> is {title!r}, not its caption")
    measured = [k for k, s in enumerate(data["panels"][0]["series"]) if s["y_low"]][0]
    points = len(data["panels"][0]["series"][measured]["x"])
    if before[0]["series"][measured]["shown"] != points:
        failures.append(f"{where}: {before[0]['series'][measured]['shown']} of {points} points shown before zooming")

    # Drag along x over the middle of the area: x zooms, y stays.
    left, top, right, bottom = before[0]["area"]
    start = tools.evaluate(CLIENT % (n, left + 0.3 * (right - left), 0.5 * (top + bottom)))
    end = tools.evaluate(CLIENT % (n, left + 0.6 * (right - left), 0.5 * (top + bottom)))
    tools.mouse("moved", *start)
    tools.mouse("pressed", *start)
    tools.mouse("moved", (start[0] + end[0]) / 2, start[1])
    tools.mouse("moved", *end)
    tools.mouse("released", *end)
    after = tools.evaluate(GEOMETRY % n)
    failures += check_drawn(data, after, where + " zoomed")
    x0, x1 = before[0]["x"]
    expected = [10 ** (math.log10(x0) + f * (math.log10(x1) - math.log10(x0))) for f in (0.3, 0.6)]
    shown = after[0]["series"][measured]["shown"]
    ticks = after[0]["x_ticks"]
    if any(abs(math.log10(a / b)) > 0.01 for a, b in zip(after[0]["x"], expected)):
        failures.append(f"{where}: zoomed to x {after[0]['x']}, expected {expected}")
    if not 0 < shown < points:
        failures.append(f"{where}: {shown} of {points} points shown after zooming")
    if len(ticks) < 2 or ticks == before[0]["x_ticks"] or not all(after[0]["x"][0] * (1 - 1e-9) <= t <= after[0]["x"][1] * (1 + 1e-9) for t in ticks):
        failures.append(f"{where}: x ticks after zooming {ticks} (range {after[0]['x']}, before {before[0]['x_ticks']})")
    print(f"{where}: zoomed x {before[0]['x']} -> {[round(v, 4) for v in after[0]['x']]}: {points} -> {shown} points, ticks {ticks}")
    failures += check_tip(tools, n, data["panels"][0], after, where + " zoomed")

    # The downloads: the CSV is the data, the SVG the plot as shown.
    table = list(csv.reader(io.StringIO(downloaded(tools, downloads, f"#plot-{n} .download-csv"))))
    rows = [[s["x"][i], s["y"][i], s["y_low"][i] if s["y_low"] else None, s["y_high"][i] if s["y_high"] else None]
            for p in data["panels"] for s in p["series"] for i in range(min(len(s["x"]), len(s["y"])))]
    values = [[float(v) if v else None for v in row[2:]] for row in table[1:]]
    if values != rows:
        failures.append(f"{where}: the CSV's {len(values)} rows are not the plot's {len(rows)} points")
    else:
        print(f"{where}: CSV of {len(values)} rows, header {table[0]}")
    svg = ElementTree.fromstring(downloaded(tools, downloads, f"#plot-{n} .download-svg").split("\n", 1)[1])
    circles = len(svg.findall(".//{http://www.w3.org/2000/svg}circle"))
    drawn_circles = tools.evaluate(f"window.inertestPlots.plots[{n}].svg.querySelectorAll('circle').length")
    if svg.tag != "{http://www.w3.org/2000/svg}svg" or circles != drawn_circles or svg.get("data-zoomed") != "true":
        failures.append(f"{where}: the SVG download ({svg.tag}, {circles} circles) is not the zoomed plot ({drawn_circles})")

    tools.evaluate(f"document.querySelector('#plot-{n} .plot-tools button:nth-child(3)').click()")
    reset = tools.evaluate(GEOMETRY % n)
    if reset[0]["x"] != before[0]["x"] or reset[0]["series"][measured]["shown"] != points:
        failures.append(f"{where}: Reset gave x {reset[0]['x']}, expected {before[0]['x']}")
    middle = tools.evaluate(CLIENT % (n, 0.5 * (left + right), 0.5 * (top + bottom)))
    tools.call("Input.dispatchMouseEvent", {"type": "mouseWheel", "x": middle[0], "y": middle[1], "deltaX": 0,
                                            "deltaY": -100}, session=True)
    wheeled = tools.evaluate(GEOMETRY % n)
    if not before[0]["x"][0] < wheeled[0]["x"][0] < wheeled[0]["x"][1] < before[0]["x"][1]:
        failures.append(f"{where}: the wheel zoomed x to {wheeled[0]['x']} from {before[0]['x']}")

    # Pan: dragging right by a tenth of the area moves the view left by a tenth of its (log) span.
    tools.evaluate(f"document.querySelector('#plot-{n} .plot-tools button:nth-child(2)').click()")
    start = tools.evaluate(CLIENT % (n, 0.5 * (left + right), 0.5 * (top + bottom)))
    end = tools.evaluate(CLIENT % (n, 0.5 * (left + right) + 0.1 * (right - left), 0.5 * (top + bottom)))
    tools.mouse("pressed", *start)
    tools.mouse("moved", (start[0] + end[0]) / 2, start[1])
    tools.mouse("moved", *end)
    tools.mouse("released", *end)
    tools.evaluate(f"document.querySelector('#plot-{n} .plot-tools button:nth-child(1)').click()")
    panned = tools.evaluate(GEOMETRY % n)
    w0, w1 = (math.log10(v) for v in wheeled[0]["x"])
    p0, p1 = (math.log10(v) for v in panned[0]["x"])
    if abs((p1 - p0) - (w1 - w0)) > 1e-6 * (w1 - w0) or abs((w0 - p0) - 0.1 * (w1 - w0)) > 0.01 * (w1 - w0):
        failures.append(f"{where}: panning moved x from {wheeled[0]['x']} to {panned[0]['x']}")

    tools.call("Emulation.setEmulatedMedia", {"media": "print"}, session=True)
    hidden = tools.evaluate("Array.prototype.every.call(document.querySelectorAll('.plot-tools'), function (t) { "
                            "return getComputedStyle(t).display === 'none'; })")
    tools.call("Emulation.setEmulatedMedia", {"media": ""}, session=True)
    if not hidden:
        failures.append(f"/{page}: the plot buttons are printed")

    lo, hi = expected
    tools.open(url + page + f"?lang=en#zoom={n}:{lo}:{hi}")  # a new document, not a move within this one
    opened = tools.evaluate(GEOMETRY % n)
    if any(abs(a / b - 1) > 1e-9 for a, b in zip(opened[0]["x"], (lo, hi))):
        failures.append(f"{where}: #zoom opened x {opened[0]['x']}, expected {[lo, hi]}")
    return failures


# Sends file through the list page's form with token; the answer shown once it is in.
ADD = """(function (token) {
  document.getElementById('add-token').value = token;
  document.querySelector('#add-form button[type=submit]').click();
  return new Promise(function (resolve) {
    (function poll() {
      var text = document.getElementById('add-answer').textContent;
      if (text && text !== '\u2026') resolve([text, document.getElementById('add-answer').className]); else setTimeout(poll, 50);
    })();
  });
})(%r)"""


def check_add_form(tools, inertest, db, campaign_file):
    """A server with --allow-add: the list page's form sends a results.json with the token typed in and
    shows the campaign added (linked to its report); with a wrong token it shows the 403."""
    failures = []
    server = subprocess.Popen([inertest, "serve", "--db", db, "--port", "0", "--allow-add"], stdout=subprocess.PIPE,
                              text=True)
    try:
        url = re.search(r"(http://127\.0\.0\.1:\d+/)", server.stdout.readline()).group(1)
        token = server.stdout.readline().split()[-1]
        tools.open(url)
        document = tools.call("DOM.getDocument", session=True)["root"]["nodeId"]
        node = tools.call("DOM.querySelector", {"nodeId": document, "selector": "#add-file"}, session=True)["nodeId"]
        tools.call("DOM.setFileInputFiles", {"nodeId": node, "files": [campaign_file]}, session=True)
        text, verdict = tools.evaluate(ADD % ("0" * 32))
        if verdict != "fail" or not text.startswith("403: "):
            failures.append(f"add with a wrong token: {text!r} ({verdict})")
        # The browser logs the refused POST; that one is expected.
        tools.problems = [p for p in tools.problems if not ("status of 403" in p and p.endswith("/api/campaigns"))]
        text, verdict = tools.evaluate(ADD % token)
        link = tools.evaluate("(document.querySelector('#add-answer a') || {}).href || null")
        campaigns = json.load(urllib.request.urlopen(url + "api/campaigns"))["campaigns"]
        added = [c["id"] for c in campaigns if c["instrument"] == "FOG-4"]
        if verdict != "pass" or len(added) != 1 or link != f"{url}campaigns/{added[0]}":
            failures.append(f"add: {text!r} ({verdict}), link {link}, archived {added}")
        else:
            print(f"add through the page: {text}")
    finally:
        server.terminate()
        server.wait(timeout=30)
    return failures


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
        add_db = os.path.join(work, "add.sqlite")
        shutil.copy(db, add_db)
        fog4 = os.path.join(work, "fog4.json")
        with open(fog4, "w") as f:
            json.dump(scale_factor_campaign("FOG-4", "2026-03-04", 36000.1), f)

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
            if "<th>仪表编号</th>" not in dom or "合格</td>" not in dom or '<span id="shown">3 / 3</span>' not in dom:
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
            downloads = os.path.join(work, "downloads")
            os.makedirs(downloads)
            with tempfile.TemporaryDirectory(dir=work) as profile, DevTools(browser, profile) as tools:
                tools.allow_downloads(downloads)
                failures += check_history_page(tools, url)
                failures += check_allan_plot(tools, url, f"campaigns/{demo_id}", downloads)
                failures += check_add_form(tools, options.inertest, add_db, fog4)
                failures += [f"interactive plots: console: {p}" for p in tools.problems]
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

#!/usr/bin/env python3
"""Renders the demo campaign's test report in headless Chromium and checks it.

Runs `inertest demo --out WORK/demo` (English report) and `inertest run` on the demo's plan with
--lang zh, then for each report.html:
  * loads it in headless Chromium (--dump-dom, logging to stderr) and fails on any console message
    or failed load (the page has no script and no external resource, so there must be none);
  * checks every procedure section that has plots, and every <figure>, holds an <svg> whose drawing
    elements (polyline/path/circle/rect) are present and non-empty, with axis tick labels;
  * saves a screenshot (PNG) and prints the English report to PDF under the output directory.
Exits 77 (ctest SKIP) with a message when chromium is not installed.
"""
import argparse
import html.parser
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from chromium import chromium_command, console_problems, run_chromium  # noqa: E402

SKIP = 77
# Kinds whose section must show at least one plot when they are in the campaign.
PLOTTED_KINDS = {
    "scale_factor", "allan", "bias", "bandwidth", "bias_temperature", "scale_factor_temperature",
    "centrifuge", "gyro_misalignment", "accelerometer_misalignment", "bias_repeatability",
    "scale_factor_repeatability", "maximum_input_rate",
}


class ReportParser(html.parser.HTMLParser):
    """Collects the plots (each <svg> with the drawing elements inside it) and the sections."""

    def __init__(self):
        super().__init__()
        self.plots = []          # [{"section": kind, "elements": {tag: count}, "empty": n, "texts": n}]
        self.sections = []       # kinds of the procedure sections, in order
        self.section_plots = {}  # section index -> number of plots
        self.figures = 0
        self._svg = None
        self._section = None
        self._in_text = False
        self.scripts = 0
        self.external = []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "script":
            self.scripts += 1
        for key in ("src", "href"):
            value = a.get(key)
            if value and not value.startswith("#"):
                self.external.append(f"{tag} {key}={value}")
        if tag == "section" and "procedure" in (a.get("class") or "").split():
            self.sections.append(a.get("data-kind", ""))
            self._section = len(self.sections) - 1
            self.section_plots[self._section] = 0
        elif tag == "figure":
            self.figures += 1
        elif tag == "svg":
            self._svg = {"section": self._section, "elements": {}, "empty": 0, "texts": 0}
            if self._section is not None:
                self.section_plots[self._section] += 1
        elif self._svg is not None:
            self._svg["elements"][tag] = self._svg["elements"].get(tag, 0) + 1
            if tag == "polyline" and not a.get("points", "").strip():
                self._svg["empty"] += 1
            if tag == "path" and not a.get("d", "").strip():
                self._svg["empty"] += 1
            if tag == "text":
                self._in_text = True

    def handle_startendtag(self, tag, attrs):
        self.handle_starttag(tag, attrs)
        if tag == "svg":
            self.handle_endtag(tag)

    def handle_data(self, data):
        if self._svg is not None and self._in_text and data.strip():
            self._svg["texts"] += 1

    def handle_endtag(self, tag):
        if tag == "text":
            self._in_text = False
        elif tag == "svg" and self._svg is not None:
            self.plots.append(self._svg)
            self._svg = None
        elif tag == "section":
            self._section = None


def check_report(browser, report, label, work, failures):
    url = "file://" + os.path.abspath(report)
    with tempfile.TemporaryDirectory(dir=work) as profile:
        dom = run_chromium(browser, profile, ["--dump-dom"], url)
    if dom.returncode != 0 or "<html" not in dom.stdout:
        failures.append(f"{label}: chromium --dump-dom failed ({dom.returncode}): {dom.stderr[-2000:]}")
        return None
    for problem in console_problems(dom.stderr):
        failures.append(f"{label}: console: {problem}")

    parser = ReportParser()
    parser.feed(dom.stdout)
    if parser.scripts:
        failures.append(f"{label}: {parser.scripts} <script> element(s); the report must need no script")
    for ref in parser.external:
        failures.append(f"{label}: reference to an outside resource: {ref}")
    if not parser.plots:
        failures.append(f"{label}: no plot at all")
    for i, plot in enumerate(parser.plots):
        elements = plot["elements"]
        drawing = elements.get("polyline", 0) + elements.get("path", 0)
        marks = elements.get("circle", 0) + elements.get("rect", 0)
        where = parser.sections[plot["section"]] if plot["section"] is not None else "?"
        if drawing == 0:
            failures.append(f"{label}: plot {i + 1} ({where}) has no path or polyline: {elements}")
        if marks == 0:
            failures.append(f"{label}: plot {i + 1} ({where}) has no frame or marker: {elements}")
        if plot["empty"]:
            failures.append(f"{label}: plot {i + 1} ({where}) has {plot['empty']} empty path(s)")
        if plot["texts"] < 4:
            failures.append(f"{label}: plot {i + 1} ({where}) has {plot['texts']} labels; axes need tick labels")
    if parser.figures != len(parser.plots):
        failures.append(f"{label}: {parser.figures} <figure>s but {len(parser.plots)} plots")
    for index, kind in enumerate(parser.sections):
        if kind in PLOTTED_KINDS and parser.section_plots.get(index, 0) == 0:
            failures.append(f"{label}: section {index + 1} ({kind}) shows no plot")
    print(f"{label}: {len(parser.sections)} procedure sections ({', '.join(parser.sections)}), "
          f"{len(parser.plots)} plots")
    return url


def main():
    arguments = argparse.ArgumentParser(description=__doc__)
    arguments.add_argument("--inertest", required=True, help="the inertest executable")
    arguments.add_argument("--out", required=True, help="directory for the reports, screenshot and PDF")
    options = arguments.parse_args()

    browser = chromium_command()
    if browser is None:
        print("SKIP: chromium is not installed (apt-get install chromium; `make test` installs it)")
        return SKIP

    work = os.path.abspath(options.out)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    demo_dir = os.path.join(work, "demo")
    demo = subprocess.run([options.inertest, "demo", "--out", demo_dir, "--lang", "en"], capture_output=True,
                          text=True, timeout=900)
    english = os.path.join(demo_dir, "report.html")
    if demo.returncode not in (0, 1) or not os.path.exists(english):
        print(f"inertest demo failed ({demo.returncode}):\n{demo.stderr[-4000:]}")
        return 1
    chinese_dir = os.path.join(work, "zh")
    run = subprocess.run([options.inertest, "run", os.path.join(demo_dir, "lab", "plan.toml"), "--out", chinese_dir,
                          "--lang", "zh"], capture_output=True, text=True, timeout=900)
    chinese = os.path.join(chinese_dir, "report.html")
    if run.returncode != 0 or not os.path.exists(chinese):
        print(f"inertest run --lang zh failed ({run.returncode}):\n{run.stderr[-4000:]}")
        return 1

    failures = []
    # The console check must be able to fail: a page that logs an error has to show up in the log.
    probe = os.path.join(work, "console_probe.html")
    with open(probe, "w", encoding="utf-8") as page:
        page.write("<!DOCTYPE html><html><body><script>console.error('probe')</script></body></html>")
    with tempfile.TemporaryDirectory(dir=work) as profile:
        probed = run_chromium(browser, profile, ["--dump-dom"], "file://" + probe)
    if not any("probe" in line for line in console_problems(probed.stderr)):
        failures.append("chromium's log does not show console messages; the console check would see nothing")

    url = check_report(browser, english, "en", work, failures)
    check_report(browser, chinese, "zh", work, failures)
    with open(chinese, encoding="utf-8") as page:
        if "标度因数" not in page.read():
            failures.append("zh: the Chinese report lacks the GJB term 标度因数")

    if url:
        screenshot = os.path.join(work, "report.png")
        pdf = os.path.join(work, "report.pdf")
        with tempfile.TemporaryDirectory(dir=work) as profile:
            shot = run_chromium(browser, profile, ["--window-size=1100,6000", f"--screenshot={screenshot}"], url)
        with tempfile.TemporaryDirectory(dir=work) as profile:
            printed = run_chromium(browser, profile, [f"--print-to-pdf={pdf}", "--no-pdf-header-footer"], url)
        if shot.returncode != 0 or not os.path.exists(screenshot) or os.path.getsize(screenshot) < 10000:
            failures.append(f"screenshot failed ({shot.returncode}): {shot.stderr[-2000:]}")
        else:
            print(f"screenshot: {screenshot}")
        if printed.returncode != 0 or not os.path.exists(pdf):
            failures.append(f"print to PDF failed ({printed.returncode}): {printed.stderr[-2000:]}")
        else:
            with open(pdf, "rb") as document:
                pages = len(re.findall(rb"/Type\s*/Page[^s]", document.read()))
            print(f"pdf: {pdf} ({pages} pages)")
            if pages < 2:
                failures.append(f"the printed report has {pages} page(s); sections start on new pages")

    for failure in failures:
        print("FAIL:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

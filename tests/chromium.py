"""Headless Chromium for the browser tests (tests/report, tests/serve): finding it, running it on a
URL, and the console messages and failed loads in its log."""
import shutil
import subprocess


def chromium_command():
    """The browser's path, or None when none is installed (the tests then exit 77, ctest's SKIP)."""
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


def run_chromium(browser, profile, extra, url):
    """Runs headless Chromium on url with a fresh profile directory and the extra flags (--dump-dom,
    --screenshot=...), logging to stderr; returns the CompletedProcess."""
    command = [browser, "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
               "--disable-component-update", "--disable-sync", "--no-first-run", "--disable-extensions",
               "--disable-default-apps", "--hide-scrollbars", f"--user-data-dir={profile}",
               "--enable-logging=stderr", "--log-level=0", "--v=0"] + extra + [url]
    return subprocess.run(command, capture_output=True, text=True, timeout=180)


def console_problems(stderr):
    """Console messages and failed loads in Chromium's log (the dbus noise of a container is not)."""
    problems = []
    for line in stderr.splitlines():
        if "CONSOLE" in line or "Uncaught" in line or "Failed to load resource" in line or "net::ERR_" in line:
            problems.append(line.strip())
    return problems

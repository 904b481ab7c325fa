"""Headless Chromium for the browser tests (tests/report, tests/serve): finding it, running it on a
URL, and the console messages and failed loads in its log."""
import json
import os
import select
import shutil
import subprocess
import time


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


class DevTools:
    """Headless Chromium driven over the DevTools protocol on a pipe (--remote-debugging-pipe: the
    browser reads commands on fd 3 and answers on fd 4, each message JSON ending in a NUL byte).
    One page; its console messages, uncaught exceptions and failed loads gather in `problems`.
    Use as a context manager: the browser is closed on exit."""

    def __init__(self, browser, profile, width=1200, height=900, timeout=60):
        to_browser_read, self._write = os.pipe()
        self._read, from_browser_write = os.pipe()

        def wire():
            os.dup2(to_browser_read, 3)
            os.dup2(from_browser_write, 4)

        command = [browser, "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                   "--disable-component-update", "--disable-sync", "--no-first-run", "--disable-extensions",
                   "--disable-default-apps", "--hide-scrollbars", f"--user-data-dir={profile}",
                   f"--window-size={width},{height}", "--remote-debugging-pipe", "about:blank"]
        self._process = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                         stderr=subprocess.DEVNULL, pass_fds=(3, 4), preexec_fn=wire)
        os.close(to_browser_read)
        os.close(from_browser_write)
        self._timeout = timeout
        self._buffer = b""
        self._next_id = 0
        self._events = []
        self.problems = []
        targets = self.call("Target.getTargets")["targetInfos"]
        page = [t for t in targets if t["type"] == "page"][0]["targetId"]
        self._session = self.call("Target.attachToTarget", {"targetId": page, "flatten": True})["sessionId"]
        for domain in ("Page", "Runtime", "Log", "Network"):
            self.call(domain + ".enable", session=True)

    def __enter__(self):
        return self

    def __exit__(self, *exception):
        self.close()

    def close(self):
        try:
            self.call("Browser.close")
        except Exception:  # noqa: BLE001 - the browser may be gone already
            self._process.kill()
        self._process.wait(timeout=30)
        os.close(self._write)
        os.close(self._read)

    def _message(self, deadline):
        while b"\0" not in self._buffer:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([self._read], [], [], left)[0]:
                raise TimeoutError("no answer from chromium")
            chunk = os.read(self._read, 1 << 20)
            if not chunk:
                raise EOFError("chromium closed its pipe")
            self._buffer += chunk
        message, self._buffer = self._buffer.split(b"\0", 1)
        message = json.loads(message)
        if "method" in message:
            self._note(message)
        return message

    def _note(self, event):
        method, params = event["method"], event.get("params", {})
        if method == "Runtime.consoleAPICalled":
            text = " ".join(str(a.get("value", a.get("description", ""))) for a in params.get("args", []))
            self.problems.append(f"console.{params.get('type')}: {text}")
        elif method == "Runtime.exceptionThrown":
            details = params.get("exceptionDetails", {})
            self.problems.append("uncaught: " + details.get("exception", {}).get("description", details.get("text", "")))
        elif method == "Log.entryAdded":
            entry = params.get("entry", {})
            self.problems.append(f"log {entry.get('level')}: {entry.get('text')} {entry.get('url', '')}".strip())
        elif method == "Network.loadingFailed" and not params.get("canceled"):
            self.problems.append(f"failed load: {params.get('errorText')}")
        self._events.append(event)

    def call(self, method, params=None, session=False):
        """Sends one command (to the page when session) and returns its result; raises on an error."""
        self._next_id += 1
        message = {"id": self._next_id, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = self._session
        os.write(self._write, json.dumps(message).encode() + b"\0")
        deadline = time.monotonic() + self._timeout
        while True:
            answer = self._message(deadline)
            if answer.get("id") == self._next_id:
                if "error" in answer:
                    raise RuntimeError(f"{method}: {answer['error']}")
                return answer.get("result", {})

    def wait_for(self, method, deadline_seconds=None):
        """The first event of that method since the last wait (waiting for it if none came yet)."""
        deadline = time.monotonic() + (deadline_seconds or self._timeout)
        while True:
            for i, event in enumerate(self._events):
                if event["method"] == method:
                    del self._events[: i + 1]
                    return event.get("params", {})
            self._message(deadline)

    def open(self, url):
        """Loads url in the page and waits for its load event."""
        self._events.clear()
        self.call("Page.navigate", {"url": url}, session=True)
        self.wait_for("Page.loadEventFired")

    def evaluate(self, expression):
        """The value of a JavaScript expression in the page (JSON-able), promises awaited."""
        result = self.call("Runtime.evaluate", {"expression": expression, "returnByValue": True, "awaitPromise": True},
                           session=True)
        if "exceptionDetails" in result:
            raise RuntimeError(f"{expression}: {result['exceptionDetails']}")
        return result["result"].get("value")

    def mouse(self, kind, x, y, button="left"):
        """A mouse event at page pixel (x, y): kind pressed, released, moved or wheel (y down by 100)."""
        params = {"type": {"pressed": "mousePressed", "released": "mouseReleased", "moved": "mouseMoved",
                           "wheel": "mouseWheel"}[kind], "x": x, "y": y}
        if kind in ("pressed", "released"):
            params.update(button=button, clickCount=1)
        if kind == "moved":
            params["button"] = "none"
        if kind == "wheel":
            params.update(deltaX=0, deltaY=100)
        self.call("Input.dispatchMouseEvent", params, session=True)

    def allow_downloads(self, directory):
        """Files the page downloads go to directory (Browser.downloadProgress events tell when done)."""
        self.call("Browser.setDownloadBehavior", {"behavior": "allow", "downloadPath": directory, "eventsEnabled": True})

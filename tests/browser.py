"""A headless Chromium driven over its DevTools protocol, with the standard library only.

Chromium started with ``--remote-debugging-pipe`` reads protocol commands from its file
descriptor 3 and writes replies and events to 4, each a JSON message ended by a NUL byte;
no websocket, no port, no extra package (selenium or playwright would add a dependency
and a driver for what a hundred lines do). Used by tests/report/test_browser.py.
"""

from __future__ import annotations

import base64
import json
import os
import shutil
import subprocess
import tempfile
import time
from typing import Any

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-dev-shm-usage", "--hide-scrollbars", "--remote-debugging-pipe"]
NAMES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
TIMEOUT = 60.0  # [s] for one reply or event


def find() -> str | None:
    """The path of a Chromium here (CHROMIUM names one), or None."""
    given = os.environ.get("CHROMIUM")
    if given:
        return shutil.which(given) or (given if os.path.exists(given) else None)
    return next((path for path in map(shutil.which, NAMES) if path), None)


class Browser:
    """One headless Chromium with a fresh profile; ``page()`` opens a tab."""

    def __init__(self, executable: str, width: int = 1200, height: int = 900) -> None:
        self.profile = tempfile.mkdtemp(prefix="dyade-chromium-")
        to_child, self._write = os.pipe()
        self._read, from_child = os.pipe()

        def descriptors() -> None:  # in the child: the protocol on 3 (in) and 4 (out)
            source, sink = to_child, from_child
            if sink == 3:  # would be overwritten by the first dup2
                sink = os.dup(sink)
            for fd, wanted in ((source, 3), (sink, 4)):
                if fd != wanted:
                    os.dup2(fd, wanted)  # inheritable
                os.set_inheritable(wanted, True)

        self.process = subprocess.Popen(
            [executable, *FLAGS, f"--user-data-dir={self.profile}",
             f"--window-size={width},{height}", "about:blank"],
            close_fds=False, preexec_fn=descriptors,  # other descriptors: not inheritable
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_child)
        os.close(from_child)
        self._buffer = b""
        self._next = 0
        self.events: list[dict] = []

    def close(self) -> None:
        try:
            self.send("Browser.close")
        except (OSError, RuntimeError, TimeoutError):
            pass
        try:
            self.process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        for fd in (self._read, self._write):
            try:
                os.close(fd)
            except OSError:
                pass
        shutil.rmtree(self.profile, ignore_errors=True)

    def __enter__(self) -> "Browser":
        return self

    def __exit__(self, *_: object) -> None:
        self.close()

    # -- the protocol --------------------------------------------------------------
    def send(self, method: str, params: dict | None = None, session: str | None = None
             ) -> dict[str, Any]:
        """Send a command and wait for its reply (events meanwhile are kept)."""
        self._next += 1
        message = {"id": self._next, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        os.write(self._write, json.dumps(message).encode() + b"\0")
        while True:
            reply = self._receive()
            if reply.get("id") == self._next:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply.get("result", {})
            self.events.append(reply)

    def wait(self, method: str, session: str | None = None) -> dict:
        """The first event ``method`` (of ``session``) not yet waited for."""
        deadline = time.monotonic() + TIMEOUT
        while True:
            for k, event in enumerate(self.events):
                if event.get("method") == method and event.get("sessionId") == session:
                    return self.events.pop(k)
            if time.monotonic() > deadline:
                raise TimeoutError(f"no {method} within {TIMEOUT:g} s")
            self.events.append(self._receive())

    def _receive(self) -> dict:
        import select

        while b"\0" not in self._buffer:
            ready, _, _ = select.select([self._read], [], [], TIMEOUT)
            if not ready:
                raise TimeoutError(f"Chromium said nothing within {TIMEOUT:g} s")
            chunk = os.read(self._read, 1 << 20)
            if not chunk:
                raise RuntimeError("Chromium closed its protocol pipe")
            self._buffer += chunk
        message, self._buffer = self._buffer.split(b"\0", 1)
        return json.loads(message)

    def page(self) -> "Page":
        target = self.send("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = self.send("Target.attachToTarget", {"targetId": target,
                                                      "flatten": True})["sessionId"]
        return Page(self, session)


class Page:
    """A tab: load a URL, evaluate script, press keys, print and take screenshots; what
    the page logs and requests is kept."""

    def __init__(self, browser: Browser, session: str) -> None:
        self.browser, self.session = browser, session
        for domain in ("Page", "Runtime", "Log", "Network"):
            self.send(f"{domain}.enable")

    def send(self, method: str, params: dict | None = None) -> dict:
        return self.browser.send(method, params, self.session)

    def load(self, url: str) -> None:
        self.send("Page.navigate", {"url": url})
        self.browser.wait("Page.loadEventFired", self.session)

    def evaluate(self, expression: str) -> Any:
        reply = self.send("Runtime.evaluate", {"expression": expression,
                                               "returnByValue": True, "awaitPromise": True})
        if "exceptionDetails" in reply:
            raise RuntimeError(f"script failed: {reply['exceptionDetails']}")
        return reply["result"].get("value")

    def key(self, name: str, code: int) -> None:
        """Press and release a key (``name`` as in KeyboardEvent.key, ``code`` its
        Windows virtual key code) on the focused element."""
        for kind in ("rawKeyDown", "keyUp"):
            self.send("Input.dispatchKeyEvent", {"type": kind, "key": name, "code": name,
                                                 "windowsVirtualKeyCode": code})

    def pdf(self) -> bytes:
        return base64.b64decode(self.send("Page.printToPDF", {"printBackground": True})["data"])

    def screenshot(self, width: int = 1200) -> bytes:
        """The whole page as PNG, ``width`` [px] wide."""
        height = int(self.evaluate("document.documentElement.scrollHeight"))
        self.send("Emulation.setDeviceMetricsOverride", {"width": width, "height": height,
                                                         "deviceScaleFactor": 1,
                                                         "mobile": False})
        data = self.send("Page.captureScreenshot", {"format": "png",
                                                    "captureBeyondViewport": True})["data"]
        return base64.b64decode(data)

    def events(self, method: str) -> list[dict]:
        """The events ``method`` of this page received so far (kept)."""
        return [e for e in self.browser.events
                if e.get("method") == method and e.get("sessionId") == self.session]

    def errors(self) -> list[str]:
        """Console errors, uncaught exceptions and error log entries so far."""
        out = [str(e["params"]["args"]) for e in self.events("Runtime.consoleAPICalled")
               if e["params"]["type"] in ("error", "assert")]
        out += [str(e["params"]["exceptionDetails"]) for e in
                self.events("Runtime.exceptionThrown")]
        out += [e["params"]["entry"]["text"] for e in self.events("Log.entryAdded")
                if e["params"]["entry"]["level"] == "error"]
        return out

    def requests(self) -> list[str]:
        """Every URL the page asked for so far."""
        return [e["params"]["request"]["url"] for e in self.events("Network.requestWillBeSent")]

"""A headless Chromium driven over the DevTools protocol on a pipe (standard library
only): open a page, run script in it (move a slider, dispatch its ``input`` event), and
read values back from its DOM."""

from __future__ import annotations

import json
import os
import shutil
import subprocess

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


def _high(fd):
    import fcntl
    high = fcntl.fcntl(fd, fcntl.F_DUPFD, 10)
    os.close(fd)
    return high


class Browser:
    """``with Browser() as b: page = b.open(uri); b.evaluate(page, "1 + 1")``."""

    def __init__(self, timeout=60):
        self.timeout = timeout
        # (kept above 4, so that wiring them to 3 and 4 in the child clobbers nothing)
        to_browser, self._commands, self._replies, from_browser = (
            _high(fd) for fd in (*os.pipe(), *os.pipe()))

        def wire():                          # the protocol's pipe is fds 3 (in) and 4 (out)
            os.dup2(to_browser, 3)
            os.dup2(from_browser, 4)

        self.process = subprocess.Popen(
            [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
             "--disable-background-networking", "--disable-component-update",
             "--disable-sync", "--remote-debugging-pipe", "about:blank"],
            preexec_fn=wire, pass_fds=(3, 4), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_browser)
        os.close(from_browser)
        self._reader = os.fdopen(self._replies, "rb")
        self._next = 0
        self._buffer = b""
        self._events = []

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        try:
            self.call("Browser.close")
        except Exception:
            pass
        self.process.kill()
        self.process.wait(timeout=self.timeout)
        os.close(self._commands)
        self._reader.close()

    def _receive(self):
        while b"\0" not in self._buffer:
            chunk = os.read(self._replies, 1 << 16)
            if not chunk:
                raise RuntimeError("Chromium closed the protocol pipe")
            self._buffer += chunk
        raw, self._buffer = self._buffer.split(b"\0", 1)
        return json.loads(raw)

    def call(self, method, session=None, **params):
        self._next += 1
        message = {"id": self._next, "method": method, "params": params}
        if session:
            message["sessionId"] = session
        os.write(self._commands, json.dumps(message).encode() + b"\0")
        while True:
            reply = self._receive()
            if reply.get("id") == self._next:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply.get("result", {})
            if "method" in reply:
                self._events.append(reply)

    def wait_for(self, method, session):
        """The next event ``method`` of the session (kept ones first)."""
        while True:
            for event in self._events:
                if event["method"] == method and event.get("sessionId") == session:
                    self._events.remove(event)
                    return event
            self._events.append(self._receive())

    def open(self, uri):
        """A session on a new tab showing ``uri``, once its page has loaded."""
        target = self.call("Target.createTarget", url="about:blank")["targetId"]
        session = self.call("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
        self.call("Page.enable", session)
        self.call("Page.navigate", session, url=uri)
        self.wait_for("Page.loadEventFired", session)
        return session

    def evaluate(self, session, expression):
        """The value of a script expression in the page (a promise is awaited)."""
        result = self.call("Runtime.evaluate", session, expression=expression,
                           awaitPromise=True, returnByValue=True)
        if "exceptionDetails" in result:
            raise RuntimeError(f"script failed: {result['exceptionDetails']}")
        return result["result"].get("value")

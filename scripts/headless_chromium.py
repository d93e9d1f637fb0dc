#!/usr/bin/env python3
"""Headless Chromium for the tests that look at netlift's HTML pages (the
structural-reasoning report, the trace timing diagram) in a real browser.

Talks to Chromium over its DevTools pipe (--remote-debugging-pipe: JSON
messages separated by NUL bytes on file descriptors 3 and 4), so it needs
nothing beyond Python's standard library and Debian's chromium.
"""
import json
import os
import shutil
import subprocess
import tempfile
import time


class Browser:
    def __init__(self):
        self.profile = tempfile.mkdtemp()
        to_child_r, self.to_child = os.pipe()
        self.from_child, from_child_w = os.pipe()
        # fd 3: commands to Chromium, fd 4: its answers.
        def place_fds():
            os.dup2(to_child_r, 3)
            os.dup2(from_child_w, 4)
        self.proc = subprocess.Popen(
            ["chromium", "--headless", "--no-sandbox", "--disable-gpu",
             "--disable-quic", "--no-first-run",
             "--disable-background-networking", "--disable-component-update",
             "--disable-sync", "--disable-dev-shm-usage",
             "--remote-debugging-pipe",
             "--window-size=1200,1400", "--user-data-dir=" + self.profile,
             "about:blank"],
            preexec_fn=place_fds, pass_fds=(3, 4),
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_child_r)
        os.close(from_child_w)
        self.next_id = 0
        self.buffer = b""

    def call(self, method, params=None, session=None):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(self.to_child, json.dumps(msg).encode() + b"\0")
        deadline = time.time() + 30
        while time.time() < deadline:
            while b"\0" not in self.buffer:
                chunk = os.read(self.from_child, 65536)
                if not chunk:
                    raise RuntimeError("chromium closed its pipe")
                self.buffer += chunk
            raw, self.buffer = self.buffer.split(b"\0", 1)
            answer = json.loads(raw)
            if answer.get("id") == self.next_id:
                if "error" in answer:
                    raise RuntimeError(f"{method}: {answer['error']}")
                return answer["result"]
        raise RuntimeError(f"{method}: no answer")

    def close(self):
        try:
            self.call("Browser.close")
        except Exception:
            pass
        self.proc.wait(timeout=30)
        shutil.rmtree(self.profile, ignore_errors=True)



def open_page(browser, path):
    """Opens `path` in a new tab, waits until it has loaded, and returns a
    function evaluating a JavaScript expression there (its value back)."""
    target = browser.call("Target.createTarget",
                          {"url": "file://" + os.path.abspath(path)})
    session = browser.call("Target.attachToTarget",
                           {"targetId": target["targetId"],
                            "flatten": True})["sessionId"]

    def js(expr):
        r = browser.call("Runtime.evaluate",
                         {"expression": expr, "returnByValue": True}, session)
        return r["result"].get("value")

    # The new target starts blank, then loads the page.
    for _ in range(200):
        if (js("location.href") or "").startswith("file:") and \
                js("document.readyState") == "complete":
            break
        time.sleep(0.05)
    return session, js


def hover(browser, session, js, selector):
    """Moves the pointer to the middle of the first element matching
    `selector` and returns the #tooltip's text, '(hidden)' when it is not
    shown, or '(no element ...)'."""
    box = js(f"""(function() {{
        var el = document.querySelector({json.dumps(selector)});
        if (!el) return null;
        el.scrollIntoView({{block: 'center'}});
        var r = el.getBoundingClientRect();
        return [r.left + r.width / 2, r.top + r.height / 2];
    }})()""")
    if box is None:
        return f"(no element {selector})"
    browser.call("Input.dispatchMouseEvent",
                 {"type": "mouseMoved", "x": box[0], "y": box[1]}, session)
    return js("""(function() { var t = document.getElementById('tooltip');
        return t.style.display === 'block' ? t.textContent : '(hidden)'; })()""")


def screenshot(browser, session, path):
    import base64
    png = browser.call("Page.captureScreenshot", {"format": "png"}, session)
    with open(path, "wb") as f:
        f.write(base64.b64decode(png["data"]))
    return os.path.getsize(path) > 1000

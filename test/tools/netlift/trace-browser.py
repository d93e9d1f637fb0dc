#!/usr/bin/env python3
"""Loads an HTML trace (reach --trace-html) in headless Chromium, prints its
signal rows and step columns, moves the pointer onto a cell and onto a
step's header, prints the tooltips shown, and saves a screenshot.

usage: trace-browser.py TRACE.html SIGNAL STEP SCREENSHOT.png
"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "..", "..", "scripts"))
from headless_chromium import Browser, hover, open_page, screenshot  # noqa


def main():
    page, signal, step, shot = sys.argv[1:5]
    b = Browser()
    try:
        session, js = open_page(b, page)
        print("title:", js("document.querySelector('h1').textContent"))
        print("signals:", ", ".join(js(
            "Array.from(document.querySelectorAll('tr.signal th'))"
            ".map(function(t) { return t.textContent; })")))
        print("steps:", ", ".join(js(
            "Array.from(document.querySelectorAll('tr.taken td'))"
            ".map(function(t) { return t.textContent; })")))
        # The signal's cell in the step's column (the header's position).
        column = js(f"""Array.from(document.querySelectorAll('tr.taken td'))
            .findIndex(function(t) {{ return t.dataset.step === {json.dumps(step)}; }})""")
        print("cell tooltip:", hover(
            b, session, js,
            f"tr.signal[data-name={json.dumps(signal)}] td:nth-of-type({column + 1})"))
        print("step tooltip:", hover(
            b, session, js, f"tr.taken td[data-step={json.dumps(step)}]"))
        print("screenshot:", screenshot(b, session, shot))
    finally:
        b.close()


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Loads a structural-reasoning HTML report in headless Chromium, moves the
pointer onto an attribute-graph node and onto an Edwards-Venn region,
prints the tooltip text shown each time, and saves a screenshot.

usage: report-browser.py REPORT.html NODE_ID REGION_ID SCREENSHOT.png
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "..", "..", "scripts"))
from headless_chromium import Browser, hover, open_page, screenshot  # noqa


def main():
    report, node_id, region_id, shot = sys.argv[1:5]
    b = Browser()
    try:
        session, js = open_page(b, report)
        # A graph node: graphviz keeps the node's id on its <g>; its ellipse
        # is where the pointer goes.
        print("node tooltip:", hover(b, session, js, f"[id='{node_id}'] ellipse"))
        # A diagram region: the first piece of the group with that id.
        print("region tooltip:",
              hover(b, session, js, f"g.region[data-id='{region_id}'] path"))
        print("screenshot:", screenshot(b, session, shot))
    finally:
        b.close()


if __name__ == "__main__":
    main()

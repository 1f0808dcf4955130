#!/usr/bin/python3
"""Opens a case's report.html in a real browser (headless Chromium from Debian): the page loads,
every picture decodes (the page marks its body data-images="<decoded>/<all>" once loaded), and a
screenshot of its top is written beside the case folder to look at.

  report_in_browser.py CASE_FOLDER SCREENSHOT.png
"""
import os
import re
import shutil
import subprocess
import sys

folder, screenshot = sys.argv[1], sys.argv[2]
page = "file://" + os.path.abspath(os.path.join(folder, "report.html"))
browser = shutil.which("chromium")
if browser is None:
    sys.exit("report_in_browser: chromium is not installed (packages-tests.txt; ./test installs it)")
flags = ["--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
         "--virtual-time-budget=10000"]
dom = subprocess.run([browser, *flags, "--dump-dom", page], capture_output=True, text=True,
                     timeout=120)
if dom.returncode != 0:
    sys.exit(f"report_in_browser: chromium failed ({dom.returncode}): {dom.stderr[-2000:]}")
marks = re.findall(r'data-images="(\d+)/(\d+)"', dom.stdout)
pngs = [p for p in os.listdir(folder) if p.endswith(".png")]
if not marks:
    sys.exit("report_in_browser: the page did not finish loading (no data-images mark)")
decoded, shown = map(int, marks[0])
if shown != len(pngs) or decoded != shown:
    sys.exit(f"report_in_browser: {decoded} of {shown} images decoded; the folder has {len(pngs)}")
shot = subprocess.run([browser, *flags, "--window-size=1250,1700", f"--screenshot={screenshot}",
                       page], capture_output=True, text=True, timeout=120)
if shot.returncode != 0 or not os.path.getsize(screenshot) > 10000:
    sys.exit(f"report_in_browser: no screenshot ({shot.returncode}): {shot.stderr[-2000:]}")
print(f"report_in_browser: {decoded}/{shown} images decoded; screenshot {screenshot}")

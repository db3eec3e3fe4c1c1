#!/usr/bin/env python3
"""How long the viewer takes to switch frames on the simulator's uncapped map (about a million held
points), measured in the page with performance.now() from the request to the drawn frame (a pixel
read back, so the drawing has finished): stepping to the next frame (fetched ahead while the last
was shown) and jumping to a frame not fetched ahead, at each of several point budgets. Headless
Chromium draws WebGL in software (SwiftShader) on a machine without a GPU.

usage: scripts/viewer-frame-switch.py [--eco build/bin/eco] [--work build/viewer-switch] [--budgets 100000,...]
Prints a markdown table for docs/benchmarks.md."""

import argparse
import os
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests", "view"))
from browser import chromium, set_slider, wait_until  # noqa: E402
from view_server import ViewServer  # noqa: E402

FRAMES = 24
MEASURED = range(16, 24)  # frames with 0.95-1.06 M held points


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--eco", default="build/bin/eco")
    parser.add_argument("--work", default="build/viewer-switch")
    parser.add_argument("--budgets", default="100000,150000,250000,400000")
    args = parser.parse_args()
    eco = os.path.abspath(args.eco)
    run = os.path.join(args.work, "run")
    if not os.path.exists(os.path.join(run, "view", f"frame_{FRAMES - 1:06d}.bin")):
        subprocess.run([eco, "run", "--frames", str(FRAMES), "--record", "--out", run], check=True, stdout=subprocess.DEVNULL)
    held = {}
    with open(os.path.join(run, "view", "frames.csv")) as f:
        for line in f.read().splitlines()[1:]:
            cells = line.split(",")
            held[int(cells[0])] = int(cells[11])

    server = ViewServer([eco, "view", run, "--port", "0"])
    driver = chromium()
    rows = []
    try:
        for budget in [int(b) for b in args.budgets.split(",")]:
            driver.get(f"{server.url}?budget={budget}")
            wait_until(driver, "return ecoView.ready", "the first frame")
            driver.execute_script("document.getElementById('follow').checked = false")
            steps, jumps = [], []
            # jumps: back and forth across the run, never to a neighbour of the frame shown
            for target in [16, 23, 17, 22, 18, 21, 16, 23]:
                count = driver.execute_script("return ecoView.switches.length")
                set_slider(driver, target)
                wait_until(driver, f"return ecoView.frame === {target} && ecoView.switches.length > {count}", "a jump")
                jumps.append(driver.execute_script("return ecoView.switches[ecoView.switches.length - 1]"))
                time.sleep(0.6)  # what was fetched ahead lands, as it would while a user looks
            set_slider(driver, MEASURED[0])
            wait_until(driver, f"return ecoView.frame === {MEASURED[0]}", "the first measured frame")
            for target in list(MEASURED)[1:]:
                time.sleep(0.6)
                count = driver.execute_script("return ecoView.switches.length")
                driver.execute_script("document.getElementById('next').click()")
                wait_until(driver, f"return ecoView.frame === {target} && ecoView.switches.length > {count}", "a step")
                steps.append(driver.execute_script("return ecoView.switches[ecoView.switches.length - 1]"))
            for kind, switches in (("step", steps), ("jump", jumps)):
                ms = [s["ms"] for s in switches]
                fetch = [s["fetchMs"] for s in switches]
                rows.append((budget, kind, statistics.median(s["drawn"] for s in switches), statistics.median(ms),
                             max(ms), statistics.median(fetch)))
    finally:
        driver.quit()
        server.stop()

    print(f"Frames {MEASURED[0]}-{MEASURED[-1]} of `eco run --frames {FRAMES} --record` (simulator, defaults): "
          f"{min(held[t] for t in MEASURED):,}-{max(held[t] for t in MEASURED):,} held points.\n")
    print("| points drawn at most | drawn | step: median / max ms | jump: median / max ms | a jump's wait for the bytes |")
    print("|--:|--:|--:|--:|--:|")
    by_budget = {}
    for budget, kind, drawn, median, worst, fetch in rows:
        by_budget.setdefault(budget, {})[kind] = (drawn, median, worst, fetch)
    for budget, kinds in by_budget.items():
        step, jump = kinds["step"], kinds["jump"]
        print(f"| {budget:,} | {step[0]:,.0f} | {step[1]:.0f} / {step[2]:.0f} | {jump[1]:.0f} / {jump[2]:.0f} | {jump[3]:.0f} |")


if __name__ == "__main__":
    main()

"""eco view in headless Chromium, as a user sees it: the page opens on a small simulated run with no
console error and draws (pixels unlike the background); the slider taken to its end shows the last
frame with the held-point count eco run printed for it; play advances the frames; the voxel map
and each colouring change the drawn pixels; a damaged frame puts its file's name and byte in an
error line while the last good frame stays drawn; and on `eco run --view` the page's frame number
rises while the run computes. Saves the page as WORK_DIR/viewer.png (README's screenshot,
docs/images/viewer.png, is a copy).

usage: view_browser_test.py ECO_CLI WORK_DIR"""

import math
import os
import sys

from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "bench"))
from browser import chromium, console_errors, wait_until  # noqa: E402
from eco_command import check, eco, start  # noqa: E402
from view_server import ViewServer  # noqa: E402

CLI, WORK = start(sys.argv)
FRAMES = 8
done = eco("run", "--frames", str(FRAMES), "--record", "--out", "run", "--clearing.enabled", "true",
           "--attributes.intensity", "true", "--attributes.ids", "true")
printed_held = {}
for line in done.stdout.splitlines():
    cells = line.split()
    if len(cells) == 11 and cells[0].isdigit():
        printed_held[int(cells[0])] = int(cells[5])
check(sorted(printed_held) == list(range(FRAMES)), f"eco run's table:\n{done.stdout}")

driver = chromium()
server = ViewServer([CLI, "view", "run", "--port", "0"], cwd=WORK)
try:
    driver.get(server.url)
    wait_until(driver, "return ecoView.ready && !!ecoView.frameCount", "the first frame drawn")
    errors = console_errors(driver)
    check(not errors, f"console errors on opening: {errors}")
    pixels = driver.execute_script("return ecoView.pixels()")
    check(pixels["lit"] > 0.01 * pixels["width"] * pixels["height"], f"the canvas is blank: {pixels}")

    # the slider to its end: the last frame, with eco run's held count
    slider = driver.find_element(By.ID, "frame-slider")
    slider.send_keys(Keys.HOME)
    wait_until(driver, "return ecoView.frame === 0", "frame 0 after HOME")
    slider.send_keys(Keys.END)
    last = FRAMES - 1
    wait_until(driver, f"return ecoView.frame === {last}", "the last frame after END")
    shown = driver.find_element(By.ID, "held-count").text.replace(",", "")
    check(shown == str(printed_held[last]), f"panel says {shown} held at frame {last}, eco run printed {printed_held[last]}")
    check(driver.find_element(By.ID, "frame-number").text == str(last), "frame number")

    # the voxel map, and each colouring, change what is drawn
    before = driver.execute_script("return ecoView.pixels()")
    driver.find_element(By.ID, "show-voxels").click()
    wait_until(driver, "return ecoView.voxelsDrawn > 0", "the voxel map fetched")
    with_voxels = driver.execute_script("return ecoView.pixels()")
    check(with_voxels["sum"] != before["sum"] and with_voxels["lit"] > before["lit"],
          f"the voxel map changed nothing: {before} -> {with_voxels}")
    driver.find_element(By.ID, "show-voxels").click()
    check(driver.execute_script("return ecoView.pixels()")["sum"] == before["sum"], "voxels off: not as before")
    seen = {before["sum"]}
    for option in ["age", "intensity", "id"]:
        driver.find_element(By.CSS_SELECTOR, f"#color-by option[value={option}]").click()
        seen.add(driver.execute_script("return ecoView.pixels()")["sum"])
    check(len(seen) == 4, f"the four colourings drew {len(seen)} different pictures")
    driver.find_element(By.CSS_SELECTOR, "#color-by option[value=height]").click()

    # play from the first frame
    slider.send_keys(Keys.HOME)
    wait_until(driver, "return ecoView.frame === 0", "frame 0")
    driver.find_element(By.ID, "play").click()
    wait_until(driver, "return ecoView.frame >= 3", "play to advance three frames", timeout=120)
    driver.find_element(By.ID, "play").click()

    # the page as README shows it
    slider.send_keys(Keys.END)
    wait_until(driver, f"return ecoView.frame === {last}", "the last frame")
    driver.save_screenshot(os.path.join(WORK, "viewer.png"))
    errors = console_errors(driver)
    check(not errors, f"console errors: {errors}")

    # a damaged frame: an error line naming it; the canvas keeps the last good frame
    with open(os.path.join(WORK, "run", "view", "frame_000003.bin"), "r+b") as f:
        f.truncate(1000)
    driver.find_element(By.ID, "follow").click()  # off: stay where we go
    slider.send_keys(Keys.HOME)
    wait_until(driver, "return ecoView.frame === 0", "frame 0")
    for _ in range(3):
        slider.send_keys(Keys.ARROW_RIGHT)
    error = wait_until(driver, "return ecoView.error", "the damaged frame's error line")
    check(error.startswith("frame_000003.bin: byte ") and "the file ends" in error, f"error line: {error}")
    check(driver.find_element(By.ID, "error").is_displayed(), "the error line is hidden")
    pixels = driver.execute_script("return ecoView.pixels()")
    check(pixels["lit"] > 0.01 * pixels["width"] * pixels["height"], "blank canvas after a damaged frame")
    slider.send_keys(Keys.ARROW_RIGHT)
    wait_until(driver, "return ecoView.frame === 4 && !ecoView.error", "frame 4 clears the error line")
    check(not driver.find_element(By.ID, "error").is_displayed(), "the error line stays")
    errors = console_errors(driver)
    check(errors and all("frame?n=3" in e and "422" in e for e in errors), f"console, damaged frame: {errors}")
finally:
    server.stop()

# a region drawn as the map held it: a box turned with the heading (100 deg/s in place), 8 m ahead
eco("simulate", "--out", "spin", "--frames", "12", "--manoeuvre", "spin", "--spin-rate", "100", "--beams", "16",
    "--columns", "400")
eco("run", "--data", "spin", "--record", "--out", "region", "--region.shape", "oriented_box", "--region.ahead", "8",
    "--region.behind", "2", "--region.left", "3", "--region.right", "4", "--region.up", "2", "--region.down", "2")
server = ViewServer([CLI, "view", "region", "--port", "0"], cwd=WORK)
try:
    driver.get("about:blank")
    console_errors(driver)  # what the last page left
    driver.get(server.url)
    wait_until(driver, "return ecoView.ready && ecoView.frameCount === 12", "the region run's frames")
    slider = driver.find_element(By.ID, "frame-slider")
    slider.send_keys(Keys.END)
    wait_until(driver, "return ecoView.frame === 11", "the region run's last frame")
    drawn = driver.execute_script("return ecoView.region()")
    check(drawn["box"] and not drawn["cube"] and not drawn["ball"], f"the region is not the drawn shape: {drawn}")
    check(drawn["size"] == [10, 7, 4] and drawn["centre"] == [3, -0.5, 0], f"the box's extents: {drawn}")
    turn = drawn["turn"]  # column-major: the box's x axis is turn[0:3]
    check(abs(turn[2]) < 1e-6 and abs(turn[0] ** 2 + turn[1] ** 2 - 1) < 1e-6, f"a yaw box tilted: {turn}")
    heading = math.degrees(math.atan2(turn[1], turn[0]))
    check(abs(heading - 110.0) < 0.5, f"the box heads {heading} deg, the sensor 110 deg (1.1 s at 100 deg/s)")
    errors = console_errors(driver)
    check(not errors, f"console errors, region: {errors}")
finally:
    server.stop()

# live: the page follows eco run --view while it computes
live = ViewServer([CLI, "run", "--frames", "60", "--view", "--port", "0", "--pace", "0.25", "--out", "live"], cwd=WORK)
try:
    driver.get("about:blank")
    console_errors(driver)  # what the last page left
    driver.get(live.url)
    first = wait_until(driver, "return ecoView.ready && ecoView.frame >= 0 && ecoView.frame + 1", "the live page") - 1
    wait_until(driver, f"return ecoView.frame > {first} + 2", "the live frame number to rise", timeout=120)
    check(driver.find_element(By.ID, "follow").is_selected(), "the live page does not follow")
    check(live.alive(), "eco run --view ended early")
    errors = console_errors(driver)
    check(not errors, f"console errors, live: {errors}")
finally:
    live.stop()
    driver.quit()

print("ok")

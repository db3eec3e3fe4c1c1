"""Debian's Chromium, headless, driven by Selenium through Debian's chromedriver; WebGL drawn in
software (SwiftShader), as a machine without a GPU has it.

usage: driver = chromium(); wait_until(driver, "return ecoView.ready", "the first frame")"""

import time

from selenium import webdriver
from selenium.webdriver.chrome.service import Service


def chromium(width=1280, height=800):
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for flag in ["--headless=new", "--no-sandbox", "--disable-dev-shm-usage", f"--window-size={width},{height}",
                 "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist"]:
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)


def wait_until(driver, script, what, timeout=60.0):
    """Runs `script` until it returns something true; returns that. Fails naming `what`."""
    deadline = time.time() + timeout
    while time.time() < deadline:
        value = driver.execute_script(script)
        if value:
            return value
        time.sleep(0.05)
    state = driver.execute_script("return JSON.stringify(window.ecoView || null)")
    raise AssertionError(f"waited {timeout:.0f} s for {what}; ecoView: {state}")


def console_errors(driver):
    """The page's console messages at SEVERE level since the last call."""
    return [entry["message"] for entry in driver.get_log("browser") if entry["level"] == "SEVERE"]


def set_slider(driver, index):
    """Moves the frame slider to `index` as a user's drag ends there."""
    driver.execute_script(
        "const s = document.getElementById('frame-slider'); s.value = arguments[0];"
        "s.dispatchEvent(new Event('input'));", index)

"""``railvib explore`` in a real headless browser (the system Chromium, as test_report_browser).

The command runs as a user starts it (a subprocess, ``--port 0``, bound to 127.0.0.1);
Chromium (Debian's ``chromium`` and ``chromium-driver``, installed by ``.ci/run``) opens
the page: it must load without console errors and request nothing beyond the server;
moving the speed slider (arrow keys on its handle, as a keyboard user does) must change
the plotted PSD in the page; the Save button (a real click) must write the one case file
named with ``-o``, which ``railvib`` then loads as any case file, at the new speed.
Skipped, with the reason, where no browser, driver or Bokeh is installed.
"""

import os
import queue
import shutil
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from railvib.case import load_case

pytestmark = pytest.mark.slow  # a server, a run per change and a browser: 10-30 s

pytest.importorskip("bokeh", reason="the extra 'explore' (Bokeh) is not installed")
webdriver = pytest.importorskip("selenium.webdriver", reason="selenium is not installed")
from selenium.webdriver.chrome.service import Service  # noqa: E402
from selenium.webdriver.common.keys import Keys  # noqa: E402
from selenium.webdriver.support.ui import WebDriverWait  # noqa: E402

_CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
_DRIVER = shutil.which("chromedriver")
SRC = Path(__file__).resolve().parents[2] / "src"
CLI = "import sys; from railvib.cli.main import main; sys.exit(main(sys.argv[1:]))"

#: the first element matching a CSS selector, searched through Bokeh's shadow roots
_DEEP = """
function deep(root, selector) {
  const hit = root.querySelector(selector);
  if (hit) return hit;
  for (const el of root.querySelectorAll('*')) {
    if (el.shadowRoot) { const found = deep(el.shadowRoot, selector); if (found) return found; }
  }
  return null;
}
"""

_MODEL = "return Bokeh.documents[0].get_model_by_name(arguments[0])"


def _psd(browser):
    """The first response's plotted PSD values, as the page holds them."""
    return browser.execute_script(
        f"{_MODEL}.data['carbody.bounce'].slice(0, 2000).map(Number);", "psd_source"
    )


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    folder = tmp_path_factory.mktemp("explore")
    saved = folder / "saved.toml"
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join([str(SRC), os.environ.get("PYTHONPATH", "")]),
    }
    log = tmp_path_factory.mktemp("explore-log") / "stderr.txt"
    errors = log.open("w")
    proc = subprocess.Popen(
        [sys.executable, "-c", CLI, "explore", "--port", "0", "-o", str(saved)],
        cwd=folder,
        env=env,
        stdout=subprocess.PIPE,
        stderr=errors,
        text=True,
    )
    lines: queue.Queue[str] = queue.Queue()
    threading.Thread(target=lambda: [lines.put(x) for x in proc.stdout], daemon=True).start()
    try:
        line = lines.get(timeout=120)  # the first line gives the URL
    except queue.Empty:
        proc.kill()
        proc.wait()
        proc.stdout.close()
        errors.close()
        pytest.fail(f"railvib explore printed nothing: {log.read_text()}")
    url = line.split()[2]
    assert url.startswith("http://127.0.0.1:")  # this machine only, by default
    yield url, folder, saved
    proc.terminate()
    proc.wait(timeout=30)
    proc.stdout.close()
    errors.close()
    assert "Traceback" not in log.read_text()


@pytest.fixture(scope="module")
def browser(server):
    if _CHROMIUM is None or _DRIVER is None:
        pytest.skip("no Chromium and chromedriver on PATH (.ci/run installs them from apt)")
    options = webdriver.ChromeOptions()
    options.binary_location = _CHROMIUM
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"):
        options.add_argument(arg)
    options.add_argument("--window-size=1300,1400")
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(options=options, service=Service(_DRIVER))
    driver.set_page_load_timeout(120)
    driver.set_script_timeout(120)
    driver.get(server[0])
    WebDriverWait(driver, 120).until(
        lambda d: d.execute_script(
            "return window.Bokeh !== undefined && Bokeh.documents.length > 0 && "
            "Bokeh.documents[0].get_model_by_name('psd_source') !== null"
        )
    )
    yield driver
    driver.quit()


def test_the_page_loads_without_console_errors(server, browser):
    errors = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    assert not errors, errors
    host = server[0].rstrip("/")
    requests = browser.execute_script(
        "return performance.getEntriesByType('resource').map(r => r.name)"
    )
    assert all(r.startswith(host) or r.startswith("ws://127.0.0.1") for r in requests), requests
    assert len(_psd(browser)) == 2000  # the default case's grid, 9,996 frequencies, drawn
    assert "<td>carbody.pitch</td>" in _text(browser, "summary_table")
    assert "<td>rad/s^2</td>" in _text(browser, "summary_table")  # units from the attrs


def _text(browser, name):
    return browser.execute_script(f"{_MODEL}.text", name)


def _pad(browser):
    return browser.execute_script(
        f"{_MODEL}.data['storage'].slice(0, 50).map(Number);", "pad_source"
    )


def test_moving_the_speed_slider_changes_the_plotted_data(browser):
    before = _psd(browser)
    table = _text(browser, "summary_table")
    pad = _pad(browser)
    handle = browser.execute_script(
        f"{_DEEP} return deep(document, '.bk-Slider') && "
        "deep(deep(document, '.bk-Slider').shadowRoot, '.noUi-handle');"
    )
    assert handle is not None  # the speed slider is the first one on the page
    start = time.perf_counter()
    for _ in range(4):  # 4 steps of 5 km/h: 80 -> 100 km/h
        handle.send_keys(Keys.ARROW_RIGHT)
    WebDriverWait(browser, 60, poll_frequency=0.02).until(lambda d: _psd(d) != before)
    elapsed = time.perf_counter() - start
    assert browser.execute_script(f"{_MODEL}.value", "speed_kmh") == 100.0
    WebDriverWait(browser, 60).until(lambda d: _text(d, "summary_table") != table)
    # the last key's run (changes during a run are coalesced into one more): the title says it
    WebDriverWait(browser, 60).until(lambda d: "speed_kmh 100]" in _text(d, "status"))
    assert _pad(browser) == pad  # the pad does not depend on the speed
    print(f"slider to redrawn data: {elapsed:.2f} s")  # reported by -s; the goal is 0.3 s


def test_save_writes_a_valid_case_file_at_the_new_speed(server, browser):
    _, folder, saved = server
    before = {p.name for p in folder.iterdir()}
    button = browser.execute_script(f"{_DEEP} return deep(document, 'button.bk-btn-primary');")
    button.click()
    WebDriverWait(browser, 60).until(
        lambda d: d.execute_script(f"{_MODEL}.text", "saved").startswith("saved")
    )
    assert {p.name for p in folder.iterdir()} - before == {"saved.toml"} - before
    case = load_case(saved)  # validated as any case file
    assert case.speed_kmh == 100.0

"""The reproduce report opened in a real headless browser (the system Chromium).

``railvib reproduce`` writes report.html; Chromium (Debian's ``chromium`` and
``chromium-driver``, installed by ``.ci/run``) loads it from the file, offline: the page
must load with no console error, request nothing from the network, draw every interactive
figure (an SVG of nonzero size with its curves) and show every static PNG. Skipped, with
the reason, only where no browser or driver is installed.
"""

import shutil

import pytest
from click.testing import CliRunner

from railvib.cli.main import cli
from railvib.reproduce import FIGURES

pytestmark = pytest.mark.slow  # runs the study (~8 s) and a browser (~3 s)

webdriver = pytest.importorskip("selenium.webdriver", reason="selenium is not installed")
from selenium.webdriver.chrome.service import Service  # noqa: E402

_CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
_DRIVER = shutil.which("chromedriver")

_STATE = """
const plots = Array.from(document.querySelectorAll('.plot')).map(div => {
  const svg = div.querySelector('svg.main-svg');
  const paths = Array.from(div.querySelectorAll('.scatterlayer .trace path'));
  return {
    id: div.id,
    width: svg ? svg.getBoundingClientRect().width : 0,
    height: svg ? svg.getBoundingClientRect().height : 0,
    drawn: paths.filter(p => (p.getAttribute('d') || '').length > 10).length,
  };
});
const images = Array.from(document.images).map(i => [i.alt, i.complete, i.naturalWidth]);
const requests = performance.getEntriesByType('resource').map(r => r.name)
  .filter(name => !name.startsWith('data:'));
return {plots, images, requests, plotly: typeof Plotly};
"""


@pytest.fixture(scope="module")
def browser():
    if _CHROMIUM is None or _DRIVER is None:
        pytest.skip("no Chromium and chromedriver on PATH (.ci/run installs them from apt)")
    options = webdriver.ChromeOptions()
    options.binary_location = _CHROMIUM
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"):
        options.add_argument(arg)
    options.add_argument("--window-size=1400,1000")
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(options=options, service=Service(_DRIVER))
    driver.set_page_load_timeout(120)
    yield driver
    driver.quit()


@pytest.fixture(scope="module")
def page(tmp_path_factory, browser):
    out = tmp_path_factory.mktemp("reproduce-browser")
    result = CliRunner().invoke(cli, ["reproduce", "-o", str(out), "--quiet"])
    assert result.exit_code == 0, result.output
    browser.get((out / "report.html").as_uri())
    logs = browser.get_log("browser")
    return browser.execute_script(_STATE), logs


def test_the_page_loads_without_console_errors(page):
    _, logs = page
    errors = [e for e in logs if e["level"] == "SEVERE"]
    assert not errors, errors


def test_nothing_is_requested_from_the_network(page):
    state, _ = page
    assert state["plotly"] == "object"  # the inline library ran
    assert state["requests"] == []


def test_every_interactive_figure_renders(page):
    state, _ = page
    plots = state["plots"]
    assert len(plots) == len(FIGURES) + 3  # Figs. 9-16 (and 13-16 predicted), Figs. 6-8
    for plot in plots:
        assert plot["width"] > 300, plot
        assert plot["height"] > 200, plot
        assert plot["drawn"] >= 1, plot  # at least one curve drawn


def test_every_static_figure_is_shown(page):
    state, _ = page
    images = state["images"]
    assert len(images) == len(FIGURES) + 3
    for alt, complete, width in images:
        assert complete, alt
        assert width > 0, alt

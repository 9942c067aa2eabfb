"""``railvib explore`` refuses bad input in one line (exit 2, no traceback), before serving.

Each case asserts the exit code, one stderr line naming the field or file, no
"Traceback", and no file left that was not there before (the page's case file included).
"""

import json
import os
import socket
import subprocess
import sys
from pathlib import Path

import pytest

from railvib.cli.main import main
from railvib.explore.app import MISSING_EXTRA


def _refused(argv, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    before = set(tmp_path.iterdir())
    code = main(argv)
    err = capsys.readouterr().err
    assert code == 2
    assert len(err.strip().splitlines()) == 1, err
    assert "Traceback" not in err
    assert set(tmp_path.iterdir()) == before
    return err.strip()


def test_without_the_extra_one_line_says_how_to_install_it(tmp_path, monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "bokeh", None)  # `import bokeh` fails as if not installed
    err = _refused(["explore"], tmp_path, monkeypatch, capsys)
    assert err == f"error: {MISSING_EXTRA}"
    assert "pip install 'railvib[explore]'" in err


def test_a_missing_case_file_is_named(tmp_path, monkeypatch, capsys):
    # the extra is checked before the case is read: without it, the extra is named
    pytest.importorskip("bokeh", reason="the extra 'explore' (Bokeh) is not installed")
    err = _refused(["explore", "nothing.toml"], tmp_path, monkeypatch, capsys)
    assert "nothing.toml" in err


def test_a_bad_case_file_names_the_field(tmp_path, monkeypatch, capsys):
    # the extra is checked before the case is read: without it, the extra is named
    pytest.importorskip("bokeh", reason="the extra 'explore' (Bokeh) is not installed")
    bad = tmp_path / "bad.toml"
    bad.write_text('preset = "wang2017_metro"\n[vehicle]\ncarbody_mass = -1.0\n')
    err = _refused(["explore", str(bad)], tmp_path, monkeypatch, capsys)
    assert err == "error: vehicle.carbody_mass = -1.0: must be > 0.0 (kg)"


@pytest.mark.slow  # imports Bokeh: 1-2 s
def test_a_port_in_use_is_refused_in_one_line(tmp_path, monkeypatch, capsys):
    pytest.importorskip("bokeh", reason="the extra 'explore' (Bokeh) is not installed")
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        err = _refused(["explore", "--port", str(port)], tmp_path, monkeypatch, capsys)
    assert err.startswith(f"error: --port = {port}: cannot listen on 127.0.0.1:{port}")


def test_a_port_out_of_range_is_a_usage_error(tmp_path, monkeypatch, capsys):
    err = _refused(["explore", "--port", "70000"], tmp_path, monkeypatch, capsys)
    assert "--port" in err


@pytest.mark.slow  # imports Bokeh: 1-2 s
def test_a_host_that_is_no_address_is_named(tmp_path, monkeypatch, capsys):
    pytest.importorskip("bokeh", reason="the extra 'explore' (Bokeh) is not installed")
    err = _refused(["explore", "--host", "no-such-host.invalid"], tmp_path, monkeypatch, capsys)
    assert err.startswith("error: --host = 'no-such-host.invalid': an address of this machine")


def test_help_loads_neither_bokeh_nor_the_numerical_stack():
    src = Path(__file__).resolve().parents[2] / "src"
    code = (
        "import json, sys\nfrom railvib.cli.main import main\n"
        "assert main(['explore', '--help']) == 0\n"
        "print(json.dumps([m for m in ('bokeh', 'numpy', 'xarray') if m in sys.modules]))"
    )
    env = {
        **os.environ,
        "PYTHONPATH": os.pathsep.join([str(src), os.environ.get("PYTHONPATH", "")]),
    }
    out = subprocess.run(
        [sys.executable, "-c", code], env=env, check=True, capture_output=True, text=True
    ).stdout
    assert "CASE_FILE" in out
    assert json.loads(out.strip().splitlines()[-1]) == []

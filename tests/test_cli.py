import json
import subprocess
import sys

import numpy as np
import pytest

from wavephys import checks, cli
from wavephys.validate import compare


def test_validate_writes_json_and_passes(tmp_path, capsys):
    out = tmp_path / "v.json"
    code = cli.main(["validate", "--only", "dispersion limits", "Hermite frames", "--json", str(out)])
    assert code == 0
    rows = json.loads(out.read_text())
    assert rows and all(r["ok"] for r in rows)
    assert {"quantity", "expected", "measured", "error", "tolerance", "ok"} <= set(rows[0])
    captured = capsys.readouterr()
    assert "quantity" in captured.out and "[1/2] dispersion limits" in captured.err


def test_validate_exit_code_on_failure(monkeypatch, capsys):
    monkeypatch.setitem(checks.CHECKS, "broken", lambda: [compare("always wrong", 1.0, 2.0, rtol=0.01)])
    assert cli.main(["validate", "--only", "broken"]) == 1
    assert "FAIL" in capsys.readouterr().out


def test_unknown_check(capsys):
    assert cli.main(["validate", "--only", "nope"]) == 2


def test_run_default_scene(tmp_path):
    assert cli.main(["run", "--n", "128", "--steps", "4", "--out", str(tmp_path)]) == 0
    data = np.load(tmp_path / "surface.npz")
    assert data["eta"].shape == (128, 128) and np.isfinite(data["eta"]).all() and np.abs(data["eta"]).max() > 0
    assert (tmp_path / "surface.png").stat().st_size > 1000


def test_console_script_installed():
    out = subprocess.run([sys.executable, "-m", "wavephys.cli", "--help"], capture_output=True, text=True)
    assert out.returncode == 0 and "validate" in out.stdout


@pytest.mark.slow
def test_full_validation_passes(tmp_path):
    """Every row of `wavephys validate` is ok (the issue's acceptance run)."""
    out = tmp_path / "all.json"
    assert cli.main(["validate", "--json", str(out)]) == 0
    assert all(r["ok"] for r in json.loads(out.read_text()))


def test_run_rejects_small_grid(tmp_path):
    with pytest.raises(ValueError, match="n must be"):
        cli.main(["run", "--n", "64", "--out", str(tmp_path)])

"""``wavephys report``: one self-contained HTML page, opened in a real headless browser."""

from __future__ import annotations

import os
import re
import shutil
import subprocess

import pytest

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    from wavephys.app.cli import main

    out = tmp_path_factory.mktemp("report")
    assert main(["report", "--out", str(out), "--checks", "fresnel", "--quick"]) == 0
    return out / "report.html"


@pytest.mark.slow
def test_report_is_one_self_contained_page(report):
    text = report.read_text(encoding="utf-8")
    for section in ("Validation", "Wake pattern", "Ring waves", "Bench", "Model cards", "Rendered frames"):
        assert f"<h2>{section}" in text
    assert re.search(r"\d+ of \d+ rows pass", text) and "pass" in text
    # nothing is fetched: no external sources or links to other files
    assert not re.search(r'(src|href)="(?!data:)', text)
    assert text.count("<img") >= 5


@pytest.mark.skipif(CHROMIUM is None and not os.environ.get("CI"), reason="Chromium is not installed "
                    "(.ci/run installs it: apt-get install chromium)")
@pytest.mark.slow
def test_report_loads_in_headless_chromium_without_errors_and_shows_its_images(report, tmp_path):
    assert CHROMIUM is not None, "CI must have Chromium (.ci/run installs it)"
    r = subprocess.run([CHROMIUM, "--headless=new", "--no-sandbox", "--disable-gpu", f"--user-data-dir={tmp_path}",
                        "--virtual-time-budget=15000", "--dump-dom", report.as_uri()],
                       capture_output=True, text=True, timeout=300)
    body = re.search(r"<body[^>]*>", r.stdout)
    assert body, r.stderr[-2000:]
    attrs = dict(re.findall(r'data-([a-z-]+)="([^"]*)"', body.group(0)))
    assert int(attrs["images"]) >= 5
    assert attrs["images-loaded"] == attrs["images"], attrs
    assert attrs["errors"] == "0", attrs


@pytest.mark.parametrize("args,words", [
    (["--checks", "no-such-check"], ["no-such-check", "--list"]),
    (["--validation", "missing.json"], ["--validation", "not a file"]),
])
def test_report_bad_input_is_a_usage_error(capsys, tmp_path, args, words):
    from wavephys.app.cli import main

    with pytest.raises(SystemExit) as info:
        main(["report", "--out", str(tmp_path / "r"), *args])
    assert info.value.code == 2
    err = capsys.readouterr().err
    for w in words:
        assert w in err


def test_ctrl_c_writes_the_sections_finished_and_says_what_is_missing(monkeypatch, tmp_path, capsys):
    """Ctrl-C while the wake section is built: exit 130 and one line (no traceback); the page holds the
    validation section (its rows printed as they finished) and names the sections missing."""
    import wavephys.app.report as report
    from wavephys.app.cli import main

    def stop(quick, say):
        raise KeyboardInterrupt

    monkeypatch.setattr(report, "_wake", stop)
    assert main(["report", "--out", str(tmp_path), "--checks", "fresnel", "--quick"]) == 130
    err = capsys.readouterr().err
    assert "Traceback" not in err and "ok  " in err
    assert err.strip().splitlines()[-1].startswith("wavephys report: interrupted (Ctrl-C) while building Wake pattern")
    page = (tmp_path / "report.html").read_text()
    assert "<h2>Validation</h2>" in page and "<h2>Ring waves</h2>" not in page
    assert "missing Wake pattern, Ring waves, Bench" in page
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report.html"]

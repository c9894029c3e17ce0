import json
import subprocess
import sys

import numpy as np
import pytest

import wavephys.checks
from wavephys.app import cli
from wavephys.harness import compare


def test_validate_writes_json_and_passes(tmp_path, capsys):
    out = tmp_path / "v.json"
    code = cli.main(["validate", "--only", "dispersion-limits", "hermite-frames", "--json", str(out)])
    assert code == 0
    rows = json.loads(out.read_text())
    assert rows and all(r["ok"] for r in rows)
    assert {"quantity", "expected", "measured", "error", "tolerance", "ok"} <= set(rows[0])
    captured = capsys.readouterr()
    assert "quantity" in captured.out and "[1/2] dispersion-limits" in captured.err


def test_validate_exit_code_on_failure(monkeypatch, capsys):
    monkeypatch.setitem(wavephys.checks.CHECKS, "broken", lambda: [compare("always wrong", 1.0, 2.0, rtol=0.01)])
    assert cli.main(["validate", "--only", "broken"]) == 1
    assert "FAIL" in capsys.readouterr().out


def test_validate_streams_rows_and_keeps_them_on_ctrl_c(monkeypatch, tmp_path, capsys):
    """Each check's rows are printed as it finishes; Ctrl-C during the second check: exit 130, one line saying
    so (no traceback), the first check's rows in the table and in --json (written whole, atomically)."""
    def interrupted():
        raise KeyboardInterrupt

    monkeypatch.setitem(wavephys.checks.CHECKS, "first", lambda: [compare("one quantity", 1.0, 1.0, rtol=0.01),
                                                                 compare("another", 2.0, 2.0, rtol=0.01)])
    monkeypatch.setitem(wavephys.checks.CHECKS, "second", interrupted)
    out = tmp_path / "v.json"
    assert cli.main(["validate", "--only", "first", "second", "--json", str(out)]) == 130
    captured = capsys.readouterr()
    assert "ok    one quantity: 1" in captured.err and "Traceback" not in captured.err
    last = captured.err.strip().splitlines()[-1]
    assert last.startswith("wavephys validate: interrupted (Ctrl-C) after 1 of 2 checks; their 2 rows") and str(out) in last
    assert [r["quantity"] for r in json.loads(out.read_text())] == ["one quantity", "another"]
    assert "one quantity" in captured.out and sorted(p.name for p in tmp_path.iterdir()) == ["v.json"]


def test_validate_leaves_the_long_checks_to_all(monkeypatch, capsys):
    """By default every check group but registry.LONG_CHECKS (measured: 46 s on a 2-core CPU, against 264 s for
    all); --all runs them too; --list marks them; --all with --only is a usage error."""
    from wavephys.app.registry import LONG_CHECKS, registry

    ran = []
    fake = {name: (lambda name=name: ran.append(name) or [compare(name, 1.0, 1.0, rtol=0.01)]) for name in registry()}
    monkeypatch.setattr(wavephys.checks, "CHECKS", {n: f for n, f in fake.items() if n in wavephys.checks.CHECKS})
    import optics.checks

    monkeypatch.setattr(optics.checks, "CHECKS", {n: f for n, f in fake.items() if n in optics.checks.CHECKS})
    monkeypatch.setattr("wavephys.app.registry.check_builtin_scenes", fake["builtin-scenes"])
    assert cli.main(["validate"]) == 0
    assert ran and not set(ran) & set(LONG_CHECKS) and set(LONG_CHECKS) <= set(registry())
    ran.clear()
    assert cli.main(["validate", "--all"]) == 0
    assert set(LONG_CHECKS) <= set(ran)
    capsys.readouterr()
    assert cli.main(["validate", "--list"]) == 0
    listed = capsys.readouterr().out.splitlines()
    assert all((" long " in line) == (line.split()[0] in LONG_CHECKS) for line in listed)
    err = _usage_error(["validate", "--all", "--only", "fresnel"], capsys)
    assert "--all and --only" in err


def test_a_reader_that_goes_away_is_no_error(monkeypatch):
    """`wavephys validate --list | head -1`: when the reader has gone, the command stops quietly (exit 0, no
    BrokenPipe traceback). Here stdout is a pipe whose reading end is closed, so every write fails."""
    import os

    read, write = os.pipe()
    os.close(read)
    with os.fdopen(write, "w") as closed:
        monkeypatch.setattr(sys, "stdout", closed)
        assert cli.main(["validate", "--list"]) == 0


def test_every_commands_help_gives_its_own_exit_codes():
    """One table (cli.COMMANDS) writes each subcommand's help and exit codes: none says 'validation row' but
    validate, plan's code 1 once, render and textures describe themselves."""
    parser = cli.build_parser()
    sub = next(a for a in parser._actions if isinstance(a, type(parser._subparsers._group_actions[0])))
    assert set(sub.choices) == set(cli.COMMANDS)
    for name, p in sub.choices.items():
        text = p.format_help()
        assert "exit status:" in text and p.description, name
        codes = [line.split()[0] for line in text.split("exit status:")[1].splitlines() if line.strip()[:1].isdigit()]
        assert codes == [str(c) for c, _ in cli.COMMANDS[name].codes], (name, codes)
        assert ("validation row" in text.split("exit status:")[1]) == (name == "validate"), name
    assert "wavephys check FRAMES" in parser.format_help()


def _usage_error(argv, capsys):
    """A usage error: exit status 2 and one line on stderr naming the problem."""
    with pytest.raises(SystemExit) as exc:
        cli.main(argv)
    assert exc.value.code == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    return err


def test_unknown_check(capsys):
    assert "nope" in _usage_error(["validate", "--only", "nope"], capsys)


def test_run_default_scene(tmp_path):
    assert cli.main(["run", "--n", "128", "--steps", "4", "--out", str(tmp_path)]) == 0
    data = np.load(tmp_path / "surface.npz")
    assert data["eta"].shape == (128, 128) and np.isfinite(data["eta"]).all() and np.abs(data["eta"]).max() > 0
    assert (tmp_path / "surface.png").stat().st_size > 1000


def test_console_script_installed():
    out = subprocess.run([sys.executable, "-m", "wavephys", "--help"], capture_output=True, text=True)
    assert out.returncode == 0 and "validate" in out.stdout


def test_run_rejects_small_grid(tmp_path, capsys):
    assert "--n" in _usage_error(["run", "--n", "64", "--out", str(tmp_path)], capsys)


def test_render_writes_a_png(tmp_path, capsys):
    from PIL import Image

    out = tmp_path / "frame.png"
    assert cli.main(["render", "--scene", "pool", "--out", str(out), "--width", "80", "--height", "60",
                     "--n", "64"]) == 0
    img = np.asarray(Image.open(out))
    assert img.shape == (60, 80, 3) and img.std() > 5  # not a blank frame
    said = capsys.readouterr()
    assert "rendered pool" in said.out and "drawn" in said.out  # each phase timed
    assert "building its water" in said.err and "built in" in said.err and "drawing" in said.err


def test_render_frames_and_effects(tmp_path):
    assert cli.main(["render", "--scene", "shore", "--out", str(tmp_path / "anim"), "--frames", "2", "--width", "40",
                     "--height", "30", "--n", "64", "--off", "caustics", "reflection"]) == 0
    assert sorted(p.name for p in (tmp_path / "anim").iterdir()) == ["frame_0000.png", "frame_0001.png"]


def test_render_without_egl_says_which_packages(tmp_path, monkeypatch, capsys):
    import moderngl

    monkeypatch.setattr(moderngl, "create_context", lambda *a, **k: (_ for _ in ()).throw(OSError("no EGL")))
    assert cli.main(["render", "--out", str(tmp_path / "f.png"), "--width", "8", "--height", "8"]) == 3
    assert "libegl1 libegl-mesa0 libgl1-mesa-dri" in capsys.readouterr().err


def test_textures_export(tmp_path):
    from optics.rendering.textures import load_npz
    from wavephys.app.scenes import builtin_scene

    assert cli.main(["textures", "--scene", "pool", "--out", str(tmp_path), "--n", "64"]) == 0
    names = {p.name for p in tmp_path.iterdir()}
    assert {"water_height.png", "water_height.json", "ground_height.png", "water_normals.png", "caustics.png",
            "fresnel.npy", "absorption.npy", "textures.npz"} <= names
    tex = load_npz(tmp_path / "textures.npz")
    scene = builtin_scene("pool", n=64)
    span = float(np.ptp(scene.water))
    assert np.abs(tex["water"] - scene.water).max() <= span / 65535 + 1e-7  # 16-bit normalized, decoded in m
    assert tex["fresnel"].shape == (256,) and tex["absorption"].shape == (256, 3)


def test_validate_table_fits_100_columns_and_shows_margins():
    """Long quantities wrap; bounds and agreements both show the margin left (negative: failed)."""
    from wavephys.harness.checks import bound, compare

    rows = [compare("a quantity whose description is much longer than the column it is given, with conditions",
                    1.0, 1.02, rtol=0.01), bound("a bound", 3.0, 2.0), bound("a lower bound", 5.0, 2.0, relation=">=")]
    table = cli._table(rows, width=100)
    assert max(len(line) for line in table.splitlines()) <= 100
    body = table.splitlines()[2:]
    assert "FAIL" in body[0] and "-0.0096" in body[0]  # 0.01 - |1/1.02 - 1|
    assert any(line.startswith("a bound") and "<= 2" in line and "-1" in line and "FAIL" in line for line in body)
    assert any(line.startswith("a lower bound") and ">= 2" in line and "3" in line and "ok" in line for line in body)


def test_progress_in_a_log_is_plain_lines(capsys):
    """Not on a terminal, progress is whole lines (never carriage returns piling up)."""
    import io

    from wavephys.core.progress import Progress

    log = io.StringIO()
    with Progress(5, "frames", stream=log, every=0.0) as p:
        for _ in range(5):
            p.update()
    lines = log.getvalue().splitlines()
    assert "\r" not in log.getvalue() and len(lines) == 5 and lines[-1].startswith("5/5 frames")
    quiet = io.StringIO()
    with Progress(5, "frames", stream=quiet) as p:  # every 5 s: the first and the last line in a fast run
        for _ in range(5):
            p.update()
    first, last = quiet.getvalue().splitlines()
    assert first.startswith("1/5 frames") and last.startswith("5/5 frames")


@pytest.mark.parametrize("argv", [
    ["validate", "--json", "{tmp}/missing/table.json"],   # the folder is not created for you
    ["validate", "--json", "{tmp}/table.txt"],            # not a .json file
    ["render", "--out", "{tmp}/missing/frame.png"],
    ["render", "--out", "{tmp}/frame.jpg"],
    ["render", "--frames", "3", "--out", "{tmp}/missing/deeper/frames"],
    ["textures", "--out", "{tmp}/missing/deeper"],
    ["run", "--out", "{tmp}/missing/deeper"],
    ["render", "--width", "0"], ["render", "--fps", "nan"], ["run", "--steps", "0"], ["run", "--n", "10"],
])
def test_bad_paths_and_options_fail_fast_with_one_line(argv, tmp_path, capsys, monkeypatch):
    """Usage errors (exit 2, one line) before any work starts, and nothing is written."""
    import time

    monkeypatch.chdir(tmp_path)
    argv = [a.format(tmp=tmp_path) for a in argv]
    start = time.perf_counter()
    message = _usage_error(argv, capsys)
    assert time.perf_counter() - start < 2.0, "the check came after the work"
    assert message.startswith("wavephys")
    assert list(tmp_path.iterdir()) == []


def test_written_files_have_the_usual_mode(tmp_path):
    """Atomic writes go through a private temporary file; the result gets the mode any new file
    gets (0666 less the umask), not 0600."""
    import os

    from wavephys.core.files import atomic_path

    with atomic_path(tmp_path / "a.txt") as tmp:
        tmp.write_text("x")
    plain = tmp_path / "b.txt"
    plain.write_text("x")
    assert (tmp_path / "a.txt").stat().st_mode & 0o777 == plain.stat().st_mode & 0o777
    assert not [p for p in os.listdir(tmp_path) if p.endswith(".part")]

"""The documented examples run as written: the README's pytest example and the guide's
worked example (docs/harness.md), whose explanation of the failure is checked."""

import re

import numpy as np
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _python_blocks(text):
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


def test_readme_pytest_example_runs_as_written(pytester):
    readme = (ROOT / "README.md").read_text()
    section = readme.split("## Check your own simulator from pytest", 1)[1].split("\n## ", 1)[0]
    (block,) = _python_blocks(section)
    pytester.makepyfile(test_readme_example=block)
    result = pytester.runpytest_subprocess("-q")  # a fresh process: the installed plugin, as a user has it
    result.assert_outcomes(passed=1)


def test_guide_worked_example_explains_the_failure(capsys):
    guide = (ROOT / "docs" / "harness.md").read_text()
    section = guide.split("## A worked example", 1)[1]
    namespace = {}
    exec(compile(_python_blocks(section)[0], "docs/harness.md", "exec"), namespace)
    row = namespace["row"]
    assert not row.ok
    assert "non-dispersive" in row.note and "band k = " in row.note and "worst at k" in row.note
    printed = capsys.readouterr().out
    assert printed.strip() == row.report()
    measured = float(re.search(r"measured ([0-9.]+), error", printed).group(1))
    assert f"measured {measured:g}" in guide.replace("\n", " ")  # the guide shows what it prints


def test_validation_doc_surfaces_example_runs_as_written(capsys):
    doc = (ROOT / "docs" / "validation.md").read_text()
    section = doc.split("## Cheap surface models, measured", 1)[1].split("\n## ", 1)[0]
    (block,) = _python_blocks(section)
    namespace = {}
    exec(compile(block, "docs/validation.md", "exec"), namespace)
    printed = capsys.readouterr().out
    assert "fold at lambda = " in printed
    assert 0.01 < float(namespace["foam"].mean()) < 0.1  # some foam, on the steepest crests
    assert namespace["eta"].shape == (128, 128)


def test_guide_shader_example_runs_as_written(pytester, tmp_path, capsys):
    """The shader section's test passes as written; its command prints the failure the guide shows."""
    from wavephys.app.cli import main

    guide = (ROOT / "docs" / "harness.md").read_text()
    section = guide.split("## Check your shaders", 1)[1]
    (block,) = _python_blocks(section)[:1]
    pytester.makepyfile(test_guide_shader=block)
    pytester.runpytest_subprocess("-q", "-p", "no:cacheprovider").assert_outcomes(passed=1)
    capsys.readouterr()
    namespace = {}
    exec(compile(block, "docs/harness.md", "exec"), namespace)
    (tmp_path / "water.glsl").write_text(namespace["SCHLICK"])
    command = re.search(r"```bash\n(wavephys check .*?)```", section, flags=re.S).group(1)
    argv = command.replace("\\\n", " ").split()[1:]
    argv = [str(tmp_path / a) if a in ("water.glsl", "fresnel.png") else a for a in argv]
    assert main(argv) == 1
    printed = capsys.readouterr().out
    shown = re.search(r"```\n(float fresnelSchlick.*?)```", section, flags=re.S).group(1)
    assert printed.splitlines()[0] == shown.splitlines()[0]
    assert shown.strip().splitlines()[-1] in printed.splitlines()  # the cause line
    assert (tmp_path / "fresnel.png").stat().st_size > 1000


def test_readme_wake_and_step_examples_run_as_written(tmp_path, monkeypatch, capsys):
    readme = (ROOT / "README.md").read_text()
    monkeypatch.chdir(tmp_path)
    for title in ("## Plot wakes and ring waves", "## The pure step"):
        (block,) = _python_blocks(readme.split(title, 1)[1].split("\n## ", 1)[0])
        namespace = {}
        exec(compile(block, "README.md", "exec"), namespace)
        if "edge" in namespace:
            assert abs(namespace["edge"].angle - 19.47) < max(1.0, 2 * namespace["edge"].uncertainty)
            assert (tmp_path / "wake.png").stat().st_size > 10_000
        else:
            assert namespace["etas"].shape == (4, 256, 256)


def test_guide_folder_of_exr_example_and_command_run_as_written(tmp_path, monkeypatch, capsys):
    """The guide's engine-style EXR export is checked as written (every row ok), and its command runs on it."""
    import shlex

    from wavephys.app.cli import main

    guide = (ROOT / "docs" / "harness.md").read_text()
    section = guide.split("## Check a folder of frames", 1)[1].split("\n## ", 1)[0]
    monkeypatch.chdir(tmp_path)
    namespace = {}
    exec(compile(_python_blocks(section)[0], "docs/harness.md", "exec"), namespace)
    report = namespace["report"]
    assert report.ok and set(report.rows) == {"dispersion", "energy", "tiling", "quantization", "standing",
                                              "direction"}, report.report()
    assert capsys.readouterr().out.strip() == report.report()
    (command,) = re.findall(r"```bash\n(wavephys check [^\n]*)\n```", section)
    assert main(shlex.split(command)[1:]) == 0
    assert (tmp_path / "checks.xml").is_file()


def test_readme_frames_command_runs_as_written(tmp_path, monkeypatch, capsys):
    """The README's `wavephys check` line on an engine's bare EXR frames (no metadata: dx and dt given)."""
    import shlex
    import sys

    import OpenEXR

    sys.path.insert(0, str(ROOT / "tests" / "harness"))
    from corpus import fft_ocean, phillips_h0

    from wavephys.app.cli import main

    readme = (ROOT / "README.md").read_text()
    section = readme.split("## Check exported frames", 1)[1].split("\n## ", 1)[0]
    (command,) = re.findall(r"```bash\n(wavephys check [^\n]*)\n```", section)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "export" / "frames").mkdir(parents=True)
    sea = fft_ocean(phillips_h0(32, 0.05, speed=1.0, seed=4), 0.05, 1 / 60, 384)
    for i, frame in enumerate(sea):
        with OpenEXR.File({}, {"Y": np.flipud(frame).astype(np.float32)}) as f:
            f.write(str(tmp_path / "export" / "frames" / f"h{i}.exr"))
    assert main(shlex.split(command)[1:]) == 0, capsys.readouterr()
    assert (tmp_path / "checks.xml").is_file()

"""The documented examples run as written: the README's pytest example and the guide's
worked example (docs/harness.md), whose explanation of the failure is checked."""

import re
from pathlib import Path

ROOT = Path(__file__).parent.parent


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


def test_readme_surfaces_example_runs_as_written(capsys):
    readme = (ROOT / "README.md").read_text()
    section = readme.split("## Cheap surface models, measured", 1)[1].split("\n## ", 1)[0]
    (block,) = _python_blocks(section)
    namespace = {}
    exec(compile(block, "README.md", "exec"), namespace)
    printed = capsys.readouterr().out
    assert "fold at lambda = " in printed
    assert 0.01 < float(namespace["foam"].mean()) < 0.1  # some foam, on the steepest crests
    assert namespace["eta"].shape == (128, 128)

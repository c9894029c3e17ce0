"""Each cause of the record checks broken once: which tests then fail.

``python tests/mutate_records.py`` (about 15 minutes on 2 cores) runs the harness's corpus and
simulator tests once per cause function below, with that function replaced by one that finds
nothing; a cause whose breaking no test notices is untested. Also a pytest plugin
(``-p mutate_records`` with ``WAVEPHYS_MUTATE=module:function:kind``), which is how it breaks them.
"""

from __future__ import annotations

import importlib
import os
import re
import subprocess
import sys
from pathlib import Path

CAUSES = [
    "wavephys.harness.dispersion:_aliasing:empty",
    "wavephys.harness.dispersion:_frequency_floor:empty",
    "wavephys.harness.dispersion:_quantized:empty",
    "wavephys.harness.dispersion:_scale_fit:empty",
    "wavephys.harness.dispersion:_depth_fit:empty",
    "wavephys.harness.dispersion:_sigma_fit:empty",
    "wavephys.harness.dispersion:_bound_components:empty",
    "wavephys.harness.dispersion:_non_dispersive:empty",
    "wavephys.harness.tank:_speed_and_depth:list",
    "wavephys.harness.maps:_normals_cause:empty",
]
"""``module:function:kind``: the cause functions, and what the broken one returns (kind)."""

TESTS = ["tests/harness/test_corpus.py", "tests/harness/test_simulators.py", "tests/harness/test_tank.py",
         "tests/harness/test_nonlinear_surfaces.py", "tests/harness/test_check_command.py"]


def pytest_configure(config):
    """Break the function named by ``WAVEPHYS_MUTATE`` for this session (nothing when it is unset)."""
    spec = os.environ.get("WAVEPHYS_MUTATE")
    if not spec:
        return
    module, name, kind = spec.split(":")
    value = {"empty": "", "none": None, "list": []}[kind]
    setattr(importlib.import_module(module), name, lambda *args, **kwargs: value)


def main() -> int:
    root = Path(__file__).resolve().parents[1]
    unnoticed = []
    for spec in CAUSES:
        env = dict(os.environ, WAVEPHYS_MUTATE=spec, PYTHONPATH=str(root / "tests"))
        out = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "mutate_records",
                              *TESTS], cwd=root, env=env, capture_output=True, text=True).stdout
        failed = re.findall(r"^FAILED (\S+)", out, re.M)
        print(f"{spec}: {len(failed)} tests fail {failed[:2]}", flush=True)
        if not failed:
            unnoticed.append(spec)
    print(f"{len(CAUSES) - len(unnoticed)} of {len(CAUSES)} causes seen failing; unnoticed: {unnoticed}")
    return 1 if unnoticed else 0


if __name__ == "__main__":
    sys.exit(main())

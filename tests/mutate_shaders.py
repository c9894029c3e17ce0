"""Each fault model of each shader check removed once: which corpus entries then lose their cause.

``python tests/mutate_shaders.py`` (about 3 minutes on 2 cores). A model whose removal no entry
notices has no entry of its own in ``tests/shader_corpus.py``, or its cause is worded like
another's: docs/harness.md ("The corpus") lists them.
"""

from __future__ import annotations

import dataclasses
import inspect
import sys
import warnings
from pathlib import Path


def sweep(write=print):
    """[(check, model, [entries that lose their cause])] for every fault model of every shader check."""
    sys.path.insert(0, str(Path(__file__).parent))
    from shader_corpus import CORPUS

    import optics.shaders.checks as checks
    from optics.shaders import check_glsl

    def cause_found(entry):
        return entry.cause in check_glsl(entry.source, entry.function, entry.against, **entry.options).cause

    faulty = [e for e in CORPUS if e.cause]
    found = {e.name: cause_found(e) for e in faulty}
    original = dict(checks.SHADER_CHECKS)
    results = []
    for name, check in original.items():
        takes = {"roles": check.takes} if "roles" in inspect.signature(check.domain).parameters else {}
        for model in sorted({m.name for m in check.domain(**takes).faults}):
            def domain(*args, _domain=check.domain, _model=model, **kwargs):
                d = _domain(*args, **kwargs)
                return dataclasses.replace(d, faults=[m for m in d.faults if m.name != _model])

            domain.__signature__ = inspect.signature(check.domain)
            checks.SHADER_CHECKS[name] = dataclasses.replace(check, domain=domain)
            try:
                lost = [e.name for e in faulty if e.against == name and found[e.name] and not cause_found(e)]
            finally:
                checks.SHADER_CHECKS[name] = check
            results.append((name, model, lost))
            write(f"{name:15s} {model:32s} {len(lost)} entries lose their cause {lost[:3]}")
    return results


if __name__ == "__main__":
    warnings.filterwarnings("ignore")
    rows = sweep()
    unseen = [(c, m) for c, m, lost in rows if not lost]
    print(f"{len(rows) - len(unseen)} of {len(rows)} fault models are seen failing; unseen: {unseen}")

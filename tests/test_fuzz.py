"""Every public callable refuses bad input by name: property-based fuzzing of the whole API.

The API is discovered from ``__all__`` (``tests/fuzzing.py``); for each parameter of each
callable, hypothesis draws bad values of the parameter's kind (``None``, strings, alien
objects, NaN, ±inf, 1e30, negative and zero sizes, arrays with a NaN, empty or misshaped
arrays) while the other arguments stay valid (``tests/fuzz_examples.py``). A bad value must
raise TypeError or ValueError naming the parameter — never a crash deep inside numpy or
XLA, a hang, a silent NaN, or a quietly accepted value. Profiles: ``ci`` (the default, a
few examples per parameter) and ``thorough`` (``HYPOTHESIS_PROFILE=thorough``).
"""

import collections
import json
import os

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import fuzzing

settings.register_profile("ci", max_examples=12, deadline=None, derandomize=True,
                          suppress_health_check=list(HealthCheck))
settings.register_profile("thorough", max_examples=200, deadline=None, suppress_health_check=list(HealthCheck))
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

TARGETS = fuzzing.discover()
CASES = [(t, p) for t in TARGETS for p in t.params]
HALVES = (CASES[0::2], CASES[1::2])  # the second half runs in tests/test_fuzz_second_half.py (its own
# xdist scope, so the two halves run on both workers)
OUTCOMES = collections.Counter()
FAILURES = []


@pytest.mark.slow  # moved to the slow run (CI runs it): the README's pytest must stay under 10 min on 2 cores
def test_every_public_callable_has_a_valid_call():
    """New public functions are covered automatically; this fails until their parameters have
    valid examples (by name in tests/fuzz_examples.py), and every valid call must succeed
    (half the targets here, half in tests/test_fuzz_second_half.py)."""
    check_valid_calls(TARGETS[0::2])


def check_valid_calls(targets):
    import numpy as np

    fuzzing.ex.RNG = np.random.default_rng(7)  # the same example fields whatever ran before in this worker
    broken = []
    for target in targets:
        try:
            fuzzing.call(target, fuzzing.valid_kwargs(target))
        except Exception as exc:  # noqa: BLE001
            broken.append(f"{target.name}: {type(exc).__name__}: {str(exc)[:160]}")
    assert not broken, "\n".join(broken)


@pytest.mark.parametrize("target,param", HALVES[0], ids=[f"{t.name}:{p.name}" for t, p in HALVES[0]])
def test_bad_input_is_refused_by_name(target, param):
    check_case(target, param)


def check_case(target, param):
    """Draw bad values of one parameter and classify what each does (module doc)."""
    try:
        example = fuzzing.example_of(target, param)
    except KeyError:
        pytest.fail(f"no valid example for {target.name}")
    values = fuzzing.bad_values(target, param, example)
    if not values:
        pytest.skip("no bad values of this kind")

    @given(st.sampled_from(values))
    def check(case):
        value, category = case
        outcome, detail = fuzzing.classify(target, param.name, value, category)
        OUTCOMES[outcome] += 1
        if outcome in fuzzing.FAILURES:
            shown = fuzzing.short(value)
            FAILURES.append(f"{target.name}({param.name}={shown}): {outcome}: {detail}")
            if os.environ.get("WAVEPHYS_FUZZ_LOG"):  # one line per failure, for working through them
                with open(os.environ["WAVEPHYS_FUZZ_LOG"], "a") as log:
                    log.write(FAILURES[-1].replace("\n", " ") + "\n")
            raise AssertionError(f"{param.name}={shown}: {outcome}: {detail}")

    check()


def pytest_fuzz_summary():
    """Counts per outcome (printed by tests/conftest.py at the end of the session)."""
    return dict(OUTCOMES), FAILURES

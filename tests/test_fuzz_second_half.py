"""The second half of the fuzz cases of ``tests/test_fuzz.py`` (a module of its own, so that
pytest-xdist's ``loadscope`` runs the two halves on different workers)."""

import pytest

import test_fuzz as _fuzz


@pytest.mark.parametrize("target,param", _fuzz.HALVES[1], ids=[f"{t.name}:{p.name}" for t, p in _fuzz.HALVES[1]])
def test_bad_input_is_refused_by_name(target, param):
    _fuzz.check_case(target, param)


@pytest.mark.slow  # moved to the slow run (CI runs it): the README's pytest must stay under 10 min on 2 cores
def test_every_public_callable_has_a_valid_call():
    """The other half of ``tests/test_fuzz.py``'s valid calls."""
    _fuzz.check_valid_calls(_fuzz.TARGETS[1::2])

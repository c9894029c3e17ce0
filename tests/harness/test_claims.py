"""Claims as data: a new check with a new claim is one function and one registry row, and Python, the fixture and
the command take the claim by name with nothing else edited; claims are checked before any work."""

import math

import numpy as np
import pytest

from wavephys import Water
from wavephys.harness import Record, check_record
from wavephys.harness.claims import Claim, Claims, claim_fields, parse_number
from wavephys.harness.suite import RECORD_CHECKS, RecordCheck, register, unregister


def _level(record, water, claims):
    """A throwaway law: the mean water level stays within a claimed offset of 0 (m)."""
    from wavephys.harness import bound

    return bound("largest |mean level|", float(np.abs(record.eta.mean(axis=(1, 2))).max()),
                 claims.get("level_offset"), unit="m")


@pytest.fixture
def level_check():
    row = register(RecordCheck("mean_level", "the mean water level against a claimed offset, m", ("level_offset",),
                               _level, claims=(Claim("level_offset", "number", "the largest mean level allowed, m",
                                                     lo=0.0, lo_open=True, metavar="M"),)))
    try:
        yield row
    finally:
        unregister("mean_level")


def _record(offset=0.0):
    rng = np.random.default_rng(0)
    return Record.from_array(rng.normal(0.0, 1e-3, (16, 16, 16)) + offset, 0.1, 0.05, axes="tyx")


def test_a_new_check_with_a_new_claim_is_one_function_and_one_row(level_check, wavephys_check, tmp_path, capsys):
    from wavephys.app.cli import main

    report = check_record(_record(), Water(), only=["mean_level"], level_offset=0.01)
    assert report.ok and "mean_level" in report.rows
    assert "needs level_offset= (--level-offset M)" in check_record(_record(), Water()).skipped["mean_level"]
    assert not check_record(_record(0.05), Water(), only=["mean_level"], level_offset=0.01).ok
    assert Claims.from_kwargs(level_offset=0.02).get("level_offset") == 0.02
    wavephys_check.record(_record(), Water(), only=["mean_level"], level_offset=0.01)  # the fixture
    _record(0.05).save(tmp_path / "r.npz")
    assert main(["check", str(tmp_path / "r.npz"), "--only", "mean_level", "--level-offset", "1/10"]) == 0
    assert main(["check", str(tmp_path / "r.npz"), "--only", "mean_level", "--level-offset", "0.01"]) == 1
    capsys.readouterr()
    with pytest.raises(SystemExit):
        main(["check", "--help"])
    text = capsys.readouterr().out
    assert "--level-offset M" in text and "mean_level" in text
    with pytest.raises(ValueError, match="level_offset"):
        check_record(_record(), Water(), only=["mean_level"], level_offset=-1.0)


def test_registering_is_checked():
    with pytest.raises(ValueError, match="already"):
        register(RECORD_CHECKS["dispersion"])
    with pytest.raises(ValueError, match="nobody declares: wind"):
        register(RecordCheck("gust", "gusts", ("wind",), _level))
    assert "gust" not in RECORD_CHECKS
    with pytest.raises(ValueError, match="not a registered check"):
        unregister("gust")


def test_claims_are_checked_by_name_before_any_work():
    rec = _record()
    for kwargs, error, words in [
        (dict(direction="north"), TypeError, "direction"),
        (dict(depth=-1.0), ValueError, "depth"),
        (dict(colour=1), TypeError, "'colour'] are not claims"),
        (dict(at_rest=True), ValueError, "at_rest describes bed: give bed= (--bed FILE) too"),
        (dict(k_range=(5.0, 1.0)), ValueError, "k_range"),
        (dict(wake=dict(speed=-1.0)), ValueError, "wake['speed']"),
        (dict(bed=np.zeros((4, 4))), ValueError, "bed"),
        (dict(claims=Claims(), sea=True), TypeError, "not both"),
    ]:
        with pytest.raises(error, match=None) as info:
            check_record(rec, Water(), **kwargs)
        assert words in str(info.value), (kwargs, info.value)
    with pytest.raises(ValueError, match="empty list"):
        check_record(rec, Water(), only=[])


def test_a_record_too_short_is_refused_with_its_length():
    short = Record.from_array(np.random.default_rng(1).normal(size=(12, 16, 16)), 0.1, 0.05, axes="tyx")
    report = check_record(short, Water())
    assert "dispersion" not in report.rows and "needs at least 16 frames (the record has 12)" in \
        report.skipped["dispersion"]
    with pytest.raises(ValueError, match="needs at least 16 frames"):
        check_record(short, Water(), only=["dispersion"])


def test_claims_show_their_fields_and_numbers_take_fractions():
    fields = claim_fields(extra=False)
    assert {"depth", "sigma", "sea", "direction", "tank", "bed", "at_rest", "dam", "wake"} <= set(fields)
    assert all(c.help and c.option.startswith("--") for c in fields.values())
    assert fields["at_rest"].option == "--at-rest" and fields["k_range"].option == "--k-range"
    assert parse_number("1/60") == pytest.approx(1 / 60) and parse_number("2/256") == 2 / 256
    assert parse_number("inf") == math.inf
    with pytest.raises(ValueError, match="expected a number"):
        parse_number("1/0")
    assert Claims(depth=0.5).made() == {"depth": fields["depth"]}

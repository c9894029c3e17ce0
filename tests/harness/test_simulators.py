"""Engine-style simulators (tests/harness/simulators.py) get the verdict their own scheme earns — decided from its
symbol, not measured — and the cause beside each failure, from Python, the pytest fixture and the command."""

import numpy as np
import pytest

from simulators import SIMULATORS, truth
from wavephys import Water
from wavephys.harness import Record, check_record

IDS = [s.name for s in SIMULATORS]


def _made(sim):
    eta, dx, dt, power = sim.run()
    decided = truth(sim, eta, dx, dt, power)
    claims = dict(sim.claims)
    if sim.maps is not None:
        claims.update(sim.maps(eta, dx))
    return Record.from_array(eta, dx, dt, axes="tyx"), claims, decided


def _holds(report, sim, decided):
    for name, ok in decided.items():
        row = report.rows[name]
        assert row.ok is ok, f"{sim.name}: {name}: {row.report()}"
        if not ok:
            assert sim.causes[name] in row.note, f"{sim.name}: {name}: {row.report()}"


@pytest.mark.parametrize("sim", SIMULATORS, ids=IDS)
def test_simulators_from_python(sim):
    record, claims, decided = _made(sim)
    assert {name for name, ok in decided.items() if not ok} == set(sim.causes), "the labelled faults are the truth's"
    _holds(check_record(record, Water(**sim.water), only=list(decided), **claims), sim, decided)


def test_the_simulators_cover_correct_and_faulty_schemes():
    verdicts = [truth(s, *s.run()) for s in SIMULATORS]
    assert len(SIMULATORS) >= 8
    assert sum(all(v.values()) for v in verdicts) >= 4 and sum(not all(v.values()) for v in verdicts) >= 6


@pytest.mark.parametrize("sim", SIMULATORS[::2], ids=IDS[::2])
def test_simulators_from_the_fixture(sim, wavephys_check):
    record, claims, decided = _made(sim)
    if all(decided.values()):
        wavephys_check.record(record, Water(**sim.water), only=list(decided), **claims)
        return
    with pytest.raises(AssertionError) as info:
        wavephys_check.record(record, Water(**sim.water), only=list(decided), **claims)
    table = str(info.value)
    assert "checks ok" in table.splitlines()[0]  # the fixture's failure is the table of rows and their causes
    for name, cause in sim.causes.items():
        assert f"FAILED {name}" in table and cause in table


@pytest.mark.parametrize("sim", SIMULATORS[1::2], ids=IDS[1::2])
def test_simulators_from_the_command(sim, tmp_path, capsys):
    from wavephys.app.cli import main
    from wavephys.harness.claims import claim_fields

    record, claims, decided = _made(sim)
    record.save(tmp_path / "frames.npz")
    argv = ["check", str(tmp_path / "frames.npz"), "--only", *decided]
    for key, value in {**sim.water, **claims}.items():
        c = claim_fields()[key]
        if c.kind == "flag":
            argv += [c.option] if value else []
        elif c.kind in ("map", "array"):
            np.save(tmp_path / f"{key}.npy", value)
            argv += [c.option, str(tmp_path / f"{key}.npy")]
        else:
            argv += [c.option, str(value)]
    code = main(argv)
    out = capsys.readouterr().out
    assert code == (0 if all(decided.values()) else 1), out
    for name, ok in decided.items():
        assert f"{'ok    ' if ok else 'FAILED'} {name}" in out, out
    for cause in sim.causes.values():
        assert cause in out, out

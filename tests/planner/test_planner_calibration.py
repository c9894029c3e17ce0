"""Costs on the user's machine: ``wavephys calibrate`` measures the cost model anywhere, ``plan``
reads it from a file and says on the card which calibration it used; bad files are refused by
name; a plan is never predicted costlier than the full model."""

import json
import math

import pytest

from wavephys.app import cli
from wavephys.planner import BUILTIN_SCENES, Scene, StoneSpec, builtin_scene, calibrate, load_calibration, plan
from wavephys.planner.cost import calibration as shipped
from wavephys.planner.measure import TABLES


def _pond(n=32, frames=6, **kw):
    return Scene(2.0, 2.0 / n, depth=0.5, open_water=False, duration=frames / 30.0, fps=30.0, height_range=0.02,
                 stones=(StoneSpec(0.1, -0.2, 0.25, 0.01),), name=f"calibration-pond-{n}", **kw)


def _scaled(cal, factor):
    """Every measured second of ``cal`` times ``factor`` (κ, a rounding ratio, kept)."""
    out = {}
    for key, value in cal.items():
        if key in ("kappa", "kappa_measured") or not isinstance(value, (dict, float, int)) or isinstance(value, bool):
            out[key] = value
        elif isinstance(value, (float, int)):
            out[key] = value * factor
        elif "n" in value:
            out[key] = {k: (v if k == "n" or k.startswith(("ratio", "work")) or isinstance(v, str) else [x * factor for x in v])
                        for k, v in value.items()}
        else:  # per form, or per surface model (a table each)
            out[key] = {k: (v * factor if isinstance(v, (int, float)) else _scaled({"t": v}, factor)["t"])
                        for k, v in value.items()}
    return out


def test_a_partial_calibration_keeps_the_rest_of_its_base(tmp_path):
    out = tmp_path / "here.json"
    lines = []
    data = calibrate(out, only=["texture"], progress=lines.append)
    assert lines and "height texture" in lines[0]
    read = load_calibration(out)
    assert read["source"] == str(out)
    assert set(read["texture"]) == set(shipped()["texture"])
    assert all(math.isfinite(v) and v > 0 for v in read["texture"].values())
    assert read["texture_date"] and "cores" in read["texture_machine"]
    for key in ("step", "caustics", "kappa", "machine", "date"):  # the base's, unchanged
        assert read[key] == shipped()[key] == data[key], key
    assert "source" not in json.loads(out.read_text())  # where it was read from is not written into it


def test_the_plan_costs_what_its_calibration_says(tmp_path):
    """Every table twice as slow: the same choices at twice the predicted cost, and the card names
    the file."""
    scene = _pond()
    path = tmp_path / "slow.json"
    path.write_text(json.dumps(_scaled({k: v for k, v in shipped().items() if k != "source"}, 2.0)))
    here = plan(scene, scene.height_quantum)
    slow = plan(scene, scene.height_quantum, calibration=path)
    assert slow.model.choices == here.model.choices
    assert slow.cost == pytest.approx(2.0 * here.cost, rel=1e-9)
    assert slow.full_cost == pytest.approx(2.0 * here.full_cost, rel=1e-9)
    assert f"costs measured by calibration {path} (x86_64" in slow.card()
    assert "costs measured by calibration shipped (" in here.card()
    assert slow.as_dict()["calibration"].startswith(str(path))


def _corrupt(cal, how):
    cal = json.loads(json.dumps({k: v for k, v in cal.items() if k != "source"}))
    if how == "missing table":
        del cal["frame"]
        return cal, r"lacks \['frame'\]"
    if how == "nan":
        cal["step"]["first"][3] = float("nan")
        return cal, r"\['step'\]\['first'\]\[3\] must be seconds"
    if how == "negative":
        cal["fresnel"]["schlick"] = -1.0
        return cal, r"\['fresnel'\]\['schlick'\] must be seconds"
    if how == "unsorted sizes":
        cal["caustics"]["n"] = cal["caustics"]["n"][::-1]
        return cal, r"\['caustics'\]\['n'\] must be positive and ascending"
    if how == "short table":
        cal["shade"]["seconds"] = cal["shade"]["seconds"][:-1]
        return cal, r"\['shade'\]\['seconds'\] has 3 values for 4 sizes"
    if how == "string seconds":
        cal["surface"]["noise"]["seconds"][0] = "fast"
        return cal, r"\['surface'\]\['noise'\]\['seconds'\]\[0\] must be seconds"
    if how == "kappa":
        cal["kappa"] = math.inf
        return cal, r"\['kappa'\] must be seconds"
    if how == "gather counted by":
        cal["caustics_jacobian"]["by"] = "pixels"
        return cal, r"\['caustics_jacobian'\]\['by'\] must be 'points' or 'texels'"
    raise AssertionError(how)


@pytest.mark.parametrize("how", ["missing table", "nan", "negative", "unsorted sizes", "short table",
                                 "string seconds", "kappa", "gather counted by"])
def test_a_damaged_calibration_file_is_refused_naming_the_entry(tmp_path, how):
    cal, message = _corrupt(shipped(), how)
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(cal))
    with pytest.raises(ValueError, match=message) as info:
        load_calibration(path)
    assert str(path) in str(info.value)
    with pytest.raises(ValueError, match=message):  # the same check for a dict given to plan
        plan(_pond(), 1e-3, calibration=cal)


def test_files_that_are_not_calibrations_are_refused(tmp_path):
    with pytest.raises(ValueError, match="does not exist"):
        load_calibration(tmp_path / "none.json")
    (tmp_path / "text.json").write_text("step = 1")
    with pytest.raises(ValueError, match="is not JSON"):
        load_calibration(tmp_path / "text.json")
    (tmp_path / "list.json").write_text("[1, 2]")
    with pytest.raises(ValueError, match="holds a list, not a calibration"):
        load_calibration(tmp_path / "list.json")
    with pytest.raises(TypeError, match="path must be a file system path"):
        load_calibration(3)
    with pytest.raises(TypeError, match="calibration must be a dict or a calibration file.s path"):
        plan(_pond(), 1e-3, calibration=3)


def test_bad_requests_are_refused_before_measuring(tmp_path):
    never = []
    with pytest.raises(ValueError, match="out must end in .json"):
        calibrate(tmp_path / "cal.txt", progress=never.append)
    with pytest.raises(ValueError, match="does not exist"):
        calibrate(tmp_path / "no" / "cal.json", progress=never.append)
    with pytest.raises(ValueError, match="only must name tables among step, "):
        calibrate(tmp_path / "cal.json", only=["steps"], progress=never.append)
    with pytest.raises(ValueError, match="lacks"):
        calibrate(tmp_path / "cal.json", only="texture", base={"step": {}}, progress=never.append)
    with pytest.raises(ValueError, match="base: calibration file .* does not exist"):
        calibrate(tmp_path / "cal.json", only="texture", base=tmp_path / "none.json", progress=never.append)
    with pytest.raises(TypeError, match="base must be a calibration"):
        calibrate(tmp_path / "cal.json", only="texture", base=3, progress=never.append)
    with pytest.raises(ValueError, match="base: it is for only="):  # before: a full seven-minute calibration
        calibrate(tmp_path / "cal.json", base=tmp_path / "cal.json", progress=never.append)
    with pytest.raises(TypeError, match="progress must be callable"):
        calibrate(tmp_path / "cal.json", only="texture", progress="print")
    assert never == [] and not (tmp_path / "cal.json").exists()


def test_an_interrupted_calibration_leaves_the_old_file(tmp_path):
    """The file is written once, whole, at the end: a run stopped midway changes nothing."""
    path = tmp_path / "cal.json"
    calibrate(path, only="texture", progress=lambda line: None)
    before = path.read_text()

    def stop(line):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        calibrate(path, only=["texture", "shade"], base=path, progress=stop)
    assert path.read_text() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cal.json"]


@pytest.mark.parametrize("index", [2, 4, pytest.param(5, marks=pytest.mark.slow), pytest.param(6, marks=pytest.mark.slow)])
def test_a_plan_is_never_predicted_costlier_than_the_full_model(index):
    """Even when a smaller texture is worth up to ten times the compute (the slack's limit), the
    plan costs at most what the full model does. Generated scenes (open sea, ripples, tank,
    slope): without the limit their plans at ½ quantum were predicted 0.4–2.2 % costlier."""
    from wavephys.planner import generate_scenes

    scene = generate_scenes(7, seed=7, texels=(32, 48))[index]
    p = plan(scene, 0.5 * scene.height_quantum, texture_slack=10.0)
    assert p.cost <= p.full_cost * (1 + 1e-12), (scene.name, p.card())


def test_the_command_calibrates_and_plans_with_it(tmp_path, capsys):
    out = tmp_path / "here.json"
    assert cli.main(["calibrate", "--out", str(out), "--only", "texture"]) == 0
    said = capsys.readouterr().out
    assert f"wrote {out}: texture measured on x86_64" in said and f"--calibration {out}" in said
    toml = tmp_path / "tank.toml"  # a small deep tank (plans in a second)
    toml.write_text('extent = 2.0\npixel = 0.0625\ndepth = "inf"\nopen_water = false\nduration = 0.2\n'
                    '[[stones]]\nx = 0.2\ny = -0.1\nradius = 0.15\ndepth = 0.01\n')
    assert cli.main(["plan", str(toml), "--calibration", str(out)]) == 0
    assert f"costs measured by calibration {out} (" in capsys.readouterr().out


@pytest.mark.parametrize("argv, message", [
    (["plan", "pond", "--calibration", "{tmp}/none.json"], "none.json' does not exist"),
    (["calibrate", "--out", "{tmp}/cal.txt"], "--out must end in .json"),
    (["calibrate", "--out", "{tmp}/cal.json", "--only", "steps"], "invalid choice: 'steps'"),
    (["calibrate", "--out", "{tmp}/cal.json", "--base", "{tmp}/cal.json"], "does not exist"),
])
def test_the_command_refuses_bad_options_as_usage_errors(tmp_path, capsys, argv, message):
    with pytest.raises(SystemExit) as info:
        cli.main([a.format(tmp=tmp_path) for a in argv])
    assert info.value.code == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "cal.json").exists()


def test_the_base_is_only_for_a_partial_calibration(tmp_path, capsys):
    base = tmp_path / "base.json"
    calibrate(base, only="texture", progress=lambda line: None)
    with pytest.raises(SystemExit) as info:
        cli.main(["calibrate", "--out", str(tmp_path / "cal.json"), "--base", str(base)])
    assert info.value.code == 2 and "--base is for --only" in capsys.readouterr().err


def test_the_commands_lists_match_the_package():
    """--help names the built-in scenes and the tables without importing the planner."""
    assert cli.PLAN_SCENES == tuple(BUILTIN_SCENES)
    assert cli.CALIBRATION_TABLES == TABLES


@pytest.mark.parametrize("caustics", [False, pytest.param(True, marks=pytest.mark.slow)])
def test_the_card_says_where_the_time_goes(caustics):
    """The cost's parts sum to it, and the card lists the largest first."""
    scene = _pond(caustics=caustics)
    p = plan(scene, scene.height_quantum)
    assert sum(p.cost_parts.values()) == pytest.approx(p.cost, rel=1e-12)
    assert all(v >= 0 for v in p.cost_parts.values())
    assert p.cost_parts["steps"] > 0 and p.cost_parts["shading"] > 0
    assert (p.cost_parts["caustics"] > 0) == caustics and p.cost_parts["ships"] == 0
    line = next(line for line in p.card().splitlines() if line.startswith("time goes to "))
    biggest = max(p.cost_parts, key=p.cost_parts.get)
    assert line.startswith(f"time goes to {biggest} ")
    assert p.as_dict()["cost_parts"] == p.cost_parts


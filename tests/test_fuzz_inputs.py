"""The kinds of bad input the API fuzz (tests/test_fuzz.py) does not draw: file contents (corrupt,
truncated, binary, empty, a folder, deeply nested), scene TOML with values of the wrong type, non-finite
values flowing through the planner's outputs and sweeps, and every numeric option of every command past
its limits. Each must be refused before any work, naming the argument (TypeError or ValueError from
Python; exit 2 with one line from a command) — never a traceback, a silent NaN or a file that lies."""

import argparse
import json
import math

import numpy as np
import pytest

from wavephys.app.cli import build_parser, main

BAD_CONTENTS = {
    "corrupt": b"\x76\x2f\x31\x01" + b"\x00\xff" * 64,  # an EXR magic number, then garbage
    "binary": bytes(range(256)) * 4,
    "empty": b"",
    "text": b"hello, world\n",
}


def _truncated_exr(tmp_path):
    from optics.rendering.textures import save_exr

    good = save_exr(tmp_path / "good.exr", {"Y": np.ones((32, 32))}).read_bytes()
    return good[: len(good) // 2]


def _readers():
    """(name of the argument, the reader) for every entry that reads a file the user names."""
    from optics.rendering.textures import load_exr, load_npz
    from wavephys.app.report import read_validation
    from wavephys.core.frames import read_exr, read_frames, read_map
    from wavephys.harness import Record
    from wavephys.planner import Scene

    return {
        "load_exr": ("path", load_exr, ".exr"), "read_exr": ("path", read_exr, ".exr"),
        "read_map": ("path", read_map, ".exr"), "read_frames": ("source", read_frames, ".exr"),
        "Record.from_files": ("source", lambda p: Record.from_files(p, dx=0.1, dt=0.1), ".exr"),
        "Record.load": ("path", Record.load, ".npz"), "load_npz": ("path", load_npz, ".npz"),
        "Scene.from_toml": ("path", Scene.from_toml, ".toml"), "read_validation": ("path", read_validation,
                                                                                  ".json"),
        "read_frames (png)": ("source", read_frames, ".png"), "read_frames (npy)": ("source", read_frames, ".npy"),
    }


@pytest.mark.parametrize("reader", list(_readers()))
@pytest.mark.parametrize("kind", list(BAD_CONTENTS) + ["truncated", "folder"])
def test_bad_files_are_refused_naming_the_argument(reader, kind, tmp_path):
    name, read, suffix = _readers()[reader]
    path = tmp_path / f"bad{suffix}"
    if kind == "folder":
        path.mkdir()
    else:
        path.write_bytes(_truncated_exr(tmp_path) if kind == "truncated" else BAD_CONTENTS[kind])
    with pytest.raises((TypeError, ValueError)) as exc:
        read(path)
    message = str(exc.value)
    assert name in message and (str(path) in message or path.name in message), (reader, kind, message)


def test_deeply_nested_files_are_refused(tmp_path):
    from wavephys.app.report import read_validation
    from wavephys.planner import Scene

    toml = tmp_path / "deep.toml"
    toml.write_text("a = " + "[" * 5000 + "]" * 5000 + "\n")
    with pytest.raises(ValueError, match="path.*too deeply"):
        Scene.from_toml(toml)
    js = tmp_path / "deep.json"
    js.write_text("[" * 100000 + "]" * 100000)
    with pytest.raises(ValueError, match="path"):
        read_validation(js)


SCENE = {"extent": 1.0, "pixel": 1 / 32, "depth": 0.5, "duration": 2 / 30, "fps": 30.0, "height_range": 0.01,
         "open_water": False, "name": "fuzz"}
WRONG_KINDS = ("9.81", True, [1.0], {"a": 1.0}, math.nan, math.inf)


@pytest.mark.parametrize("key", [k for k in SCENE if k != "name"] + ["water.g", "water.rho", "water.sigma",
                                                                      "stones.x", "stones.radius", "wind.speed"])
def test_scene_values_of_the_wrong_type_are_refused_by_name(key):
    """TOML type confusion: every key of a scene, as a string, a bool, an array, a table, NaN and inf."""
    from wavephys.planner import Scene

    for wrong in WRONG_KINDS:
        data = {**SCENE, "water": {"g": 9.81}, "stones": [dict(x=0.0, y=0.0, radius=0.1, depth=0.01)],
                "wind": dict(speed=5.0)}
        table, _, field = key.partition(".")
        if field:
            target = data[table][0] if isinstance(data[table], list) else data[table]
            target[field] = wrong
        else:
            data[key] = wrong
        if key == "depth" and wrong == math.inf or key == "open_water" and wrong is True:
            continue  # valid: deep water; a bool flag
        with pytest.raises((TypeError, ValueError)) as exc:
            Scene.from_dict(data)
        assert (field or key) in str(exc.value), (key, wrong, str(exc.value))


def test_non_finite_outputs_are_refused():
    """A run whose heights went NaN is refused as an Output, so compare never returns NaN; sweeps refuse NaN
    items and warn on NaN results."""
    import jax.numpy as jnp

    from wavephys.parallel import sweep
    from wavephys.planner import Output

    good = np.zeros((2, 4, 4))
    image = np.zeros((4, 4, 3))
    for kw, name in ((dict(heights=np.full((2, 4, 4), np.nan)), "heights"), (dict(seconds=math.nan), "seconds"),
                     (dict(shade_seconds=-1.0), "shade_seconds"), (dict(image=image + 2.0), "image")):
        args = {**dict(heights=good, image=image, seconds=1.0, shade_seconds=0.1), **kw}
        with pytest.raises(ValueError, match=name):
            Output(**args)
    with pytest.raises(ValueError, match=r"items\[1\]"):
        sweep(lambda x: x, [np.ones(3), np.array([1.0, np.nan, 0.0])])
    with pytest.raises(TypeError, match=r"items\[1\]"):
        sweep(lambda x: x, [np.ones(3), "x"])
    with pytest.warns(RuntimeWarning, match="NaN or inf for items"):
        sweep(lambda x: jnp.log(x - 2.0), [np.ones(3), 3 * np.ones(3)])
    assert len(sweep(lambda x: 2 * x, [np.ones(3)], per_device=10**9)) == 1  # no batch of a billion


def _numeric_options():
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for command, p in sub.choices.items():
        for action in p._actions:
            if action.option_strings and action.type is not None and action.type not in (str,):
                yield command, action.option_strings[0], getattr(action.type, "__name__", "")


OPTIONS = list(_numeric_options())


def _actions(command):
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return sub.choices[command]._actions


@pytest.mark.parametrize("command, option, kind", OPTIONS, ids=[f"{c} {o}" for c, o, _ in OPTIONS])
def test_every_numeric_option_past_its_limits_is_one_line(command, option, kind, capsys):
    """NaN, ±inf, words, empty strings and 1e30 (where a limit exists) end at the parser: exit 2, one line
    naming the option, before any work."""
    values = ["nan", "inf", "-inf", "x", ""]
    parse = next(a.type for a in _actions(command) if option in a.option_strings)
    for big in ("1e30", "-1e30"):  # past a documented limit (options with none take any finite number)
        try:
            parse(big)
        except (argparse.ArgumentTypeError, ValueError, TypeError):
            values.append(big)
    for value in values:
        with pytest.raises(SystemExit) as exc:
            main([command, option, value])
        err = capsys.readouterr().err.strip()
        assert exc.value.code == 2 and option in err and "\n" not in err and "Traceback" not in err, \
            (command, option, value, err)


def test_cli_limits_are_the_scenes():
    from wavephys.app import cli, scenes

    assert (cli.MAX_N, cli.MAX_TIME) == (scenes.MAX_N, scenes.MAX_TIME)


@pytest.mark.parametrize("argv, words", [
    (["render", "--frames", "1000000", "--out", "frames"], "--frames"),
    (["report", "--validation", "{folder}", "--out", "rep"], "--validation"),
    (["report", "--validation", "{bad_json}", "--out", "rep"], "--validation"),
    (["plan", "{folder}"], "folder"),
    (["check", "{bad_json}"], "FRAMES"),
])
def test_commands_refuse_bad_files_and_counts_in_one_line(argv, words, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    bad = tmp_path / "bad.json"
    bad.write_text("{bad")
    argv = [a.format(folder=tmp_path, bad_json=bad) for a in argv]
    try:
        code = main(argv)
    except SystemExit as exc:
        code = exc.code
    err = capsys.readouterr().err.strip()
    assert code == 2 and words in err and "Traceback" not in err, (argv, err)


def _scene_params():
    from wavephys.app import SCENES

    # the shallow-water scenes run their solver for seconds, the caustics scenes trace for seconds: their own
    # tests (tests/app, tests/rendering) build them
    slow = {"beach", "dambreak", "wakebeach", "pool", "shore", "ship", "harbour", "storm", "calm"}  # 5-11 s each
    return [pytest.param(name, marks=pytest.mark.slow) if name in slow else name for name in SCENES]


@pytest.mark.parametrize("name", _scene_params())
def test_every_builtin_scene_builds_at_the_smallest_size(name):
    """n = 64, the smallest size the commands accept, for every scene (calm once raised deep in its noise)."""
    from wavephys.app.scenes import builtin_scene

    scene = builtin_scene(name, n=64)
    assert np.all(np.isfinite(np.asarray(scene.water)))


def test_half_float_exr_never_holds_inf(tmp_path):
    from optics.rendering.textures import save_exr

    with pytest.raises(ValueError, match=r"channels\['Y'\].*16-bit"):
        save_exr(tmp_path / "h.exr", {"Y": np.full((4, 4), 7e4)}, half=True)
    with pytest.raises(ValueError, match="channel name"):
        save_exr(tmp_path / "h.exr", {"Y" * 300: np.ones((4, 4))})
    with pytest.raises(ValueError, match="attributes"):
        save_exr(tmp_path / "h.exr", {"Y": np.ones((4, 4))}, attributes={"dx": math.nan})
    assert not (tmp_path / "h.exr").exists()  # nothing half-written
    json.dumps({})  # (json imported for the report's files above)


@pytest.mark.parametrize("command, option, kind", OPTIONS, ids=[f"{c} {o}" for c, o, _ in OPTIONS])
def test_every_numeric_option_at_its_limits_parses(command, option, kind):
    """The documented limits themselves are accepted (and one step past them refused) by the parser."""
    parse = next(a.type for a in _actions(command) if option in a.option_strings)
    limits = getattr(parse, "limits", None)
    if limits is None:
        pytest.skip("no documented range (any finite number, a pair, a fraction of seconds, a setting)")
    lo, hi, lo_open = limits
    if not lo_open:
        assert parse(str(lo)) == lo
    if hi is not None:
        assert parse(str(hi)) == hi
        with pytest.raises(argparse.ArgumentTypeError):
            parse(str(hi + 2 if isinstance(hi, int) else hi * 1.001))
    with pytest.raises(argparse.ArgumentTypeError):
        parse(str(lo - 2 if isinstance(lo, int) else lo - 1.0))

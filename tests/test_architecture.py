"""The structure the project promises: layers that point one way, no import cycles, small public
functions, cheap imports, and the old module names still importable."""

import ast
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).parent.parent
PACKAGES = ("wavephys", "optics")


def _modules():
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            parts = path.relative_to(ROOT).with_suffix("").parts
            name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
            yield name, path


def _imports(path: Path):
    """Every module a file imports (at any depth: lazy imports count for layering)."""
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            yield from (a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            yield node.module
            yield from (f"{node.module}.{a.name}" for a in node.names)


def _top_level_imports(path: Path):
    """Imports executed when the module is imported (not inside functions)."""
    tree = ast.parse(path.read_text())
    for node in tree.body:
        if isinstance(node, ast.Import):
            yield from (a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            yield node.module
            yield from (f"{node.module}.{a.name}" for a in node.names)


MODULES = dict(_modules())


def _layer(name: str) -> str:
    if name.startswith(("wavephys.app", "wavephys.__main__", "wavephys.planner")):  # the command, the planner
        return "app"
    return "optics" if name.startswith("optics") else "wavephys"


@pytest.mark.parametrize("name", sorted(MODULES))
def test_layers_point_one_way(name):
    """Core physics and the harness never import optics; optics never imports the application."""
    layer = _layer(name)
    for imported in _imports(MODULES[name]):
        if layer == "wavephys":
            assert not imported.startswith(("optics", "wavephys.app", "wavephys.planner")), f"{name} imports {imported}"
        if layer == "optics":
            assert not imported.startswith(("wavephys.app", "wavephys.planner")), f"{name} imports {imported}"


def test_no_import_cycles():
    graph = {name: {m for m in _top_level_imports(path) if m in MODULES and m != name}
             for name, path in MODULES.items()}
    state = {}

    def visit(node, stack):
        state[node] = "open"
        for nxt in graph[node]:
            if state.get(nxt) == "open":
                raise AssertionError("import cycle: " + " -> ".join(stack[stack.index(nxt):] + [nxt]))
            if nxt not in state:
                visit(nxt, stack + [nxt])
        state[node] = "done"

    for node in graph:
        if node not in state:
            visit(node, [node])


def _public_functions():
    for name, path in MODULES.items():
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and not node.name.startswith("_"):
                body = node.body[1:] if ast.get_docstring(node) else node.body
                if body:
                    yield f"{name}.{node.name}", body[-1].end_lineno - body[0].lineno + 1


def test_no_public_function_over_80_lines():
    long = [f"{name}: {lines} lines" for name, lines in _public_functions() if lines > 80]
    assert not long, long


def test_plugin_costs_no_jax_import():
    code = "import sys, wavephys.app.pytest_plugin, wavephys, optics; print('jax' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_optics_submodules_on_attribute_access():
    code = ("import optics; print(round(float(optics.fresnel.reflectance(1.0)), 5), "
            "optics.caustics.__name__, optics.rendering.__name__)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["0.02033", "optics.caustics", "optics.rendering"]


@pytest.mark.parametrize("old,new,name", [
    ("wavephys.dispersion", "wavephys.physics.dispersion", "angular_frequency"),
    ("wavephys.ship_waves", "wavephys.physics.ship_waves", "Ship"),
    ("wavephys.finite_difference", "wavephys.models.finite_difference", "fd_run"),
    ("wavephys.validate", "wavephys.harness", "measure_dispersion"),
    ("wavephys.params", "wavephys.core.grid", "Grid"),
    ("optics.fresnel", "optics.light.fresnel", "reflectance"),
    ("optics.render", "optics.rendering.renderer", "Renderer"),
])
def test_old_module_names_still_import(old, new, name):
    import importlib

    assert getattr(importlib.import_module(old), name) is getattr(importlib.import_module(new), name)


def test_split_module_re_exports_both_halves():
    from wavephys.wake import steady_wake, wake_angle  # physics + harness under the old name

    from wavephys.harness.wake import wake_angle as measured
    from wavephys.physics.wake import steady_wake as physics

    assert wake_angle is measured and steady_wake is physics


def test_bench_is_not_installed():
    import importlib.util

    spec = importlib.util.find_spec("bench")
    assert spec is None or Path(spec.origin).parent.parent == ROOT  # only from a checkout


def test_moved_plugin_path_warns_and_is_the_same_module():
    code = ("import warnings, importlib; warnings.simplefilter('error', DeprecationWarning)\n"
            "try:\n    importlib.import_module('wavephys.harness.pytest_plugin')\n"
            "except DeprecationWarning as w:\n    print('warned', 'wavephys.app.pytest_plugin' in str(w))\n"
            "warnings.simplefilter('ignore')\n"
            "import wavephys.harness.pytest_plugin as old, wavephys.app.pytest_plugin as new\n"
            "print(old is new, hasattr(new.Checker, 'glsl'))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["warned", "True", "True", "True"]


def test_plugin_entry_point_names_the_application_layer():
    from importlib.metadata import entry_points

    (ep,) = [e for e in entry_points(group="pytest11") if e.name == "wavephys"]
    assert ep.value == "wavephys.app.pytest_plugin"

"""The structure the project promises: layers that point one way, no import cycles, small public
functions, cheap imports, and the old module names still importable."""

import ast
import re
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


MODULES = dict(_modules())
TABLE = ROOT / "docs" / "architecture.md"


def _layer_table():
    """docs/architecture.md's layer table: [(layer, packages, may import)], each a tuple of the
    backquoted names in its column ("everything" for the application)."""
    text = TABLE.read_text()
    start = text.index("| layer | packages |")
    rows = []
    for line in text[start:].splitlines()[2:]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip("|").split("|")]
        names = lambda cell: tuple(re.findall(r"`([A-Za-z_][\w.]*)`", cell))
        rows.append((cells[0], names(cells[1]), "everything" if cells[3] == "everything" else names(cells[3])))
    return rows


LAYERS = _layer_table()
FACES = {"wavephys", "optics"}  # the packages' own __init__: matched exactly, never as a prefix


def _package(module: str):
    """The table's package of ``module``: the longest listed prefix (the faces match exactly)."""
    best = None
    for _, packages, _ in LAYERS:
        for p in packages:
            hit = module == p if p in FACES else (module == p or module.startswith(p + "."))
            if hit and (best is None or len(p) > len(best)):
                best = p
    return best


def _allowed(package: str):
    for _, packages, may in LAYERS:
        if package in packages:
            return may
    raise KeyError(package)


def test_the_layer_table_is_read():
    """The table parses into every layer the project has (a reformatted table must not make the
    layer test vacuous)."""
    names = [row[0] for row in LAYERS]
    assert len(LAYERS) >= 15 and names[0] == "foundation" and "application" in names, names
    assert _allowed("wavephys.app") == "everything" and _allowed("wavephys.core") == ()
    assert "optics.gpu" in _allowed("optics.caustics")


@pytest.mark.parametrize("name", sorted(MODULES))
def test_every_module_is_in_the_layer_table(name):
    assert _package(name) is not None, f"{name}: no row of docs/architecture.md's layer table names its package"


@pytest.mark.parametrize("name", sorted(MODULES))
def test_imports_follow_the_layer_table(name):
    """Every import of ours (at any depth) is of the module's own package or one its row allows."""
    own = _package(name)
    may = _allowed(own)
    if may == "everything":
        return
    bad = sorted({m for m in _imports(MODULES[name]) if m.split(".")[0] in PACKAGES
                  and (p := _package(m)) is not None and p != own and p not in may})
    assert not bad, f"{name} (package {own}) imports {bad}; docs/architecture.md allows {list(may)}"


def _cycles(graph):
    """Strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in graph:
        if v not in index:
            visit(v)
    return out


def _graph():
    return {name: {m for m in _imports(path) if m in MODULES and m != name} for name, path in MODULES.items()}


def test_no_import_cycles():
    """No circle among modules, lazy imports counted (a function-level import that closes a
    circle is still one: the modules cannot be understood or moved apart)."""
    assert not _cycles(_graph())


def test_layer_and_cycle_tests_can_fail():
    """The checks above catch what they promise, on a made-up import of each kind."""
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": set()}) == [["a", "b", "c"]]
    assert "optics.rendering" not in _allowed("optics.caustics")  # the GL caustics' old import
    assert "wavephys.parallel" not in _allowed("wavephys.physics")  # the forcing's old import
    assert _package("wavephys.core.grid") == "wavephys.core" and _package("wavephys.corex") is None


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
    ("wavephys.finite_difference", "wavephys.models.finite_difference", "fd_step"),
    ("wavephys.validate", "wavephys.harness", "measure_dispersion"),
    ("wavephys.params", "wavephys.core.grid", "Grid"),
    ("optics.fresnel", "optics.light.fresnel", "reflectance"),
    ("optics.render", "optics.rendering.renderer", "Renderer"),
])
@pytest.mark.filterwarnings("ignore::DeprecationWarning")  # they warn (the test below): here, that they still work
def test_old_module_names_still_import(old, new, name):
    import importlib

    assert getattr(importlib.import_module(old), name) is getattr(importlib.import_module(new), name)


def test_every_old_module_name_warns_naming_the_new_one():
    """Each moved name of wavephys, optics and wavephys.harness, imported in a fresh interpreter as a module and
    as an attribute: a DeprecationWarning naming the new place and the release that removes it (0.4), pointing
    at the importing line, so Python's default filter shows it to a script."""
    code = r"""  # the old names: from each package's installed finder
import sys, warnings
import wavephys, optics, wavephys.harness
from wavephys.core.aliases import REMOVAL, _AliasFinder
olds = {}
for f in sys.meta_path:
    if isinstance(f, _AliasFinder):
        olds.update(f.aliases)
print(len(olds))
for old, new in sorted(olds.items()):
    package, name = old.rsplit(".", 1)
    for how in ("import", "attribute"):
        for m in [m for m in sys.modules if m == old]:
            del sys.modules[m]
        if name in vars(sys.modules[package]):
            delattr(sys.modules[package], name)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            if how == "import":
                __import__(old)
            else:
                getattr(sys.modules[package], name)
        said = [str(w.message) for w in caught if issubclass(w.category, DeprecationWarning)]
        here = [w.filename for w in caught if issubclass(w.category, DeprecationWarning)]
        ok = len(said) == 1 and all(n in said[0] for n in new) and REMOVAL in said[0] and here[0] == "<string>"
        print(old, how, "ok" if ok else f"BAD {said} {here}")
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    lines = out.stdout.split("\n")
    assert int(lines[0]) >= 25, out.stdout
    bad = [line for line in lines[1:] if line and not line.endswith(" ok")]
    assert not bad, "\n".join(bad)


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
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


def test_the_old_scenes_module_imports_with_a_warning():
    code = ("import warnings; warnings.simplefilter('error', DeprecationWarning)\n"
            "try:\n    import optics.scenes\nexcept DeprecationWarning as w:\n    print('warned', 'wavephys.app.scenes' in str(w))\n"
            "warnings.simplefilter('ignore')\n"
            "import optics.scenes as old, wavephys.app.scenes as new\nprint(old is new)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["warned", "True", "True"]


def test_renamed_options_keep_working_with_a_warning():
    """lut_size → size (reflectance) and samples → refine (floor_irradiance), renamed in 0.2: the
    old name gives the new one's answer and a DeprecationWarning; both at once is a TypeError."""
    import jax.numpy as jnp
    import numpy as np

    from optics.caustics import floor_irradiance
    from optics.light.fresnel import reflectance
    from wavephys.core.grid import Grid

    with pytest.warns(DeprecationWarning, match="'lut_size' was renamed 'size'"):
        old = float(reflectance(0.3, method="lut", lut_size=16))
    assert old == float(reflectance(0.3, method="lut", size=16))
    grid = Grid(16, 1.0)
    eta = jnp.asarray(0.002 * np.cos(2 * np.pi * np.asarray(grid.mesh()[0]) / 0.5), jnp.float32)
    with pytest.warns(DeprecationWarning, match="'samples' was renamed 'refine'"):
        old = np.asarray(floor_irradiance(eta, grid, 1.0, samples=2))
    np.testing.assert_array_equal(old, np.asarray(floor_irradiance(eta, grid, 1.0, refine=2)))
    with pytest.raises(TypeError, match="pass only 'size'"):
        reflectance(0.3, method="lut", lut_size=16, size=16)


def test_test_folders_do_not_shadow_the_packages():
    """tests/ is on sys.path (its conftest), so a tests/wavephys or tests/optics folder would be
    imported as a namespace package in place of the installed one under the ``pytest`` command:
    the folders mirror the subpackages (tests/physics ↔ wavephys/physics, tests/light ↔
    optics/light), whose names are unique across the two packages."""
    tests = ROOT / "tests"
    folders = {p.name for p in tests.iterdir() if p.is_dir() and not p.name.startswith((".", "_"))} - {"data"}
    assert not folders & set(PACKAGES), folders & set(PACKAGES)
    sub = lambda pkg: {p.name for p in (ROOT / pkg).iterdir() if (p / "__init__.py").exists()}
    assert not sub("wavephys") & sub("optics")  # unique, so one folder per subpackage is unambiguous
    assert folders <= sub("wavephys") | sub("optics"), folders - (sub("wavephys") | sub("optics"))

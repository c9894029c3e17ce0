"""Public API docs in numpydoc form: every public function and class (a name in a module's
``__all__``, ``__internal__`` modules included: being left out of the fuzz exempts nothing here) of the packages
and modules listed in NUMPYDOC (all of them) has a Parameters section (classes: Parameters or Attributes) and,
where it returns a value, a Returns section."""

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).parent.parent
NUMPYDOC = ("wavephys/core", "wavephys/physics", "wavephys/surfaces", "wavephys/models", "wavephys/harness",
            "wavephys/checks", "wavephys/planner", "wavephys/simulation", "wavephys/steppers", "wavephys/parallel", "wavephys/app",
            "wavephys/plot.py", "optics/light", "optics/caustics", "optics/gpu", "optics/rendering", "optics/shaders",
            "optics/checks.py")
"""Every package and module of the public API (a new one is added here)."""


def _all(tree) -> set:
    for n in tree.body:
        if isinstance(n, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "__all__" for t in n.targets):
            try:
                return set(ast.literal_eval(n.value))
            except ValueError:  # built from a table (a package face): it defines nothing itself
                return set()
    return set()


def _public(folder):
    place = ROOT / folder
    for path in ([place] if place.is_file() else sorted(place.rglob("*.py"))):
        tree = ast.parse(path.read_text())
        names = _all(tree)
        for node in tree.body:
            if isinstance(node, (ast.FunctionDef, ast.ClassDef)) and node.name in names:
                yield f"{path.relative_to(ROOT)}:{node.name}", node


def _problems(node) -> list:
    doc = ast.get_docstring(node) or ""
    if isinstance(node, ast.ClassDef):
        if any(isinstance(b, ast.Name) and b.id.endswith(("Error", "Exception", "Unavailable", "Fold", "Infeasible"))
               or isinstance(b, ast.Name) and b.id in ("ValueError", "RuntimeError", "TypeError") for b in node.bases):
            return [] if doc else ["no docstring"]
        fields = any(isinstance(n, ast.AnnAssign) for n in node.body)  # a dataclass's fields
        init = next((n for n in node.body if isinstance(n, ast.FunctionDef) and n.name == "__init__"), None)
        takes = fields or (init is not None and len(init.args.args) + len(init.args.kwonlyargs) > 1)
        if takes and not ("Parameters\n" in doc or "Attributes\n" in doc):
            return ["no Parameters/Attributes"]
        return [] if doc else ["no docstring"]
    args = [a.arg for a in node.args.posonlyargs + node.args.args + node.args.kwonlyargs if a.arg not in ("self", "cls")]
    out = []
    if (args or node.args.vararg or node.args.kwarg) and "Parameters\n" not in doc:
        out.append("no Parameters")
    returns = any(isinstance(n, ast.Return) and n.value is not None for n in ast.walk(node))
    if returns and "Returns\n" not in doc and "Yields\n" not in doc:
        out.append("no Returns")
    return out


@pytest.mark.parametrize("folder", NUMPYDOC)
def test_public_api_is_documented_in_numpydoc(folder):
    missing = [f"{name}: {', '.join(p)}" for name, node in _public(folder) if (p := _problems(node))]
    assert not missing, "\n".join(missing)


def test_the_docs_check_can_fail():
    bare = ast.parse('def f(x):\n    """Does f."""\n    return x\n').body[0]
    assert _problems(bare) == ["no Parameters", "no Returns"]
    good = ast.parse('def f(x):\n    """Does f.\n\n    Parameters\n    ----------\n    x : float\n\n'
                     '    Returns\n    -------\n    float\n    """\n    return x\n').body[0]
    assert _problems(good) == []


def test_every_public_module_is_in_numpydoc():
    """No module with public names escapes the docs test."""
    listed = [ROOT / f for f in NUMPYDOC]
    for package in ("wavephys", "optics"):
        for path in sorted((ROOT / package).rglob("*.py")):
            if path.name == "__init__.py" and path.parent.name in ("wavephys", "optics"):
                continue  # the package faces define nothing themselves
            if any(path == f or f in path.parents for f in listed):
                continue
            assert "__all__" not in path.read_text(), f"{path} has public names: add it to NUMPYDOC"

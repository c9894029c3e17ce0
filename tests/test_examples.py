"""The example notebooks run in a real Jupyter kernel (nbclient), and every figure shows once.

Cells tagged ``figure`` must carry exactly one PNG image output; no cell may show a
figure as text (``<Figure size …>``), which is what a notebook shows when the library
forces a non-inline backend.
"""

from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

NOTEBOOKS = sorted((Path(__file__).parent.parent / "examples").glob("*.ipynb"))


@pytest.mark.slow
@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_notebook_runs_and_shows_its_figures(path, tmp_path):
    nb = nbformat.read(path, as_version=4)
    NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}).execute()
    figure_cells = 0
    for i, cell in enumerate(nb.cells):
        if cell.cell_type != "code":
            continue
        outputs = cell.get("outputs", [])
        images = [o for o in outputs if "image/png" in o.get("data", {})]
        texts = "".join(o.get("data", {}).get("text/plain", "") + o.get("text", "") for o in outputs)
        assert "<Figure size" not in texts, f"{path.name} cell {i} shows a figure as text"
        if "figure" in cell.metadata.get("tags", []):
            figure_cells += 1
            assert len(images) == 1, f"{path.name} cell {i}: {len(images)} images, expected 1"
        else:
            assert not images, f"{path.name} cell {i} (not tagged 'figure') shows {len(images)} images"
    assert figure_cells > 0, f"{path.name} has no figure cells"


def test_spray_example_runs_as_its_docstring_says(tmp_path, capsys):
    """examples/spray_drops.py, as a user runs it (a shorter flight): it writes its figure and prints each size's
    error, the finest drop refused by Euler at 60 Hz by name."""
    import importlib.util

    from PIL import Image

    spec = importlib.util.spec_from_file_location("spray_drops", Path(__file__).parents[1] / "examples" / "spray_drops.py")
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    out = tmp_path / "spray.png"
    example.main(["--out", str(out), "--seconds", "0.3"])
    printed = capsys.readouterr().out
    assert Image.open(out).size == (960, 540)
    assert "0.05 mm, euler: dt" in printed and "euler_stable_dt" in printed
    assert printed.count("exponential: largest error") == 3 and printed.count("euler: largest error") == 2


def test_water_meshes_example_runs_as_its_docstring_says(tmp_path, capsys):
    """examples/water_meshes.py, as a user runs it (a small scene): the strip of four pictures over their errors,
    and each technique's cost and bands printed."""
    import importlib.util

    from PIL import Image

    spec = importlib.util.spec_from_file_location("water_meshes", Path(__file__).parents[1] / "examples" / "water_meshes.py")
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    out = tmp_path / "meshes.png"
    example.main(["--scene", "calm", "--out", str(out), "--width", "64", "--height", "48", "--texels", "64"])
    printed = capsys.readouterr().out
    assert Image.open(out).size == (4 * 64, 2 * 48)
    for technique in ("uniform", "clipmap", "projected"):
        assert f"{technique}: " in printed
    assert printed.count("height error ≤") >= 3 and "bare pixels" in printed

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

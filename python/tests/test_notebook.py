"""The example notebooks (docs/examples/*.ipynb) run: every code cell, top to bottom, in one
namespace, as a fresh Python process with matplotlib's Agg backend in an empty working folder.

The cells run through nbformat and exec, not through Jupyter (which CI does not install), so a
notebook must be plain Python (no IPython magics or shell escapes)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

REPOSITORY = Path(__file__).resolve().parents[2]
NOTEBOOKS = sorted((REPOSITORY / "docs" / "examples").glob("*.ipynb"))

# Run as `python RUNNER NOTEBOOK`: exits 1 naming the first cell that raises, with its source and
# traceback, on stderr.
RUNNER = r'''
import sys
import traceback

import nbformat

notebook = nbformat.read(sys.argv[1], as_version=4)
namespace = {"__name__": "__main__"}
cells = [cell for cell in notebook.cells if cell.cell_type == "code"]
for number, cell in enumerate(cells, start=1):
    try:
        exec(compile(cell.source, f"<code cell {number}>", "exec"), namespace)
    except BaseException:
        sys.stderr.write(
            f"code cell {number} of {len(cells)} raised.\n"
            f"--- its source ---\n{cell.source}\n--- traceback ---\n{traceback.format_exc()}"
        )
        sys.exit(1)
    try:  # figures a cell made are shown by Jupyter; here they only take memory
        import matplotlib.pyplot

        matplotlib.pyplot.close("all")
    except ImportError:
        pass
print(f"{len(cells)} code cells ran")
'''


def run_notebook(notebook: Path, workdir: Path) -> subprocess.CompletedProcess[str]:
    """Runs every code cell of `notebook` in a fresh Python process working in `workdir`."""
    runner = workdir / "run_notebook.py"
    runner.write_text(RUNNER, encoding="utf-8")
    env = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run(
        [sys.executable, str(runner), str(notebook)],
        cwd=workdir,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )


def test_there_are_example_notebooks():
    assert NOTEBOOKS, f"no notebooks in {REPOSITORY / 'docs' / 'examples'}"


@pytest.mark.parametrize("notebook", NOTEBOOKS, ids=[n.name for n in NOTEBOOKS])
def test_every_cell_of_the_notebook_runs(tmp_path, notebook):
    done = run_notebook(notebook, tmp_path)
    assert done.returncode == 0, (
        f"{notebook.relative_to(REPOSITORY)} failed:\n{done.stderr}\n{done.stdout}"
    )
    assert "code cells ran" in done.stdout


def test_a_failing_cell_fails_with_its_source_and_traceback(tmp_path):
    import nbformat
    from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

    broken = tmp_path / "broken.ipynb"
    nbformat.write(
        new_notebook(
            cells=[
                new_markdown_cell("# A notebook whose second cell raises"),
                new_code_cell("x = 1"),
                new_code_cell("y = x + undefined_name"),
                new_code_cell("z = 3"),
            ]
        ),
        broken,
    )
    done = run_notebook(broken, tmp_path)
    assert done.returncode == 1
    assert "code cell 2 of 3 raised" in done.stderr
    assert "y = x + undefined_name" in done.stderr
    assert "NameError" in done.stderr
    assert "code cells ran" not in done.stdout

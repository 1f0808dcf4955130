"""The notebooks in examples/ run from top to bottom on an IPython kernel (nbclient), one after
the other in one folder (as a user would: the later ones reuse the first's cached stages), and
are kept in the repository without outputs. Their output root (GEARKIT_OUTPUT_ROOT; for a user
../out, where ./run writes) starts with the default case's output as the executable left it (the
case test's): its cached stages verify and are reused, as they would be for a user who ran ./run
first."""
import glob
import os
import shutil

import nbformat
import pytest
from nbclient import NotebookClient

from conftest import PYTHON, SOURCE

NOTEBOOKS = sorted(glob.glob(os.path.join(SOURCE, "examples", "*.ipynb")))


def test_there_are_notebooks():
    assert len(NOTEBOOKS) >= 3


@pytest.mark.parametrize("path", NOTEBOOKS, ids=os.path.basename)
def test_stored_without_outputs(path):
    nb = nbformat.read(path, as_version=4)
    for cell in nb.cells:
        if cell.cell_type == "code":
            assert cell.outputs == [] and cell.execution_count is None, \
                f"{os.path.basename(path)}: outputs stored (clear them before committing)"


@pytest.fixture(scope="module")
def folder(tmp_path_factory, case_out):
    folder = str(tmp_path_factory.mktemp("notebooks"))
    default = os.path.join(case_out, "default")
    if os.path.isdir(default):
        shutil.copytree(default, os.path.join(folder, "out", "default"))
    return folder


@pytest.mark.parametrize("path", NOTEBOOKS, ids=os.path.basename)
def test_runs(path, folder, monkeypatch):
    # the kernel finds gearkit as the README says: PYTHONPATH=build/python
    monkeypatch.setenv("PYTHONPATH", PYTHON + os.pathsep + os.environ.get("PYTHONPATH", ""))
    # the notebooks' output root (../out beside examples/ for a user: where ./run writes)
    monkeypatch.setenv("GEARKIT_OUTPUT_ROOT", os.path.join(folder, "out"))
    nb = nbformat.read(path, as_version=4)
    NotebookClient(nb, timeout=900, kernel_name="python3",
                   resources={"metadata": {"path": folder}}).execute()
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs
              if o.output_type == "error"]
    assert errors == []

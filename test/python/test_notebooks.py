"""The tutorial notebooks of examples/notebooks/ run from the first cell to
the last (docs/python.md, "Notebooks").

Each notebook is executed by nbclient (Debian python3-nbclient) in a fresh
python3 kernel (python3-ipykernel), as Jupyter's "Run all" would: its cells
assert physical facts of the runs (the Sun held, angular momentum kept,
the Python law equal to the C flight software's), so a cell that raises
fails the test, which names the notebook and the cell. The kernel gets
PYTHONPATH at the folder of the `kestrel` package this test imports (the
build tree's python/ under ctest) and MPLBACKEND=Agg; its working folder is
a temporary one with a link to scenarios/, so nothing is written into the
source tree. The committed notebooks carry no outputs (small files, no
stale figures): checked here too.

Environment (ctest): PYTHONPATH at the build's python/ folder,
KESTREL_SOURCE_DIR.
"""
import importlib.util
import os
import tempfile
import unittest

import kestrel

# Debian python3-nbclient, python3-nbformat, python3-ipykernel; the notebooks
# plot with python3-matplotlib and tabulate with python3-pandas
NEEDED = ["nbclient", "nbformat", "ipykernel", "matplotlib", "pandas"]
MISSING = [m for m in NEEDED if importlib.util.find_spec(m) is None]
if not MISSING:
    import nbformat
    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionError

SRC = os.environ.get("KESTREL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
NB_DIR = os.path.join(SRC, "examples", "notebooks")
NOTEBOOKS = ["01_first_run.ipynb", "02_python_control_law.ipynb", "03_monte_carlo_pandas.ipynb"]
CELL_TIMEOUT = 120  # [s] one cell; each notebook takes seconds


def kernel_env():
    """The kernel's environment: this process's, with the kestrel package
    imported here first on PYTHONPATH and a headless Matplotlib."""
    env = dict(os.environ)
    pkg_parent = os.path.dirname(os.path.dirname(os.path.abspath(kestrel.__file__)))
    env["PYTHONPATH"] = os.pathsep.join(p for p in (pkg_parent, env.get("PYTHONPATH", "")) if p)
    env["MPLBACKEND"] = "Agg"
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    env["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"  # ipykernel's debugger: no frozen-modules warning
    return env


def failed_cell(nb):
    """(index, source) of the first cell with an error output, else None."""
    for i, cell in enumerate(nb.cells):
        if any(o.get("output_type") == "error" for o in cell.get("outputs", [])):
            return i, cell.source
    return None


def execute(nb, name):
    """Runs every cell of nb in a new kernel, in a temporary folder with a
    link to scenarios/. Returns None, or a message naming the failed cell."""
    with tempfile.TemporaryDirectory() as tmp:
        os.symlink(os.path.join(os.path.abspath(SRC), "scenarios"), os.path.join(tmp, "scenarios"))
        client = NotebookClient(nb, timeout=CELL_TIMEOUT, kernel_name="python3",
                                resources={"metadata": {"path": tmp}})
        try:
            client.execute(env=kernel_env())
        except CellExecutionError as e:
            where = failed_cell(nb)
            cell = "cell %d:\n%s\n" % where if where else ""
            return "%s: %s%s" % (name, cell, e)
    return None


@unittest.skipIf(MISSING, "needs %s (scripts/install-deps.sh host)" % ", ".join(MISSING))
class NotebooksRun(unittest.TestCase):
    def test_the_folder_holds_the_listed_notebooks(self):
        # a notebook added to the folder is added to NOTEBOOKS, so it is run
        found = sorted(f for f in os.listdir(NB_DIR) if f.endswith(".ipynb"))
        self.assertEqual(found, NOTEBOOKS)

    def test_committed_without_outputs(self):
        for name in NOTEBOOKS:
            nb = nbformat.read(os.path.join(NB_DIR, name), as_version=4)
            nbformat.validate(nb)
            self.assertEqual(nb.metadata.kernelspec.name, "python3", name)
            for i, cell in enumerate(nb.cells):
                if cell.cell_type == "code":
                    self.assertEqual((cell.outputs, cell.execution_count), ([], None),
                                     "%s cell %d has outputs: clear them before committing" % (name, i))

    def test_a_failing_cell_is_reported(self):
        # the runner itself: an assertion in a cell fails and is named
        nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("x = 1"),
                                             nbformat.v4.new_code_cell("assert x == 2, 'x is %d' % x"),
                                             nbformat.v4.new_code_cell("y = 3")])
        msg = execute(nb, "probe.ipynb")
        self.assertIsNotNone(msg)
        self.assertIn("probe.ipynb: cell 1:", msg)
        self.assertIn("x is 1", msg)
        # execution stopped at the failed cell
        self.assertEqual((nb.cells[2].outputs, nb.cells[2].execution_count), ([], None))


def _notebook_case(name):
    def test(self):
        nb = nbformat.read(os.path.join(NB_DIR, name), as_version=4)
        msg = execute(nb, name)
        if msg:
            self.fail(msg)
        self.assertTrue(all(c.execution_count for c in nb.cells if c.cell_type == "code"), name)
    return test


for _name in NOTEBOOKS:
    setattr(NotebooksRun, "test_" + _name.split(".")[0], _notebook_case(_name))


if __name__ == "__main__":
    unittest.main()

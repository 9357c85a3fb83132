"""The notebook-style example runs as a script (it cannot rot unnoticed)."""

import pathlib
import runpy


def test_notebook_example_runs(capsys):
    runpy.run_path(str(pathlib.Path(__file__).parents[1] / "examples" / "notebook.py"), run_name="__main__")
    out = capsys.readouterr().out
    assert "measurable range: mu0 in [0, 0.6426]" in out
    assert "Sweep(18 scenes, 0 with an error)" in out

"""Every example scenario solved from Python at CI size, through its script in examples/python
(meshes bounded by their convex hulls, as the C++ tests load them)."""
import pathlib
import subprocess
import sys

import pytest

SCRIPTS = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python"


@pytest.mark.parametrize("script", [
    "pick_and_place.py", "bartender.py", "tables.py", "move_and_stack.py",
    "remove_objects.py", "stacked.py", "circular_rearrange.py", "python_attachment.py",
    "python_pick.py",
])
def test_the_example_script_solves_and_verifies(script, tmp_path):
    command = [sys.executable, str(SCRIPTS / script), "--hulls"]
    if script != "python_attachment.py":
        command += ["--plan-out", str(tmp_path / "plan.json")]
    run = subprocess.run(command, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    if script != "python_attachment.py":
        assert (tmp_path / "plan.json").exists()
    assert "(" in run.stdout  # the plan tree

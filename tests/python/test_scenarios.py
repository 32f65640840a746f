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


def test_the_bimanual_assembly_solves_with_its_parts_joined(tmp_path):
    """The whole scenario on its decomposed meshes (the C++ tests' decomposition cache), without
    the verification on the original meshes, which takes minutes."""
    command = [sys.executable, str(SCRIPTS / "bimanual_assembly.py"), "--no-verify",
               "--time-limit", "300", "--plan-out", str(tmp_path / "plan.json")]
    run = subprocess.run(command, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "(assemblepipetree" in run.stdout
    assert "joined" in run.stdout
    assert (tmp_path / "plan.json").exists()

"""Bad input raises kaboum.InputError (a ValueError) with the CLI's one-line message naming the
file and position; Ctrl-C stops a long solve with KeyboardInterrupt."""
import os
import signal
import threading

import pytest

import kaboum
from conftest import DATA, GUARDED, example


def test_a_missing_scene_names_the_file():
    with pytest.raises(kaboum.InputError, match="no-such-scene.yaml"):
        kaboum.World("no-such-scene.yaml")
    assert issubclass(kaboum.InputError, ValueError)


def test_a_bad_scene_entry_names_its_line(tmp_path):
    scene = tmp_path / "scene.yaml"
    scene.write_text("settings:\n  epsilon: -1\n")
    with pytest.raises(kaboum.InputError, match=r"scene.yaml:2:\d+"):
        kaboum.World(str(scene))


def test_bad_pddl_names_the_file_line_and_column(pick_and_place, tmp_path):
    problem = tmp_path / "problem.pddl"
    problem.write_text("(define (problem p) (:domain pick-and-place)\n  (:objects kr5 - robot)\n"
                       "  (:init (nosuchpredicate kr5))\n  (:goal (handempty kr5)))\n")
    with pytest.raises(kaboum.InputError, match=r"problem.pddl:3:\d+"):
        kaboum.solve(pick_and_place, example("pick-and-place/domain.pddl"), str(problem))


@pytest.mark.parametrize("option, value, message", [
    ("search", "best", "search: expected one of gbfs, astar"),
    ("heuristic", "h", "heuristic: expected one of"),
    ("placement", "grid", "placement: expected one of random, quadtree, linear"),
    ("planner", "none", "planner: expected one of"),
    ("time_limit", 0.0, "time_limit: expected a positive number"),
    ("samples", 0, "samples: expected 1 to 1000"),
])
def test_a_bad_option_names_it(pick_and_place, option, value, message):
    with pytest.raises(kaboum.InputError, match=message):
        kaboum.solve(pick_and_place, example("pick-and-place/domain.pddl"),
                     example("pick-and-place/problem.pddl"), **{option: value})


def test_bad_world_options_and_names(pick_and_place):
    with pytest.raises(kaboum.InputError, match="geometry: expected 'bounded' or 'exact'"):
        kaboum.World(example("pick-and-place/scene.yaml"), geometry="round")
    with pytest.raises(kaboum.InputError, match="--epsilon"):
        kaboum.World(example("pick-and-place/scene.yaml"), epsilon="-1")
    with pytest.raises(kaboum.InputError, match="scene.yaml: no robot named 'r2d2'"):
        pick_and_place.initial_state().configuration("r2d2")
    with pytest.raises(kaboum.InputError, match="no object named 'kr5'"):
        pick_and_place.initial_state().object_pose("kr5")


def test_ctrl_c_cancels_a_long_solve(pick_and_place):
    # The goal cannot be reached and every pick counts into a fluent: the states never run out,
    # only the time limit or Ctrl-C ends the search.
    timer = threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            kaboum.solve(pick_and_place, str(GUARDED / "guarded-domain.pddl"),
                         str(DATA / "unreachable-problem.pddl"), time_limit=600,
                         attachments={"mayPick": lambda call: True,
                                      "countPicks": lambda call: call.reads[0] + 1})
    finally:
        timer.cancel()

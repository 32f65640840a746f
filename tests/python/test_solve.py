"""kaboum.solve from Python: the plan tree, its certified paths as numpy arrays, the statistics
and the plan file, on the pick-and-place example."""
import json

import numpy as np
import pytest

import kaboum
from conftest import example


@pytest.fixture(scope="module")
def solution(pick_and_place):
    return kaboum.solve(pick_and_place, example("pick-and-place/domain.pddl"),
                        example("pick-and-place/problem.pddl"))


def test_the_plan_picks_then_places_and_passes_its_checks(solution):
    assert solution.solved, solution.message
    assert solution.status == "solved"
    pick = solution.nodes[solution.root]
    place = solution.nodes[pick.next]
    assert (pick.kind, pick.text) == ("action", "(pickup kr5 block left)")
    assert (place.kind, place.text) == ("action", "(putdown kr5 block right)")
    assert solution.nodes[place.next].kind == "goal"
    assert pick.on_false == -1
    assert "(pickup kr5 block left)" in solution.plan_text()


def test_every_motion_is_a_waypoint_array_that_continues_the_last(solution, pick_and_place):
    configuration = pick_and_place.initial_state().configuration("kr5")
    motions = 0
    node = solution.nodes[solution.root]
    while node.kind == "action":
        for action in node.geometry:
            assert action.procedure in ("pickUp", "putDown")
            for step in action.steps:
                if step.kind in ("grasp", "release"):
                    assert step.object == "block"
                    assert step.path.shape == (0, len(configuration))
                    continue
                assert step.robot == "kr5"
                assert step.path.dtype == np.float64
                assert step.path.shape[1] == len(configuration)
                np.testing.assert_allclose(step.path[0], configuration, atol=1e-9)
                configuration = step.path[-1]
                motions += 1
        node = solution.nodes[node.next]
    assert motions == 6


def test_states_of_the_plan_hold_the_block_between_pick_and_place(solution):
    pick = solution.nodes[solution.root].geometry[0]
    assert solution.state(pick.from_state).holder("block") is None
    held = solution.state(pick.to_state)
    assert held.holder("block") == "kr5"
    assert held.held("kr5") == ["block"]
    with pytest.raises(IndexError):
        solution.state(10**9)


def test_statistics_and_plan_file_are_the_cli_s(solution, tmp_path):
    statistics = solution.statistics
    assert statistics["geometry"] == "bounded"
    assert statistics["total_seconds"] > 0
    assert statistics["plan_actions"] == 2
    plan = solution.plan_file()
    assert plan["format"] == "kaboum-plan"
    assert plan["verification"]["passed"]
    path = tmp_path / "plan.json"
    solution.write_plan(str(path))
    assert json.loads(path.read_text())["nodes"] == plan["nodes"]


def test_the_viewer_page_of_the_plan(solution, tmp_path):
    page = tmp_path / "plan.html"
    summary = solution.write_page(str(page))
    assert summary["actions"] == 2 and summary["branches"] == 0
    assert page.read_text().startswith("<!doctype html>")
    with pytest.raises(kaboum.InputError, match="cannot write the page"):
        solution.write_page(str(tmp_path / "no-such-folder" / "plan.html"))


def test_the_same_seed_gives_the_same_paths(pick_and_place, solution):
    again = kaboum.solve(pick_and_place, example("pick-and-place/domain.pddl"),
                         example("pick-and-place/problem.pddl"))
    first = solution.nodes[solution.root].geometry[0].steps[0].path
    np.testing.assert_array_equal(again.nodes[again.root].geometry[0].steps[0].path, first)


def test_a_time_limit_reached_is_a_status_not_an_exception(pick_and_place):
    result = kaboum.solve(pick_and_place, example("pick-and-place/domain.pddl"),
                          example("pick-and-place/problem.pddl"), node_limit=1, integrated=True)
    assert not result.solved
    assert result.status == "node-limit"
    assert result.root == -1


def test_execution_times_the_paths_as_trajectories(solution, pick_and_place):
    run = solution.execute()
    assert run.reached_goal
    names = [name for name, start, end in run.actions]
    assert names == ["(pickup kr5 block left)", "(putdown kr5 block right)"]
    times, positions, velocities, accelerations = run.trajectory("kr5", rate=100)
    assert times[0] == 0 and times[-1] == pytest.approx(run.duration)
    assert positions.shape == velocities.shape == accelerations.shape == (len(times), 6)
    np.testing.assert_allclose(positions[0], pick_and_place.initial_state().configuration("kr5"))
    np.testing.assert_allclose(velocities[0], 0, atol=1e-12)  # rest to rest
    last = solution.nodes[solution.nodes[solution.root].next].geometry[0].steps[-1].path[-1]
    np.testing.assert_allclose(positions[-1], last, atol=1e-9)


def test_a_sensing_callback_chooses_the_branch_executed():
    from conftest import world
    bartender = world("bartender/scene.yaml")
    solution = kaboum.solve(bartender, example("bartender/domain.pddl"),
                            example("bartender/problem-1.pddl"), search="astar")
    assert solution.solved, solution.message
    assert any(node.kind == "branch" for node in solution.nodes)
    empty = solution.execute(lambda test: True)
    full = solution.execute(lambda test: False)
    assert empty.sensed[0][:2] == ("(isemptybottle o1)", True)
    assert full.sensed[0][:2] == ("(isemptybottle o1)", False)
    assert len(empty.actions) > len(full.actions)
    with pytest.raises(kaboum.InputError, match="no sensing source"):
        solution.execute()

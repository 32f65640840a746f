"""Attachments written in Python: a condition checker and an effect applicator that change the
outcome of a solve, the geometric state and utilities they are given, and their errors."""
import numpy as np
import pytest

import kaboum
from conftest import GUARDED


def solve(world, **attachments):
    return kaboum.solve(world, str(GUARDED / "guarded-domain.pddl"),
                        str(GUARDED / "guarded-problem.pddl"), attachments=attachments)


def count(call):
    return call.reads[0] + 1


def module_calls(solution, name):
    return next(m["calls"] for m in solution.statistics["modules"] if m["name"] == name)


def test_a_checker_that_allows_the_pick_solves(pick_and_place):
    solution = solve(pick_and_place, mayPick=lambda call: True, countPicks=count)
    assert solution.solved, solution.message
    assert module_calls(solution, "allowed") >= 1
    assert module_calls(solution, "count") >= 1


def test_a_checker_that_forbids_the_pick_leaves_no_plan(pick_and_place):
    solution = solve(pick_and_place, mayPick=lambda call: False, countPicks=count)
    assert not solution.solved
    assert solution.status == "unsolvable"


def test_an_infeasible_effect_leaves_no_plan(pick_and_place):
    solution = solve(pick_and_place, mayPick=lambda call: True, countPicks=lambda call: None)
    assert solution.status == "unsolvable"


def test_the_checker_sees_the_geometric_state_and_the_kinematics(pick_and_place):
    seen = []

    def may_pick(call):
        robot, item = call.args
        state = call.state
        assert call.world.robots == ["kr5"]
        pose = state.object_pose(item)
        tool = call.world.tool_pose(state, robot)
        seen.append((robot, item, pose[:3, 3].copy(), state.holder(item), tool.shape))
        return True

    assert solve(pick_and_place, mayPick=may_pick, countPicks=count).solved
    robot, item, position, holder, tool_shape = seen[0]
    assert (robot, item, holder, tool_shape) == ("kr5", "block", None, (4, 4))
    initial = pick_and_place.initial_state().object_pose("block")[:3, 3]
    np.testing.assert_allclose(position, initial)


def test_an_exception_in_an_attachment_is_raised_by_solve(pick_and_place):
    def broken(call):
        raise ZeroDivisionError("broken checker")

    with pytest.raises(ZeroDivisionError, match="broken checker"):
        solve(pick_and_place, mayPick=broken, countPicks=count)


def test_an_effect_returning_the_wrong_number_of_values_is_a_value_error(pick_and_place):
    with pytest.raises(ValueError, match="'countPicks' returned 2 value"):
        solve(pick_and_place, mayPick=lambda call: True, countPicks=lambda call: (1.0, 2.0))


def test_an_attachment_that_is_not_callable_is_an_input_error(pick_and_place):
    with pytest.raises(kaboum.InputError, match=r"attachments\['mayPick'\]: expected a callable"):
        solve(pick_and_place, mayPick=3, countPicks=count)

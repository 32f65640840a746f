"""Geometric effects written in Python: a Transition of certified motions, gripper events and joins
recorded as an action's geometry, carried by the plan and verified as the C++ effects' geometry
is; constraint sampling (Table 5.1); the progress callback of a long solve."""
import importlib.util
import json

import numpy as np
import pytest

import kaboum
from conftest import DATA, EXAMPLES, GUARDED, example, world


def load_example(name):
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / "python" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


python_pick = load_example("python_pick")


@pytest.fixture(scope="module")
def picked(pick_and_place):
    return python_pick.solve(pick_and_place)


def motion_kinds(action):
    return [step.kind for step in action.steps]


def test_a_python_pick_is_carried_by_the_plan_and_verified(picked, pick_and_place):
    assert picked.solved, picked.message
    pick = picked.nodes[picked.root]
    assert pick.text == "(pickup kr5 block left)"
    [geometry] = pick.geometry
    assert (geometry.procedure, geometry.arguments) == ("pyPick", ["kr5", "block"])
    assert motion_kinds(geometry) == ["transit", "approach", "grasp", "retreat"]
    start = pick_and_place.initial_state().configuration("kr5")
    np.testing.assert_allclose(geometry.steps[0].path[0], start)
    reached = picked.state(geometry.to_state)
    assert reached.holder("block") == "kr5"
    initial = pick_and_place.initial_state().object_pose("block")[:3, 3]
    np.testing.assert_allclose(reached.object_pose("block")[:3, 3],
                               initial + [0.0, 0.0, python_pick.APPROACH], atol=1e-3)
    # kaboum's putDown goes on from where the Python pick ended.
    [place] = picked.nodes[pick.next].geometry
    assert place.procedure == "putDown" and place.from_state == geometry.to_state
    np.testing.assert_allclose(place.steps[0].path[0], geometry.steps[-1].path[-1])
    plan = picked.plan_file()
    verification = plan["verification"]
    assert verification["passed"] and verification["colliding_paths"] == 0
    assert verification["paths"] == 3 + sum(1 for s in place.steps if len(s.path))
    assert '"procedure": "pyPick"' in json.dumps(plan["nodes"])
    execution = picked.execute()
    assert execution.reached_goal
    assert [name for name, _, _ in execution.actions] == [pick.text, picked.nodes[pick.next].text]


def reach_above_table(call):
    """[arrive ?r]: the tool centre point 20 cm above the table, its z axis vertical, by
    constraint sampling; a certified motion there."""
    (robot,) = call.args
    target = (0.45, 0.0, 0.1)
    constraints = [
        kaboum.Constraint("coincident", kaboum.Shape("point", robot=robot),
                          kaboum.Shape("point", target)),
        kaboum.Constraint("parallel", kaboum.Shape("line", robot=robot),
                          kaboum.Shape("line", target, (0.0, 0.0, 1.0))),
    ]
    for sample in call.world.sample_constraints(call.state, constraints, samples=8):
        if call.world.first_collision(sample):
            continue
        transition = call.transition()
        if transition.move(robot, sample.configuration(robot)).solved:
            return call.record(transition)
    return None


def solve_reach(world, **options):
    return kaboum.solve(world, str(DATA / "reach-domain.pddl"), str(DATA / "reach-problem.pddl"),
                        **options)


def test_a_domain_whose_only_geometric_effect_is_python(pick_and_place):
    solution = solve_reach(pick_and_place, attachments={"pyReach": reach_above_table},
                           geometric_effects=["pyReach"])
    assert solution.solved, solution.message
    [geometry] = solution.nodes[solution.root].geometry
    assert motion_kinds(geometry) == ["transit"]
    reached = solution.state(geometry.to_state)
    tool = pick_and_place.tool_pose(reached, "kr5")
    np.testing.assert_allclose(tool[:3, 3], [0.45, 0.0, 0.1], atol=1e-5)
    assert abs(abs(tool[2, 2]) - 1.0) < 1e-5
    assert solution.plan_file()["verification"]["paths"] == 1


def test_recording_needs_the_procedure_named_a_geometric_effect(pick_and_place):
    with pytest.raises(ValueError, match="attachment 'pyReach' records geometry: name it in "
                                         "kaboum.solve's geometric_effects"):
        solve_reach(pick_and_place, attachments={"pyReach": reach_above_table})
    with pytest.raises(kaboum.InputError,
                       match="geometric_effects: 'pyMissing' is not one of the attachments"):
        solve_reach(pick_and_place, attachments={"pyReach": reach_above_table},
                    geometric_effects=["pyMissing"])


def test_a_transition_from_another_state_is_refused(pick_and_place):
    def elsewhere(call):
        state = call.state.copy()
        state.set_configuration("kr5", state.configuration("kr5") + 0.1)
        return call.record(kaboum.Transition(state))

    with pytest.raises(ValueError, match="the transition does not start in the call's state"):
        solve_reach(pick_and_place, attachments={"pyReach": elsewhere},
                    geometric_effects=["pyReach"])


def test_a_python_effect_that_finds_nothing_leaves_no_plan(pick_and_place):
    solution = solve_reach(pick_and_place, attachments={"pyReach": lambda call: None},
                           geometric_effects=["pyReach"])
    assert solution.status == "unsolvable"


def test_a_transition_applies_its_steps_as_the_plan_replays_them(pick_and_place):
    state = pick_and_place.initial_state()
    transition = kaboum.Transition(state)
    goal = state.configuration("kr5") + np.array([0.3, 0.0, 0.0, 0.0, 0.0, 0.0])
    motion = transition.move("kr5", goal)
    assert motion.solved, motion.message
    assert transition.start == state
    np.testing.assert_allclose(transition.state.configuration("kr5"), goal)
    [step] = transition.steps
    assert (step.kind, step.robot, step.tool) == ("transit", "kr5", "gripper")
    np.testing.assert_allclose(step.path, motion.path)
    with pytest.raises(ValueError, match="robot 'kr5' does not hold object 'block'"):
        transition.release("kr5", "block")
    with pytest.raises(ValueError, match="object 'table' is not movable"):
        transition.grasp("kr5", "table")
    with pytest.raises(ValueError, match="kind: expected one of transit, transfer, approach, "
                                         "retreat, got 'jump'"):
        transition.move("kr5", goal, kind="jump")
    with pytest.raises(ValueError, match="the path starts 0.3 \\(joint 0\\) from where robot"):
        transition.follow("kr5", [state.configuration("kr5"), goal])
    assert len(transition.steps) == 1


def test_a_path_into_an_object_is_not_followed(pick_and_place):
    state = pick_and_place.initial_state()
    block = state.object_pose("block")
    down = block.copy()
    down[:3, :3] = np.diag([1.0, -1.0, -1.0])
    down[2, 3] -= 0.02
    inside = pick_and_place.inverse_kinematics(state, "kr5", down)[0]
    transition = kaboum.Transition(state)
    reason = transition.follow("kr5", [state.configuration("kr5"), inside])
    assert "goal" in reason
    assert transition.steps == [] and transition.state == state


def test_a_join_step_names_its_two_objects():
    scene = world("circular-rearrange/scene.yaml")
    transition = kaboum.Transition(scene.initial_state())
    transition.join("robot1", "o1", "o2")
    [step] = transition.steps
    assert (step.kind, step.object, step.joined_to) == ("join", "o1", "o2")
    with pytest.raises(ValueError, match="object 'table' is not movable"):
        transition.join("robot1", "o1", "table")
    with pytest.raises(ValueError, match="an object cannot be joined to itself"):
        transition.join("robot1", "o1", "o1")


def test_constraint_samples_satisfy_their_constraints(pick_and_place):
    state = pick_and_place.initial_state()
    table_top = kaboum.Shape("plane", (0.45, 0.0, -0.1), (0.0, 0.0, 1.0))
    constraints = [
        kaboum.Constraint("distance", kaboum.Shape("point", robot="kr5"), table_top, 0.15),
        kaboum.Constraint("parallel", kaboum.Shape("plane", robot="kr5", tool="gripper"),
                          table_top),
    ]
    samples = pick_and_place.sample_constraints(state, constraints, samples=5, seed=3)
    assert len(samples) == 5
    for sample in samples:
        assert sample.configuration("kr5").shape == (6,)
        tool = pick_and_place.tool_pose(sample, "kr5")
        assert abs(abs(tool[2, 3] + 0.1) - 0.15) < 1e-5
        assert abs(abs(tool[2, 2]) - 1.0) < 1e-5
    again = pick_and_place.sample_constraints(state, constraints, samples=5, seed=3)
    assert again == samples
    other = pick_and_place.sample_constraints(state, constraints, samples=5, seed=4)
    assert other != samples


def test_constraint_errors_name_what_is_wrong(pick_and_place):
    point = kaboum.Shape("point", robot="kr5")
    plane = kaboum.Shape("plane")
    with pytest.raises(kaboum.InputError, match=r"Distance\(Plane, Point\) is not a defined "
                                                r"constraint \(Table 5.1\)"):
        kaboum.Constraint("distance", plane, point, 0.1)
    with pytest.raises(kaboum.InputError, match="type: expected one of coincident"):
        kaboum.Constraint("touching", point, plane)
    with pytest.raises(kaboum.InputError, match="kind: expected one of point, line, plane"):
        kaboum.Shape("circle")
    with pytest.raises(ValueError, match="point: expected 3 values"):
        kaboum.Shape("point", (0.0, 1.0))
    state = pick_and_place.initial_state()
    fixed = kaboum.Constraint("coincident", kaboum.Shape("point"), plane)
    with pytest.raises(ValueError, match="no shape is on a robot's tool"):
        pick_and_place.sample_constraints(state, [fixed])
    with pytest.raises(kaboum.InputError, match="no robot named 'r2d2'"):
        pick_and_place.sample_constraints(
            state, [kaboum.Constraint("coincident", kaboum.Shape("point", robot="r2d2"), plane)])


def test_progress_reports_a_long_solve_and_can_stop_it(pick_and_place):
    reports = []

    def progress(figures):
        reports.append((figures.seconds, figures.expanded, figures.geometric_states,
                        figures.motion_queries, figures.failures))
        return len(reports) < 3

    solution = kaboum.solve(pick_and_place, str(GUARDED / "guarded-domain.pddl"),
                            str(DATA / "unreachable-problem.pddl"), time_limit=60,
                            progress=progress, progress_period=0.05,
                            attachments={"mayPick": lambda call: True,
                                         "countPicks": lambda call: call.reads[0] + 1})
    assert solution.status == "cancelled"
    assert len(reports) == 3
    seconds = [report[0] for report in reports]
    assert seconds == sorted(seconds) and seconds[0] >= 0.05
    assert all(report[2] >= 1 for report in reports)
    assert reports[-1][1] >= reports[0][1] > 0
    with pytest.raises(kaboum.InputError, match="progress_period: expected a positive number"):
        kaboum.solve(pick_and_place, example("pick-and-place/domain.pddl"),
                     example("pick-and-place/problem.pddl"), progress=print, progress_period=0)

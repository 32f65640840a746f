"""A geometric effect written in Python (docs/python.md): pick and place whose pick is the Python
function `pick` below — inverse kinematics for a grasp from above, a certified motion to the
pre-grasp, a Cartesian approach, the grasp and a Cartesian lift, recorded as the action's geometry
— while the place stays kaboum's putDown. The plan carries the Python pick's motions, and solve
verifies them on the original meshes as it verifies every other path."""
import argparse
import pathlib

import numpy as np

import kaboum

HERE = pathlib.Path(__file__).resolve().parent
PICK_AND_PLACE = HERE.parent / "pick-and-place"
# Metres: the grasp's tool centre point above the object's centre, and how far the hand comes
# down to the grasp and lifts the object after it.
GRASP_HEIGHT = 0.01
APPROACH = 0.05


def raised(pose: np.ndarray, height: float) -> np.ndarray:
    """`pose` moved `height` metres up (world z)."""
    moved = pose.copy()
    moved[2, 3] += height
    return moved


def grasps_from_above(object_pose: np.ndarray, turns: int = 4):
    """Tool poses grasping the object from above: the tool's z axis down, GRASP_HEIGHT above the
    centre, turned about the vertical in `turns` steps of a half turn (the gripper is
    symmetric)."""
    for angle in np.linspace(0.0, np.pi, turns, endpoint=False):
        c, s = np.cos(angle), np.sin(angle)
        pose = np.eye(4)
        pose[:3, :3] = np.array([[c, s, 0.0], [s, -c, 0.0], [0.0, 0.0, -1.0]])
        pose[:3, 3] = object_pose[:3, 3] + [0.0, 0.0, GRASP_HEIGHT]
        yield pose


def pick(call: kaboum.AttachmentCall):
    """[grasp ?r ?o]: the first grasp from above whose pre-grasp has a collision-free IK solution
    reached by a certified motion, then approached, grasped and lifted along certified lines.
    Returns the identifier of the state reached, or None (the pick is infeasible here)."""
    robot, item = call.args
    world, state = call.world, call.state
    for grasp in grasps_from_above(state.object_pose(item)):
        for q in world.inverse_kinematics(state, robot, raised(grasp, APPROACH)):
            at_pre_grasp = state.copy()
            at_pre_grasp.set_configuration(robot, q)
            if world.first_collision(at_pre_grasp):
                continue
            transition = call.transition()
            if not transition.move(robot, q).solved:
                continue
            if not transition.line(robot, grasp, kind="approach").solved:
                continue
            transition.grasp(robot, item)
            if transition.line(robot, raised(grasp, APPROACH), kind="retreat").solved:
                return call.record(transition)
    return None


def solve(world: kaboum.World) -> kaboum.Solution:
    return kaboum.solve(world, str(HERE / "python-pick-domain.pddl"),
                        str(PICK_AND_PLACE / "problem.pddl"),
                        attachments={"pyPick": pick}, geometric_effects=["pyPick"])


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--hulls", action="store_true", help="convex hulls instead of the "
                        "decomposition (fast and coarse)")
    parser.add_argument("--plan-out", metavar="FILE", help="write the plan file (JSON)")
    args = parser.parse_args()
    world = kaboum.World(str(PICK_AND_PLACE / "scene.yaml"),
                         pieces="hulls" if args.hulls else "decomposition")
    solution = solve(world)
    if not solution.solved:
        raise SystemExit(f"python_pick: {solution.message}")
    if args.plan_out:
        solution.write_plan(args.plan_out)
    print(solution.plan_text())
    for node in solution.nodes:
        for action in node.geometry:
            steps = ", ".join(f"{step.kind} {len(step.path)}" for step in action.steps)
            print(f"{node.text}: {action.procedure}: {steps}")
    print(f"{solution.plan_file()['verification']['paths']} path(s) verified on the original "
          "meshes")

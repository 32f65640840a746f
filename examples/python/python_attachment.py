"""Attachments written in Python (docs/python.md): pick and place with a condition checker that
allows a pick only while the block stands within the arm's reach — measured in the geometric
state with forward kinematics — and an effect applicator that counts the picks into a fluent."""
import argparse
import pathlib

import numpy as np

import kaboum

HERE = pathlib.Path(__file__).resolve().parent
PICK_AND_PLACE = HERE.parent / "pick-and-place"


def within_reach(reach: float):
    """The checker of [allowed ?r ?o]: the object's centre is within `reach` metres of the robot's
    tool centre point in the geometric state of the call."""
    def may_pick(call: kaboum.AttachmentCall) -> bool:
        robot, item = call.args
        state = call.state
        tool = call.world.tool_pose(state, robot)
        return bool(np.linalg.norm(state.object_pose(item)[:3, 3] - tool[:3, 3]) < reach)
    return may_pick


def count_picks(call: kaboum.AttachmentCall) -> float:
    """[count ?r]: (picks) + 1."""
    return call.reads[0] + 1

if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--reach", type=float, default=1.0, help="metres (default 1.0)")
    parser.add_argument("--hulls", action="store_true", help="convex hulls instead of the "
                        "decomposition (fast and coarse)")
    args = parser.parse_args()
    world = kaboum.World(str(PICK_AND_PLACE / "scene.yaml"),
                         pieces="hulls" if args.hulls else "decomposition")
    solution = kaboum.solve(world, str(HERE / "guarded-domain.pddl"),
                            str(HERE / "guarded-problem.pddl"),
                            attachments={"mayPick": within_reach(args.reach), "countPicks": count_picks})
    print(solution.plan_text() if solution.solved else solution.message)
    for module in solution.statistics["modules"]:
        print(f"{module['name']}: {module['calls']} call(s), {module['seconds'] * 1e3:.3f} ms")

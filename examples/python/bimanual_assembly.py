"""The Bimanual Assembly (examples/bimanual-assembly): two Comau arms assemble a gearbox from two
bearings, a pipe and a tree. Depth-first search solves it in seconds (README there); the
verification of its paths on the original meshes takes minutes, so it may be skipped. The search's
progress goes to stderr through the progress callback. The meshes are decomposed (convex hulls are
too coarse for the fits) through the decomposition cache ($KABOUM_CACHE_DIR, else the user's)."""
import argparse
import pathlib
import sys

import kaboum

HERE = pathlib.Path(__file__).resolve().parent.parent / "bimanual-assembly"


def report(figures: kaboum.Progress) -> None:
    """The progress line `kaboum solve` prints."""
    print(f"bimanual_assembly: {figures.seconds:.0f} s, {figures.expanded} expanded, "
          f"{figures.geometric_states} geometric state(s), {figures.motion_queries} motion "
          f"query(ies), {figures.failures} failed geometric call(s)", file=sys.stderr)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--time-limit", type=float, default=1200, help="seconds (default 1200)")
    parser.add_argument("--no-verify", action="store_true",
                        help="skip replaying the paths on the original meshes (minutes)")
    parser.add_argument("--plan-out", metavar="FILE", help="write the plan file (JSON)")
    args = parser.parse_args()
    world = kaboum.World(str(HERE / "scene.yaml"))
    solution = kaboum.solve(world, str(HERE / "domain.pddl"), str(HERE / "problem.pddl"),
                            search="dfs", time_limit=args.time_limit, verify=not args.no_verify,
                            progress=report)
    if solution.status != "solved":
        raise SystemExit(f"bimanual_assembly: {solution.message}")
    print(solution.plan_text())
    order, open_nodes = [], [solution.root]
    while open_nodes:  # the plan's nodes from its root
        index = open_nodes.pop()
        if index >= 0 and index not in order:
            order.append(index)
            open_nodes += [solution.nodes[index].on_false, solution.nodes[index].next]
    for node in (solution.nodes[index] for index in order):
        for action in node.geometry:
            joins = [f"{step.object} into {step.joined_to}" for step in action.steps
                     if step.kind == "join"]
            print(f"{action.procedure}({', '.join(action.arguments)}): {len(action.steps)} "
                  f"step(s)" + (f", joined {', '.join(joins)}" if joins else ""))
    if args.plan_out:
        solution.write_plan(args.plan_out)
    print(f"bimanual_assembly: {solution.statistics['total_seconds']:.1f} s, "
          f"{solution.plan_file()['verification']['paths']} path(s) verified")
    if not solution.solved:
        raise SystemExit(f"bimanual_assembly: {solution.message}")

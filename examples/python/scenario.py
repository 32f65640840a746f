"""What every example script here shares: its command line, loading the scene, solving as
`kaboum solve` does, and printing the plan with its statistics (docs/python.md)."""
import argparse
import pathlib
import sys

import kaboum

EXAMPLES = pathlib.Path(__file__).resolve().parent.parent


def solve_example(description: str, folder: str, domain: str, problem: str, scene: str,
                  **options) -> kaboum.Solution:
    """Solves examples/`folder`'s `domain` and `problem` in `scene` with the options of
    kaboum.solve, prints the plan tree and a summary, writes the plan file with --plan-out, and
    exits with 1 unless the plan is solved and verified."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--hulls", action="store_true",
                        help="bound every mesh by its convex hull instead of decomposing it "
                             "(fast and coarse: what the tests use)")
    parser.add_argument("--plan-out", metavar="FILE", help="write the plan file (JSON)")
    parser.add_argument("--quiet", action="store_true", help="print nothing but errors")
    args = parser.parse_args()
    here = EXAMPLES / folder
    world = kaboum.World(str(here / scene), pieces="hulls" if args.hulls else "decomposition")
    solution = kaboum.solve(world, str(here / domain), str(here / problem), **options)
    if args.plan_out and solution.solved:
        solution.write_plan(args.plan_out)
    if not args.quiet:
        if solution.solved:
            print(solution.plan_text())
        statistics = solution.statistics
        actions = sum(1 for node in solution.nodes if node.kind == "action")
        paths = sum(1 for node in solution.nodes for action in node.geometry
                    for step in action.steps if len(step.path))
        print(f"{folder}: {solution.status}, {actions} action node(s), {paths} certified "
              f"path(s), {solution.geometric_states} geometric state(s), "
              f"{statistics['total_seconds']:.2f} s")
    if not solution.solved:
        print(f"{folder}: {solution.message}", file=sys.stderr)
        sys.exit(1)
    return solution

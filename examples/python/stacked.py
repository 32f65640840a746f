"""The Stacked n Objects scenario with a mobile manipulator (examples/stacked), n = 4."""
from scenario import solve_example

if __name__ == "__main__":
    solve_example(__doc__, "stacked", "stacked-geometry-domain.pddl", "stacked-geometry-4.pddl",
                  "stacked-geometry-4.yaml", search="bfs", placement="quadtree", time_limit=120)

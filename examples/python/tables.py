"""Seed 004's Tables (examples/tables), Table I's problem class-1-01: a mobile manipulator among
three tables whose places hold one item each."""
from scenario import solve_example

if __name__ == "__main__":
    solve_example(__doc__, "tables", "domain.pddl", "class-1-01.pddl", "scene.yaml",
                  search="astar")

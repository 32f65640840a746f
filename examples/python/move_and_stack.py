"""Seed 003's MOVE AND STACK (examples/move-and-stack): a bottle stacked on a can because the tray
has no room beside it."""
from scenario import solve_example

if __name__ == "__main__":
    solve_example(__doc__, "move-and-stack", "domain.pddl", "problem-full.pddl", "scene.yaml",
                  search="astar", time_limit=120)

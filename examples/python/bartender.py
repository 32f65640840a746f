"""The Bartender (examples/bartender) with one bottle of unknown content: the plan branches on
sensing and hands the empty bottle over."""
from scenario import solve_example

if __name__ == "__main__":
    solve_example(__doc__, "bartender", "domain.pddl", "problem-1.pddl", "scene.yaml",
                  search="astar", time_limit=120)

"""REMOVE n OBJECTS (examples/remove-objects) with three objects in a line."""
from scenario import solve_example

if __name__ == "__main__":
    solve_example(__doc__, "remove-objects", "remove-objects-domain.pddl",
                  "remove-objects-line-3.pddl", "remove-objects-line-3.yaml")

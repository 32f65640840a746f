"""The Bimanual Circular Rearrange (examples/circular-rearrange) with three bottles."""
from scenario import solve_example

if __name__ == "__main__":
    solve_example(__doc__, "circular-rearrange", "domain.pddl", "problem-3.pddl", "scene.yaml")

"""Pick and place (examples/pick-and-place): one KUKA KR5 moves a block from the table's left
region to its right region."""
from scenario import solve_example

if __name__ == "__main__":
    solve_example(__doc__, "pick-and-place", "domain.pddl", "problem.pddl", "scene.yaml")

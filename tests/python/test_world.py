"""The scene from Python: geometric states and their numpy round trips, forward and inverse
kinematics, collisions, certified motions; meshes bounded and decomposed."""
import pathlib

import numpy as np
import pytest

import kaboum
from conftest import example


def test_names_and_the_initial_state(pick_and_place):
    assert pick_and_place.robots == ["kr5"]
    assert "block" in pick_and_place.objects
    assert pick_and_place.locations == ["left", "right"]
    assert pick_and_place.tools("kr5")
    state = pick_and_place.initial_state()
    assert pick_and_place.first_collision(state) is None
    assert state.holder("block") is None and state.held("kr5") == []


def test_placement_seed_chooses_the_layout_of_objects_placed_at_random(tmp_path):
    text = pathlib.Path(example("pick-and-place/scene.yaml")).read_text()
    pose = "    pose: {position: [0.45, 0.25, -0.075]}\n"
    assert pose in text
    scene = tmp_path / "scene.yaml"
    scene.write_text(text.replace(pose, "    place_in: left\n    resting_faces: [[0, 0, -1]]\n"))

    def block(seed):
        world = kaboum.World(str(scene), pieces="hulls", placement_seed=seed)
        return world.initial_state().object_pose("block")

    np.testing.assert_array_equal(block(3), block(3))
    assert not np.allclose(block(3), block(4))
    for seed in (3, 4):
        x, y = block(seed)[:2, 3]
        assert 0.3 < x < 0.6 and 0.1 < y < 0.4  # in the location 'left'


def test_a_configuration_round_trips_through_numpy(pick_and_place):
    state = pick_and_place.initial_state()
    q = state.configuration("kr5") + 0.1
    state.set_configuration("kr5", q)
    np.testing.assert_array_equal(state.configuration("kr5"), q)
    state.set_configuration("kr5", list(q))  # any sequence of numbers
    assert state != pick_and_place.initial_state()
    assert state.copy() == state
    with pytest.raises(ValueError, match="robot 'kr5' has 6 joints, got 2 values"):
        state.set_configuration("kr5", [0.0, 0.0])


def test_inverse_kinematics_reaches_the_forward_kinematics_pose(pick_and_place):
    state = pick_and_place.initial_state()
    q = state.configuration("kr5") + np.array([0.2, -0.1, 0.1, 0.3, 0.2, 0.1])
    moved = state.copy()
    moved.set_configuration("kr5", q)
    pose = pick_and_place.tool_pose(moved, "kr5")
    assert pose.shape == (4, 4)
    solutions = pick_and_place.inverse_kinematics(state, "kr5", pose)
    assert solutions
    for solution in solutions:
        reached = state.copy()
        reached.set_configuration("kr5", solution)
        np.testing.assert_allclose(pick_and_place.tool_pose(reached, "kr5"), pose, atol=1e-6)
    with pytest.raises(ValueError, match="last row"):
        pick_and_place.inverse_kinematics(state, "kr5", np.ones((4, 4)))


def test_a_collision_is_named_and_a_certified_motion_avoids_it(pick_and_place):
    state = pick_and_place.initial_state()
    block = state.object_pose("block")
    down = block.copy()
    down[:3, :3] = np.diag([1.0, -1.0, -1.0])  # the tool's z axis pointing down
    down[2, 3] -= 0.02  # into the block
    inside = pick_and_place.inverse_kinematics(state, "kr5", down)
    assert inside
    colliding = state.copy()
    colliding.set_configuration("kr5", inside[0])
    assert "collides with" in pick_and_place.first_collision(colliding)

    goal = state.configuration("kr5") + np.array([0.5, 0.0, 0.0, 0.0, 0.0, 0.0])
    motion = pick_and_place.plan_motion(state, "kr5", goal)
    assert motion.solved, motion.message
    np.testing.assert_allclose(motion.path[0], state.configuration("kr5"))
    np.testing.assert_allclose(motion.path[-1], goal)
    failed = pick_and_place.plan_motion(state, "kr5", inside[0])
    assert failed.status == "invalid-goal"
    assert failed.path.shape == (0, 6)

    assert pick_and_place.swept_collision(state, "kr5", motion.path) is None
    into_block = np.array([state.configuration("kr5"), inside[0]])
    assert "goal" in pick_and_place.swept_collision(state, "kr5", into_block)
    check = pick_and_place.verify_path(state, "kr5", motion.path)
    assert check.collision_free and check.samples > len(motion.path)
    assert check.clearance > 0
    hit = pick_and_place.verify_path(state, "kr5", into_block)
    assert not hit.collision_free
    assert "collides with" in hit.first_collision


def cube(size=1.0):
    vertices = np.array([[x, y, z] for x in (0, size) for y in (0, size) for z in (0, size)],
                        dtype=float)
    triangles = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                          [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return kaboum.Mesh(vertices, triangles)


def test_a_mesh_round_trips_through_numpy_and_a_file(tmp_path):
    mesh = cube()
    assert mesh.vertices.shape == (8, 3) and mesh.triangles.shape == (12, 3)
    path = tmp_path / "cube.obj"
    kaboum.write_mesh(mesh, str(path))
    again = kaboum.read_mesh(str(path))
    assert again.triangles.shape == (12, 3)
    assert abs(abs(again.volume) - 1.0) < 1e-9
    with pytest.raises(ValueError, match="vertex index 9 out of range"):
        kaboum.Mesh(mesh.vertices, [[0, 1, 9]])


def test_bound_and_decompose_contain_the_mesh():
    mesh = cube()
    outer = kaboum.bound(mesh, vertices=8)
    assert outer.volume >= mesh.volume - 1e-9
    pieces = kaboum.decompose(mesh, epsilon="3%")
    assert len(pieces) == 1
    assert abs(pieces[0].volume - 1.0) < 1e-6


def test_forward_kinematics_of_a_urdf_chain():
    urdf = example("robots/two-arm.urdf")
    with pytest.raises(kaboum.InputError, match="two-arm.urdf"):
        kaboum.forward_kinematics(urdf, [0.0])

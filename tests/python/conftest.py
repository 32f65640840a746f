"""Shared fixtures of the Python API's tests: the repository's examples, each scene loaded once."""
import os
import pathlib

import pytest

import kaboum

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
GUARDED = EXAMPLES / "python"
DATA = pathlib.Path(__file__).resolve().parent / "data"


def example(path: str) -> str:
    return str(EXAMPLES / path)


_worlds: dict = {}


def world(scene: str) -> kaboum.World:
    """The example scene, its meshes bounded by convex hulls (as the C++ tests load them)."""
    if scene not in _worlds:
        _worlds[scene] = kaboum.World(example(scene), pieces="hulls")
    return _worlds[scene]


@pytest.fixture(scope="session")
def pick_and_place() -> kaboum.World:
    return world("pick-and-place/scene.yaml")

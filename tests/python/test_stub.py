"""The type stub kaboum.pyi beside the module names every public function, class, method and
property of the module, and nothing it lacks, so that editors complete the real API."""
import ast
import pathlib

import kaboum


def stub_names():
    stub = pathlib.Path(kaboum.__file__).with_name("kaboum.pyi")
    tree = ast.parse(stub.read_text())
    names = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            names[node.name] = {item.name for item in node.body
                                if isinstance(item, ast.FunctionDef)}
        elif isinstance(node, ast.FunctionDef):
            names[node.name] = None
    return names


def public(names):
    return {name for name in names if not name.startswith("_")}


def test_the_stub_names_the_module_s_functions_and_classes():
    stub = stub_names()
    module = {name for name in public(dir(kaboum))
              if callable(getattr(kaboum, name)) or isinstance(getattr(kaboum, name), type)}
    assert module == set(stub)


def test_the_stub_names_every_method_and_property_of_each_class():
    for name, members in stub_names().items():
        if members is None:
            continue
        cls = getattr(kaboum, name)
        if issubclass(cls, Exception):
            continue
        own = public(vars(cls)) | ({"__init__"} if "__init__" in members else set())
        if "__eq__" in members:
            own |= {"__eq__", "__hash__"}
        assert public(members) | (members & {"__init__", "__eq__", "__hash__"}) == own, name

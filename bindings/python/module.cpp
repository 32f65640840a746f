// The module's entry point: every part bound in dependency order (errors first, then the scene,
// then what uses it).
#include "bindings.hpp"

PYBIND11_MODULE(kaboum, module) {
  module.doc() =
      "kaboum: robot task-and-motion planning (KABouM). Load a scene, solve a PDDL domain whose "
      "geometric preconditions and effects are kaboum's attachments or Python functions, and "
      "read the plan with its certified paths (docs/python.md).";
  kaboum::python::bindErrors(module);
  kaboum::python::bindWorld(module);
  kaboum::python::bindTransition(module);
  kaboum::python::bindConstraints(module);
  kaboum::python::bindSolve(module);
  kaboum::python::bindGeometry(module);
}

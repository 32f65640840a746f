// The Python module `kaboum` (docs/python.md): pybind11 bindings of the scene and its geometric
// states (thesis §6.1.1), the integrated planner (Chapter 6) with attachments written in Python
// (§3.3.2) and the geometry they record, constraint sampling (§5.2), and the mesh and kinematics
// tools (Chapters 4 and 5). One bind function per file.
#pragma once

#include <pybind11/pybind11.h>

namespace kaboum::python {

namespace py = pybind11;

void bindErrors(py::module_& module);
void bindWorld(py::module_& module);
void bindTransition(py::module_& module);
void bindConstraints(py::module_& module);
void bindSolve(py::module_& module);
void bindGeometry(py::module_& module);

}  // namespace kaboum::python

// Errors as Python exceptions with the library's messages: kaboum.InputError (a ValueError) for
// bad files, PDDL, scenes and options; std::invalid_argument becomes ValueError and
// std::out_of_range IndexError (pybind11's own translation).
#include "bindings.hpp"
#include "kaboum/core/error.hpp"

namespace kaboum::python {

void bindErrors(py::module_& module) {
  py::register_exception<InputError>(module, "InputError", PyExc_ValueError).doc() =
      "Bad input: a file, mesh, domain, problem, scene or option that cannot be used. The message "
      "names the file (with line and column where they apply) and what is wrong.";
}

}  // namespace kaboum::python

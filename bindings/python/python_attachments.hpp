// Procedures of a domain written in Python (thesis §3.3.2, semantic attachments; docs/python.md):
// a condition checker or an effect applicator is a Python callable given an AttachmentCall — the
// names of its arguments, the values of the fluents it reads, its sample, and the geometric state
// behind its first read value — registered beside the geometric attachments (thesis §6.1.2).
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "kaboum/symbolic/attachments.hpp"
#include "kaboum/tamp/geometric_attachments.hpp"
#include "scene_world.hpp"

namespace kaboum::python {

// What a Python procedure receives.
struct AttachmentCall {
  std::shared_ptr<SceneWorld> scene;
  const tamp::GeometricAttachments* attachments = nullptr;
  py::tuple args;   // names of the arguments' objects
  py::tuple reads;  // values of the fluents the module reads, in declaration order
  std::uint32_t sample = 0;
};

class PythonAttachments {
 public:
  // `procedures` maps a procedure name (as the domain's :modules name it) to a callable. Throws
  // InputError naming the procedure for a value that is not callable.
  PythonAttachments(std::shared_ptr<SceneWorld> scene, const py::dict& procedures);

  // Registers every procedure as a condition checker and an effect applicator of that name (the
  // module's kind picks one): a checker's result is taken as a truth value; an effect returns
  // None or False when it is infeasible, else a number or a sequence of one number per fluent it
  // writes. Called without the GIL; each call takes it.
  void registerProcedures(const tamp::GeometricAttachments& attachments,
                          symbolic::ProcedureRegistry& registry);

 private:
  py::object call(const py::object& procedure, const symbolic::AttachmentArgs& args);
  bool check(const py::object& procedure, const symbolic::AttachmentArgs& args);
  bool apply(const std::string& name, const py::object& procedure,
             const symbolic::AttachmentArgs& args, std::span<double> writes);

  std::shared_ptr<SceneWorld> scene_;
  std::vector<std::pair<std::string, py::object>> procedures_;
  const tamp::GeometricAttachments* attachments_ = nullptr;
  std::vector<py::object> objectNames_;  // by ObjectId, made on first use
};

}  // namespace kaboum::python

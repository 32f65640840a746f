// Procedures of a domain written in Python (thesis §3.3.2, semantic attachments; docs/python.md):
// a condition checker or an effect applicator is a Python callable given an AttachmentCall — the
// names of its arguments, the values of the fluents it reads, its sample, and the geometric state
// behind its first read value — registered beside the geometric attachments (thesis §6.1.2). A
// geometric effect records the geometry that leads to the state it returns.
#pragma once

#include <pybind11/pybind11.h>

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "kaboum/symbolic/attachments.hpp"
#include "kaboum/tamp/geometric_attachments.hpp"
#include "scene_world.hpp"

namespace kaboum::python {

class PythonAttachments;

// What a Python procedure receives.
struct AttachmentCall {
  PythonAttachments* owner = nullptr;
  const std::string* procedure = nullptr;
  py::tuple args;   // names of the arguments' objects
  py::tuple reads;  // values of the fluents the module reads, in declaration order
  std::uint32_t sample = 0;
};

class PythonAttachments {
 public:
  // `procedures` maps a procedure name (as the domain's :modules name it) to a callable;
  // `geometricEffects` names those that record geometry (AttachmentCall::record); their motions
  // stop when `cancel` is set. Throws InputError naming the procedure for a value that is not
  // callable or a geometric effect that is not among them.
  PythonAttachments(std::shared_ptr<SceneWorld> scene, const py::dict& procedures,
                    std::vector<std::string> geometricEffects,
                    std::shared_ptr<std::atomic<bool>> cancel);

  // Registers every procedure as a condition checker and an effect applicator of that name (the
  // module's kind picks one): a checker's result is taken as a truth value; an effect returns
  // None or False when it is infeasible, else a number or a sequence of one number per fluent it
  // writes. Called without the GIL; each call takes it.
  void registerProcedures(tamp::GeometricAttachments& attachments,
                          symbolic::ProcedureRegistry& registry);

  [[nodiscard]] const std::shared_ptr<SceneWorld>& scene() const { return scene_; }
  [[nodiscard]] tamp::GeometricAttachments& attachments() const { return *attachments_; }
  [[nodiscard]] const std::shared_ptr<std::atomic<bool>>& cancel() const { return cancel_; }
  [[nodiscard]] const std::vector<std::string>& geometricEffects() const {
    return geometricEffects_;
  }
  // The identifier of the geometric state a call reads first; ValueError for another value.
  [[nodiscard]] std::size_t stateId(const AttachmentCall& call) const;

 private:
  py::object call(const std::string& name, const py::object& procedure,
                  const symbolic::AttachmentArgs& args);
  bool check(const std::string& name, const py::object& procedure,
             const symbolic::AttachmentArgs& args);
  bool apply(const std::string& name, const py::object& procedure,
             const symbolic::AttachmentArgs& args, std::span<double> writes);

  std::shared_ptr<SceneWorld> scene_;
  std::vector<std::pair<std::string, py::object>> procedures_;
  std::vector<std::string> geometricEffects_;
  std::shared_ptr<std::atomic<bool>> cancel_;
  tamp::GeometricAttachments* attachments_ = nullptr;
  std::vector<py::object> objectNames_;  // by ObjectId, made on first use
};

}  // namespace kaboum::python

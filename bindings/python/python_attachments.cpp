#include "python_attachments.hpp"

#include <fmt/format.h>

#include "kaboum/core/error.hpp"

namespace kaboum::python {

PythonAttachments::PythonAttachments(std::shared_ptr<SceneWorld> scene, const py::dict& procedures)
    : scene_(std::move(scene)) {
  for (const auto& [name, procedure] : procedures) {
    const std::string key = py::str(name);
    if (!PyCallable_Check(procedure.ptr())) {
      throw InputError(fmt::format("attachments['{}']: expected a callable, got {}", key,
                                   py::str(py::type::of(procedure)).cast<std::string>()));
    }
    procedures_.emplace_back(key, py::reinterpret_borrow<py::object>(procedure));
  }
}

void PythonAttachments::registerProcedures(const tamp::GeometricAttachments& attachments,
                                           symbolic::ProcedureRegistry& registry) {
  attachments_ = &attachments;
  for (const auto& [name, procedure] : procedures_) {
    const py::object* callable = &procedure;
    const std::string* procedureName = &name;
    registry.addChecker(name, [this, callable](const symbolic::AttachmentArgs& args) {
      return check(*callable, args);
    });
    registry.addApplicator(name,
                           [this, callable, procedureName](const symbolic::AttachmentArgs& args,
                                                           std::span<double> writes) {
                             return apply(*procedureName, *callable, args, writes);
                           });
  }
}

py::object PythonAttachments::call(const py::object& procedure,
                                   const symbolic::AttachmentArgs& args) {
  py::tuple names(args.objects.size());
  for (std::size_t i = 0; i < args.objects.size(); ++i) {
    const auto id = static_cast<std::size_t>(args.objects[i]);
    if (id >= objectNames_.size()) objectNames_.resize(args.objectNames->size());
    if (!objectNames_[id]) objectNames_[id] = py::str((*args.objectNames)[id]);
    names[i] = objectNames_[id];
  }
  py::tuple reads(args.reads.size());
  for (std::size_t i = 0; i < args.reads.size(); ++i) reads[i] = py::float_(args.reads[i]);
  return procedure(
      AttachmentCall{scene_, attachments_, std::move(names), std::move(reads), args.sample});
}

bool PythonAttachments::check(const py::object& procedure, const symbolic::AttachmentArgs& args) {
  py::gil_scoped_acquire locked;
  return py::bool_(call(procedure, args));
}

bool PythonAttachments::apply(const std::string& name, const py::object& procedure,
                              const symbolic::AttachmentArgs& args, std::span<double> writes) {
  py::gil_scoped_acquire locked;
  const py::object result = call(procedure, args);
  if (result.is_none() || (py::isinstance<py::bool_>(result) && !result.cast<bool>())) {
    return false;
  }
  if (py::isinstance<py::sequence>(result)) {
    const auto values = result.cast<py::sequence>();
    if (values.size() != writes.size()) {
      throw std::invalid_argument(
          fmt::format("attachment '{}' returned {} value(s) for the {} fluent(s) its module writes",
                      name, values.size(), writes.size()));
    }
    for (std::size_t i = 0; i < writes.size(); ++i) writes[i] = values[i].cast<double>();
    return true;
  }
  if (writes.size() != 1) {
    throw std::invalid_argument(
        fmt::format("attachment '{}' returned one value for the {} fluent(s) its module writes",
                    name, writes.size()));
  }
  writes[0] = result.cast<double>();
  return true;
}

}  // namespace kaboum::python

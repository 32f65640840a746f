#include "python_attachments.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "kaboum/core/error.hpp"

namespace kaboum::python {

PythonAttachments::PythonAttachments(std::shared_ptr<SceneWorld> scene, const py::dict& procedures,
                                     std::vector<std::string> geometricEffects,
                                     std::shared_ptr<std::atomic<bool>> cancel)
    : scene_(std::move(scene)),
      geometricEffects_(std::move(geometricEffects)),
      cancel_(std::move(cancel)) {
  for (const auto& [name, procedure] : procedures) {
    const std::string key = py::str(name);
    if (!PyCallable_Check(procedure.ptr())) {
      throw InputError(fmt::format("attachments['{}']: expected a callable, got {}", key,
                                   py::str(py::type::of(procedure)).cast<std::string>()));
    }
    procedures_.emplace_back(key, py::reinterpret_borrow<py::object>(procedure));
  }
  for (const std::string& name : geometricEffects_) {
    if (std::none_of(procedures_.begin(), procedures_.end(),
                     [&](const auto& procedure) { return procedure.first == name; })) {
      throw InputError(
          fmt::format("geometric_effects: '{}' is not one of the attachments given", name));
    }
  }
}

std::size_t PythonAttachments::stateId(const AttachmentCall& call) const {
  const double id = call.reads.empty() ? -1.0 : call.reads[0].cast<double>();
  if (!(id >= 0) || id != std::floor(id) || id >= static_cast<double>(attachments_->map().size())) {
    throw std::invalid_argument(
        "the module's first read value is no geometric state identifier: read the geometric "
        "state fluent first, e.g. :reads ((geometry))");
  }
  return static_cast<std::size_t>(id);
}

void PythonAttachments::registerProcedures(tamp::GeometricAttachments& attachments,
                                           symbolic::ProcedureRegistry& registry) {
  attachments_ = &attachments;
  for (const auto& [name, procedure] : procedures_) {
    const py::object* callable = &procedure;
    const std::string* procedureName = &name;
    registry.addChecker(name,
                        [this, callable, procedureName](const symbolic::AttachmentArgs& args) {
                          return check(*procedureName, *callable, args);
                        });
    registry.addApplicator(name,
                           [this, callable, procedureName](const symbolic::AttachmentArgs& args,
                                                           std::span<double> writes) {
                             return apply(*procedureName, *callable, args, writes);
                           });
  }
}

py::object PythonAttachments::call(const std::string& name, const py::object& procedure,
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
  return procedure(AttachmentCall{this, &name, std::move(names), std::move(reads), args.sample});
}

bool PythonAttachments::check(const std::string& name, const py::object& procedure,
                              const symbolic::AttachmentArgs& args) {
  py::gil_scoped_acquire locked;
  return py::bool_(call(name, procedure, args));
}

bool PythonAttachments::apply(const std::string& name, const py::object& procedure,
                              const symbolic::AttachmentArgs& args, std::span<double> writes) {
  py::gil_scoped_acquire locked;
  const py::object result = call(name, procedure, args);
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

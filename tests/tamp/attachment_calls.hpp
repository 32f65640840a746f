// Calls one geometric attachment of a GeometricAttachments library directly, as the planner's
// attachment runtime does: the arguments by name, the geometric state identifier as the one read
// value. Shared by the tamp tests.
#pragma once

#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "kaboum/symbolic/attachments.hpp"
#include "kaboum/tamp/geometric_attachments.hpp"

namespace kaboum::tamp::calls {

// The call's arguments: object ids 0, 1, … naming `arguments`, and state `stateId` read.
struct AttachmentCall {
  AttachmentCall(const std::vector<std::string>& arguments, std::size_t stateId)
      : ids(arguments.size()), reads{static_cast<double>(stateId)} {
    std::iota(ids.begin(), ids.end(), 0);
  }
  std::vector<symbolic::ObjectId> ids;
  std::vector<double> reads;
};

// Condition checker `name` on state `stateId` with `arguments`.
inline bool check(GeometricAttachments& attachments, const std::string& name,
                  const std::vector<std::string>& arguments, std::size_t stateId) {
  symbolic::ProcedureRegistry registry;
  attachments.registerProcedures(registry);
  const AttachmentCall call(arguments, stateId);
  return (*registry.checker(name))({call.ids, &arguments, call.reads});
}

// Effect `name` applied in state `stateId` with `arguments`: the state reached, or nullopt when
// the effect fails.
inline std::optional<std::size_t> apply(GeometricAttachments& attachments, const std::string& name,
                                        const std::vector<std::string>& arguments,
                                        std::size_t stateId) {
  symbolic::ProcedureRegistry registry;
  attachments.registerProcedures(registry);
  const AttachmentCall call(arguments, stateId);
  double reached = -1;
  if (!(*registry.applicator(name))({call.ids, &arguments, call.reads}, std::span(&reached, 1))) {
    return std::nullopt;
  }
  return static_cast<std::size_t>(reached);
}

}  // namespace kaboum::tamp::calls

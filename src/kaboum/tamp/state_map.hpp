// The symbolic–geometric map (thesis §6.1.2, Definition 5): geometric states and the identifiers
// the symbolic planner holds as fluent values, both ways. Equal states (every value equal after
// rounding to a tolerance) get one identifier; a new state gets the next one (0, 1, 2, … in order
// of first appearance). Lookup is hashed, the inverse an array access. Component-wise maps of
// object poses serve predicates that depend on one object's pose only (thesis, "Mapping parts of
// the geometric state").
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "kaboum/world/geometric_state.hpp"

namespace kaboum::tamp {

using namespace kaboum::world;

// The rounded values a state or pose is compared by.
using StateKey = std::vector<std::int64_t>;

struct StateKeyHash {
  std::size_t operator()(const StateKey& key) const noexcept;
};

class GeometricStateMap {
 public:
  // `tolerance`: the grid every value is rounded to before comparing (metres for positions and
  // prismatic joints, radians for revolute joints, unitless for rotation matrix entries). Two
  // states whose values all round to the same multiples of it are one state; values closer than
  // it but on either side of a rounding boundary stay apart (never a wrong merge of different
  // states farther apart than the tolerance).
  explicit GeometricStateMap(double tolerance = 1e-9);

  // The identifier of `state`: that of the equal state stored before, else a new one.
  std::size_t intern(const GeometricState& state);
  // The identifier of a stored state equal to `state`, if any.
  [[nodiscard]] std::optional<std::size_t> find(const GeometricState& state) const;
  // The state of identifier `id` (f⁻¹, constant time). Throws std::out_of_range for an unknown id.
  [[nodiscard]] const GeometricState& state(std::size_t id) const { return states_.at(id); }
  [[nodiscard]] std::size_t size() const { return states_.size(); }

  // Component-wise map of object `object`'s poses: the identifier of `pose` among that object's
  // poses (0, 1, … per object), and back.
  std::size_t internPose(std::size_t object, const Pose& pose);
  [[nodiscard]] const Pose& pose(std::size_t object, std::size_t id) const;

  [[nodiscard]] double tolerance() const { return tolerance_; }

 private:
  void appendRounded(double value, StateKey& key) const;
  void appendPose(const Pose& pose, StateKey& key) const;
  void keyOf(const GeometricState& state, StateKey& key) const;

  struct PoseComponent {
    std::unordered_map<StateKey, std::size_t, StateKeyHash> ids;
    std::vector<Pose> poses;
  };

  double tolerance_;
  std::unordered_map<StateKey, std::size_t, StateKeyHash> ids_;
  std::vector<GeometricState> states_;
  std::vector<PoseComponent> poses_;  // by object id
  mutable StateKey key_;              // reused by every lookup
};

}  // namespace kaboum::tamp

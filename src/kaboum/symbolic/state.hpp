// Packed search states (thesis §3.2): bitsets over atoms followed by one 64-bit slot per fluent.
// A classical state has one bitset (the true atoms, closed world). The layout takes more bitsets
// so the knowledge level (thesis §3.3.1, PKS) can store Kf (known true / known false), Kw over
// atoms and Kv over fluents in the same registry.
#pragma once

#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include "kaboum/symbolic/attachments.hpp"
#include "kaboum/symbolic/task.hpp"

namespace kaboum::symbolic {

class StateLayout {
 public:
  StateLayout(std::size_t atoms, std::size_t fluents, std::size_t atomBitsets = 1,
              std::size_t fluentBitsets = 0)
      : atomWords_((atoms + 63) / 64),
        fluentWords_((fluents + 63) / 64),
        atomBitsets_(atomBitsets),
        fluentBitsets_(fluentBitsets),
        fluents_(fluents) {}

  std::size_t words() const { return fluentOffset() + fluents_; }
  // First word of atom bitset `index` (0: the true atoms) and of fluent bitset `index`.
  std::size_t atomBitset(std::size_t index) const { return index * atomWords_; }
  std::size_t fluentBitset(std::size_t index) const {
    return atomBitsets_ * atomWords_ + index * fluentWords_;
  }
  std::size_t fluentOffset() const { return fluentBitset(fluentBitsets_); }

 private:
  std::size_t atomWords_;
  std::size_t fluentWords_;
  std::size_t atomBitsets_;
  std::size_t fluentBitsets_;
  std::size_t fluents_;
};

// Read access to a packed classical state.
class StateView {
 public:
  StateView(const std::uint64_t* words, std::size_t fluentOffset)
      : words_(words), fluentOffset_(fluentOffset) {}
  bool atom(AtomId atom) const { return (words_[atom >> 6] >> (atom & 63)) & 1u; }
  double fluent(FluentId fluent) const {
    return std::bit_cast<double>(words_[fluentOffset_ + static_cast<std::size_t>(fluent)]);
  }
  const std::uint64_t* words() const { return words_; }
  std::size_t fluentOffset() const { return fluentOffset_; }

 private:
  const std::uint64_t* words_;
  std::size_t fluentOffset_;
};

// Evaluates conditions and applies operators on packed states, calling attachments (memoized) for
// module checks and effects. Scratch buffers are reused, so evaluation does not allocate.
class StateEvaluator {
 public:
  StateEvaluator(const GroundTask& task, AttachmentRuntime& attachments);

  const StateLayout& layout() const { return layout_; }
  StateView view(std::span<const std::uint64_t> words) const {
    return {words.data(), layout_.fluentOffset()};
  }
  // Packs the task's initial state into `out` (layout().words() words).
  void initialState(std::span<std::uint64_t> out) const;

  bool holds(const Condition& condition, StateView state);
  bool holdsAny(const std::vector<Condition>& disjuncts, StateView state);
  bool isGoal(StateView state);
  // Writes the successor of `state` under `op` (whose precondition holds) into `out`. Returns
  // false if an effect applicator reports the effect infeasible. Without `effectApplicators`,
  // none is called and the fluents they write keep their values (a preview of the successor).
  bool apply(const Operator& op, StateView state, std::span<std::uint64_t> out,
             bool effectApplicators = true);

  double evaluate(const NumericCode& code, StateView state);

 private:
  bool collect(const EffectList& effect, StateView state, bool effectApplicators);

  const GroundTask& task_;
  AttachmentRuntime& attachments_;
  StateLayout layout_;
  std::vector<double> stack_;
  std::vector<double> reads_;
  std::vector<double> writes_;
  std::vector<const EffectList*> firing_;
  std::vector<std::pair<FluentId, double>> pendingWrites_;
};

}  // namespace kaboum::symbolic

// Semantic attachments (thesis §3.3.2 and §6.1.2; seed 004 §II, PDDL/M): C++ procedures behind the
// domain's modules. Condition checkers decide a precondition; effect applicators compute new values
// of declared fluents (e.g. the identifier of a new geometric state). Calls are memoized by
// (module, arguments, values of the fluents the module reads) and counted per module.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "kaboum/symbolic/packed_set.hpp"
#include "kaboum/symbolic/pddl.hpp"

namespace kaboum::symbolic {

// What a procedure receives: its arguments (object ids and names), the values of the fluents its
// module declares under `:reads`, in declaration order, and, for an effect applicator, which of
// the search's geometric samples of this call it computes (0 unless the search asks for several
// outcomes per call, ContingentOptions::samples): a sampling procedure draws sample s from a
// generator seeded apart for each s.
struct AttachmentArgs {
  std::span<const ObjectId> objects;
  const std::vector<std::string>* objectNames = nullptr;
  std::span<const double> reads;
  std::uint32_t sample = 0;

  std::string_view name(std::size_t i) const { return (*objectNames)[objects[i]]; }
};

// Returns whether the condition holds.
using ConditionChecker = std::function<bool(const AttachmentArgs&)>;
// Fills `writes` (one value per fluent the module sets); returns false if the effect is infeasible,
// which makes the action inapplicable.
using EffectApplicator = std::function<bool(const AttachmentArgs&, std::span<double> writes)>;

// C ABI of procedures loaded from a shared library (`proc@libfoo.so`): returns nonzero for
// true/success. Condition checkers get writeCount == 0. They are not told the sample: every sample
// of a call to one gives its one outcome.
extern "C" {
using KaboumProcedure = int (*)(const char* const* args, std::size_t argCount, const double* reads,
                                std::size_t readCount, double* writes, std::size_t writeCount);
}

// Procedures registered in code, by the name a module declaration gives after its kind.
class ProcedureRegistry {
 public:
  void addChecker(const std::string& name, ConditionChecker checker);
  void addApplicator(const std::string& name, EffectApplicator applicator);
  const ConditionChecker* checker(const std::string& name) const;
  const EffectApplicator* applicator(const std::string& name) const;

 private:
  std::unordered_map<std::string, ConditionChecker> checkers_;
  std::unordered_map<std::string, EffectApplicator> applicators_;
};

struct ModuleStatistics {
  std::string name;
  std::size_t calls = 0;      // requests, including cache hits
  std::size_t cacheHits = 0;  // answered from the memo
  double seconds = 0.0;       // time spent inside the procedure
};

// Binds every module of a domain to a procedure (registered, or loaded with dlopen) and evaluates
// calls with memoization. Throws InputError for unknown procedures, missing libraries or symbols.
class AttachmentRuntime {
 public:
  // Libraries named without '/' are looked up next to the domain file first, then by dlopen's
  // search path.
  AttachmentRuntime(const Domain& domain, const Problem& problem,
                    const ProcedureRegistry& registry);
  ~AttachmentRuntime();
  AttachmentRuntime(const AttachmentRuntime&) = delete;
  AttachmentRuntime& operator=(const AttachmentRuntime&) = delete;

  bool check(int module, std::span<const ObjectId> args, std::span<const double> reads);
  // Writes the module's output fluent values into `writes`; false if the effect is infeasible.
  // Computes sample `sample()` of the call; each sample is memoized apart.
  bool apply(int module, std::span<const ObjectId> args, std::span<const double> reads,
             std::span<double> writes);

  // The sample that apply() computes (AttachmentArgs::sample), until set again.
  void setSample(std::uint32_t sample) { sample_ = sample; }
  [[nodiscard]] std::uint32_t sample() const { return sample_; }

  std::vector<ModuleStatistics> statistics() const;
  bool empty() const { return bindings_.empty(); }

 private:
  struct Binding;
  bool call(Binding& binding, std::span<const ObjectId> args, std::span<const double> reads,
            std::span<double> writes);

  const Problem& problem_;
  std::uint32_t sample_ = 0;
  std::vector<std::unique_ptr<Binding>> bindings_;
  std::vector<void*> libraries_;
};

}  // namespace kaboum::symbolic

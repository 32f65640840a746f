#include "kaboum/symbolic/attachments.hpp"

#include <dlfcn.h>

#include <bit>
#include <filesystem>

#include "kaboum/core/error.hpp"

namespace kaboum::symbolic {

void ProcedureRegistry::addChecker(const std::string& name, ConditionChecker checker) {
  checkers_[name] = std::move(checker);
}

void ProcedureRegistry::addApplicator(const std::string& name, EffectApplicator applicator) {
  applicators_[name] = std::move(applicator);
}

const ConditionChecker* ProcedureRegistry::checker(const std::string& name) const {
  const auto it = checkers_.find(name);
  return it == checkers_.end() ? nullptr : &it->second;
}

const EffectApplicator* ProcedureRegistry::applicator(const std::string& name) const {
  const auto it = applicators_.find(name);
  return it == applicators_.end() ? nullptr : &it->second;
}

struct AttachmentRuntime::Binding {
  ModuleStatistics stats;
  std::size_t writeCount = 0;
  ConditionChecker checker;
  EffectApplicator applicator;
  KaboumProcedure native = nullptr;
  PackedSet memo;
  std::vector<std::uint64_t> key;       // reused lookup key: arguments then reads
  std::vector<std::uint8_t> results;    // per memo id
  std::vector<double> resultWrites;     // per memo id, writeCount values
  std::vector<const char*> nativeArgs;  // reused C argument array

  explicit Binding(std::size_t width) : memo(width), key(width) {}
};

AttachmentRuntime::AttachmentRuntime(const Domain& domain, const Problem& problem,
                                     const ProcedureRegistry& registry)
    : problem_(problem) {
  std::unordered_map<std::string, void*> opened;
  for (const Module& module : domain.modules) {
    // An effect applicator's memo key ends with the sample.
    const std::size_t sampleSlot = module.kind == Module::Kind::ConditionChecker ? 0 : 1;
    auto binding =
        std::make_unique<Binding>(module.paramTypes.size() + module.reads.size() + sampleSlot);
    binding->stats.name = module.name;
    binding->writeCount = module.writes.size();
    const auto fail = [&](const std::string& what) {
      throw InputError(locate(domain.file, "module '" + module.name + "': " + what, module.pos.line,
                              module.pos.column));
    };
    if (module.library.empty()) {
      const bool isChecker = module.kind == Module::Kind::ConditionChecker;
      if (isChecker && registry.checker(module.procedure) != nullptr) {
        binding->checker = *registry.checker(module.procedure);
      } else if (!isChecker && registry.applicator(module.procedure) != nullptr) {
        binding->applicator = *registry.applicator(module.procedure);
      } else {
        fail(std::string("no ") + (isChecker ? "condition checker" : "effect applicator") +
             " named '" + module.procedure + "' is registered");
      }
    } else {
      void*& handle = opened[module.library];
      if (handle == nullptr) {
        std::string path = module.library;
        if (path.find('/') == std::string::npos) {
          const auto local = std::filesystem::path(domain.file).parent_path() / path;
          if (std::filesystem::exists(local)) path = std::filesystem::absolute(local).string();
        }
        handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (handle == nullptr) {
          const char* reason = dlerror();
          fail("cannot load library '" + module.library + "'" +
               (reason != nullptr ? std::string(": ") + reason : std::string()));
        }
        libraries_.push_back(handle);
      }
      dlerror();
      void* symbol = dlsym(handle, module.procedure.c_str());
      if (symbol == nullptr) {
        fail("symbol '" + module.procedure + "' not found in '" + module.library + "'");
      }
      binding->native = reinterpret_cast<KaboumProcedure>(symbol);
    }
    bindings_.push_back(std::move(binding));
  }
}

AttachmentRuntime::~AttachmentRuntime() {
  for (void* handle : libraries_) dlclose(handle);
}

bool AttachmentRuntime::call(Binding& binding, std::span<const ObjectId> args,
                             std::span<const double> reads, std::span<double> writes) {
  ++binding.stats.calls;
  std::size_t k = 0;
  for (const ObjectId arg : args) binding.key[k++] = static_cast<std::uint64_t>(arg);
  for (const double read : reads) binding.key[k++] = std::bit_cast<std::uint64_t>(read);
  const std::uint32_t sample = k < binding.key.size() ? sample_ : 0;
  if (k < binding.key.size()) binding.key[k] = sample;
  const auto [id, inserted] = binding.memo.insert(binding.key);
  const std::size_t at = static_cast<std::size_t>(id) * binding.writeCount;
  if (!inserted) {
    ++binding.stats.cacheHits;
    std::copy_n(binding.resultWrites.begin() + static_cast<long>(at), writes.size(),
                writes.begin());
    return binding.results[id] != 0;
  }
  binding.resultWrites.resize(at + binding.writeCount);
  std::span<double> out(binding.resultWrites.data() + at, binding.writeCount);
  const AttachmentArgs input{args, &problem_.objectNames, reads, sample};
  const auto start = std::chrono::steady_clock::now();
  bool result = false;
  if (binding.native != nullptr) {
    binding.nativeArgs.clear();
    for (const ObjectId arg : args) binding.nativeArgs.push_back(problem_.objectNames[arg].c_str());
    result = binding.native(binding.nativeArgs.data(), args.size(), reads.data(), reads.size(),
                            out.data(), out.size()) != 0;
  } else if (binding.checker) {
    result = binding.checker(input);
  } else {
    result = binding.applicator(input, out);
  }
  binding.stats.seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  binding.results.push_back(result ? 1 : 0);
  std::copy(out.begin(), out.end(), writes.begin());
  return result;
}

bool AttachmentRuntime::check(int module, std::span<const ObjectId> args,
                              std::span<const double> reads) {
  return call(*bindings_[module], args, reads, {});
}

bool AttachmentRuntime::apply(int module, std::span<const ObjectId> args,
                              std::span<const double> reads, std::span<double> writes) {
  return call(*bindings_[module], args, reads, writes);
}

std::vector<ModuleStatistics> AttachmentRuntime::statistics() const {
  std::vector<ModuleStatistics> out;
  for (const auto& binding : bindings_) out.push_back(binding->stats);
  return out;
}

}  // namespace kaboum::symbolic

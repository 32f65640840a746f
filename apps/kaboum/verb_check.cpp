// `kaboum check`: verifies a bounding mesh against its original (containment on dense surface
// samples, self-intersections, and the one-sided Hausdorff distances of thesis Table 4.2).
#include <fmt/format.h>

#include <iostream>

#include "kaboum/io/json_geometry.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "mesh_cli.hpp"
#include "verb.hpp"

namespace kaboum::cli {

using namespace kaboum::geometry;
using namespace kaboum::io;

namespace {

struct CheckArgs {
  std::string original, result;
  BoundSide side = BoundSide::Outer;
  std::size_t samples = 200000;
  std::uint64_t seed = 1;
  bool json = false;
};

int runCheck(const CheckArgs& args) {
  const LoadedMesh original = loadOrientedMesh(args.original);
  const TriangleMesh result = readMesh(args.result);
  const ContainmentReport containment =
      verifyContainment(original.mesh, result, args.side, args.samples, args.seed);
  const HausdorffReport hausdorff =
      measureHausdorff(original.mesh, result, args.samples, args.seed);
  const bool violated =
      containment.defined && (containment.insideOut || containment.violations > 0 ||
                              containment.selfIntersectingPairs > 0);

  if (args.json) {
    nlohmann::json out = toJson(containment);
    out.update({{"original", args.original},
                {"result", args.result},
                {"side", sideName(args.side)},
                {"verified", containment.defined && !violated},
                {"hausdorff", toJson(hausdorff)}});
    std::cout << out.dump(2) << "\n";
  } else {
    const char* relation =
        args.side == BoundSide::Outer ? "result contains original" : "original contains result";
    if (!containment.defined) {
      std::cout << fmt::format("containment: not defined — {}\n", containment.note);
    } else if (containment.insideOut) {
      std::cout << fmt::format("containment: VIOLATED: {}\n", containment.note);
    } else if (violated) {
      std::cout << fmt::format(
          "containment: VIOLATED ({}): {} of {} samples outside (worst {:.4g}), {} "
          "self-intersecting triangle pairs\n",
          relation, containment.violations, containment.checked, containment.worstViolation,
          containment.selfIntersectingPairs);
    } else {
      std::cout << fmt::format("containment: verified ({}) on {} samples, no self-intersections\n",
                               relation, containment.checked);
    }
    std::cout << "distance original->result: "
              << describe(hausdorff.originalToResult, hausdorff.diagonal) << "\n";
    std::cout << "distance result->original: "
              << describe(hausdorff.resultToOriginal, hausdorff.diagonal) << "\n";
  }
  return violated ? 1 : 0;
}

VerbRunner setupCheck(CLI::App& command) {
  auto args = std::make_shared<CheckArgs>();
  command.add_option("original", args->original, "The original mesh")->required();
  command.add_option("result", args->result, "The bounding mesh made from it")->required();
  addSideFlags(command, args->side);
  command.add_option("--samples", args->samples,
                     "Random area-weighted samples per surface (all vertices and edge midpoints "
                     "are always checked)");
  command.add_option("--seed", args->seed, "Seed for the random samples");
  command.add_flag("--json", args->json, "Print one JSON object instead of text");
  return [args] { return runCheck(*args); };
}

const VerbRegistration registration{
    "check",
    "Verify a bounding mesh: containment on dense samples, self-intersections, Hausdorff "
    "distances (exit 1 if violated)",
    &setupCheck};

}  // namespace
}  // namespace kaboum::cli

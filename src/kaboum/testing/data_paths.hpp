// Where tests and benchmarks find their inputs: the repository's data/ and examples/ folders
// (provenance in data/README-*.md), the robots of Debian's dart-doc package (installed by
// scripts/setup.sh), and the optional shared benchmark folder beside the checkout.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace kaboum::testing {

// `relative` inside the repository's data/ folder, e.g. dataFile("meshes/cow.obj").
std::string dataFile(std::string_view relative);
// `relative` inside the repository's examples/ folder.
std::string exampleFile(std::string_view relative);
// `relative` inside the repository (e.g. "tests/symbolic/fuzz/corpus").
std::string sourceFile(std::string_view relative);

// dart-doc's URDF folder, and its KUKA KR5 sixx R650 and Barrett WAM robots.
std::filesystem::path dartUrdfDir();
std::string kr5Urdf();
std::string wamUrdf();
// The KR5's link meshes (STL).
std::filesystem::path kr5MeshDir();

// The shared benchmark folder (public meshes, PDDL benchmarks, scenarios) when it exists: the
// environment variable KABOUM_SHARED_DIR, or else ../shared beside the checkout. Benchmarks and
// a few tests use it for optional, larger inputs and skip them without it.
std::optional<std::filesystem::path> sharedDir();

}  // namespace kaboum::testing

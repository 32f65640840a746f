#include "kaboum/testing/data_paths.hpp"

#include <cstdlib>

namespace kaboum::testing {

namespace {

// Plain strings, not paths: the helpers may run during other files' static initialisation.
constexpr const char* kSourceDir = KABOUM_SOURCE_DIR;
constexpr const char* kDartUrdfDir = "/usr/share/doc/dart/data/urdf";

std::filesystem::path source() {
  return kSourceDir;
}

}  // namespace

std::string dataFile(std::string_view relative) {
  return (source() / "data" / relative).string();
}

std::string exampleFile(std::string_view relative) {
  return (source() / "examples" / relative).string();
}

std::string sourceFile(std::string_view relative) {
  return (source() / relative).string();
}

std::filesystem::path dartUrdfDir() {
  return kDartUrdfDir;
}

std::string kr5Urdf() {
  return (dartUrdfDir() / "KR5" / "KR5 sixx R650.urdf").string();
}

std::string wamUrdf() {
  return (dartUrdfDir() / "wam" / "wam.urdf").string();
}

std::filesystem::path kr5MeshDir() {
  return dartUrdfDir() / "KR5" / "meshes";
}

std::optional<std::filesystem::path> sharedDir() {
  const char* given = std::getenv("KABOUM_SHARED_DIR");
  const std::filesystem::path shared =
      given && *given ? std::filesystem::path(given) : source().parent_path() / "shared";
  if (std::filesystem::is_directory(shared)) return shared;
  return std::nullopt;
}

}  // namespace kaboum::testing

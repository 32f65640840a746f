#include "kaboum/io/mesh_io.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "kaboum/core/error.hpp"
#include "kaboum/core/text.hpp"
#include "kaboum/geometry/mesh_analysis.hpp"
#include "kaboum/geometry/mesh_cleanup.hpp"
#include "kaboum/io/mesh_formats.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;

namespace {

using FileHandle = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

std::string lowerExtension(const std::string& path) {
  return lowerCase(std::filesystem::path(path).extension().string());
}

std::string unknownFormat(const std::string& extension, const char* expected) {
  return (extension.empty() ? std::string("no file extension")
                            : "unknown mesh format '" + extension + "'") +
         " (expected " + expected + ")";
}

TriangleMesh readByExtension(const std::string& path) {
  const std::string extension = lowerExtension(path);
  if (extension == ".stl") return io::readStl(path, io::readFileBytes(path));
  if (extension == ".obj") return io::readObj(path, io::readFileBytes(path));
  if (extension == ".off") return io::readOff(path, io::readFileBytes(path));
  if (extension == ".ply") return io::readPly(path, io::readFileBytes(path));
  if (extension == ".dae") return io::readDae(path);
  if (extension == ".wrl" || extension == ".vrml") return io::readVrml(path);
  throw InputError(locate(path, unknownFormat(extension, ".stl .obj .ply .off .dae .wrl")));
}

// The checks every reader shares: finite coordinates and indices in range (readers report these
// with a line where they can; this catches binary formats), then at least one face with area.
void validate(const TriangleMesh& mesh, const std::string& path) {
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!mesh.vertices[i].allFinite()) {
      throw InputError(
          locate(path, "vertex " + std::to_string(i) + " has a non-finite coordinate"));
    }
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const std::uint32_t index : mesh.triangles[t]) {
      if (index >= mesh.vertices.size()) {
        throw InputError(locate(path, "triangle " + std::to_string(t) + " uses vertex " +
                                          std::to_string(index) + " but there are only " +
                                          std::to_string(mesh.vertices.size()) + " vertices"));
      }
    }
  }
  if (mesh.triangles.empty()) throw InputError(locate(path, "empty mesh: no faces"));
}

}  // namespace

std::string readFileBytes(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw InputError(locate(path, "cannot read: is a directory"));
  }
  const FileHandle file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw InputError(locate(path, std::string("cannot open: ") + std::strerror(errno)));
  std::string bytes;
  char buffer[1 << 16];
  std::size_t count = 0;
  while ((count = std::fread(buffer, 1, sizeof buffer, file.get())) > 0)
    bytes.append(buffer, count);
  if (std::ferror(file.get())) {
    throw InputError(locate(path, std::string("cannot read: ") + std::strerror(errno)));
  }
  return bytes;
}

void appendShortest(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

TriangleMesh readMesh(const std::string& path) {
  TriangleMesh mesh = readByExtension(path);
  validate(mesh, path);
  weldVertices(mesh);
  const bool anyArea =
      std::any_of(mesh.triangles.begin(), mesh.triangles.end(),
                  [&](const Triangle& triangle) { return !isDegenerateTriangle(mesh, triangle); });
  if (!anyArea) {
    throw InputError(
        locate(path, "all " + std::to_string(mesh.triangles.size()) + " faces have zero area"));
  }
  return mesh;
}

void writeMesh(const TriangleMesh& mesh, const std::string& path) {
  const std::string extension = lowerExtension(path);
  std::string contents;
  if (extension == ".obj") {
    io::formatObj(mesh, contents);
  } else if (extension == ".stl") {
    io::formatStl(mesh, contents);
  } else if (extension == ".ply") {
    io::formatPly(mesh, contents);
  } else if (extension == ".off") {
    io::formatOff(mesh, contents);
  } else {
    throw InputError(locate(path, unknownFormat(extension, ".obj .stl .ply .off")));
  }
  FileHandle file(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!file) throw InputError(locate(path, std::string("cannot write: ") + std::strerror(errno)));
  const bool written =
      std::fwrite(contents.data(), 1, contents.size(), file.get()) == contents.size();
  const int writeErrno = errno;
  if (std::fclose(file.release()) != 0 || !written) {
    throw InputError(
        locate(path, std::string("cannot write: ") + std::strerror(written ? errno : writeErrno)));
  }
}

}  // namespace kaboum::io

// Per-format readers and writers behind readMesh/writeMesh. Readers return the faces and vertices
// as stored (indices already range-checked, nothing welded); readMesh does the common clean-up.
#pragma once

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>
#include <string_view>

#include "kaboum/geometry/triangle_mesh.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;

// Whole file as bytes; throws InputError naming the file when it cannot be read.
std::string readFileBytes(const std::string& path);

TriangleMesh readStl(const std::string& path, std::string_view bytes);
TriangleMesh readObj(const std::string& path, std::string_view text);
TriangleMesh readOff(const std::string& path, std::string_view text);
TriangleMesh readPly(const std::string& path, std::string_view bytes);
TriangleMesh readDae(const std::string& path);
TriangleMesh readVrml(const std::string& path);

// Appends the complete file contents in each format to `out`.
void formatObj(const TriangleMesh& mesh, std::string& out);
void formatStl(const TriangleMesh& mesh, std::string& out);
void formatPly(const TriangleMesh& mesh, std::string& out);
void formatOff(const TriangleMesh& mesh, std::string& out);

// A scalar stored in `bytes` in little- or big-endian order.
template <typename T>
T loadScalar(const char* bytes, bool bigEndian) {
  char buffer[sizeof(T)];
  std::memcpy(buffer, bytes, sizeof(T));
  if (bigEndian != (std::endian::native == std::endian::big))
    std::reverse(buffer, buffer + sizeof(T));
  T value;
  std::memcpy(&value, buffer, sizeof(T));
  return value;
}

// Appends `value` in little-endian byte order.
template <typename T>
void appendLittleEndian(std::string& out, T value) {
  char buffer[sizeof(T)];
  std::memcpy(buffer, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(buffer, buffer + sizeof(T));
  out.append(buffer, sizeof(T));
}

// Appends the shortest decimal text that parses back to exactly `value`.
void appendShortest(std::string& out, double value);

}  // namespace kaboum::io

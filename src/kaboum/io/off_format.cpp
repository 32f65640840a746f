// Object File Format: "OFF", the counts "V F E", V lines "x y z [colour...]", F lines
// "n i1 .. in [colour...]" (0-based), fan-triangulated. C/N/ST prefixes (COFF, NOFF, ...) are
// accepted; their extra per-line values are ignored.
#include <algorithm>
#include <string>

#include "kaboum/io/mesh_formats.hpp"
#include "kaboum/io/text_cursor.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;

namespace {

bool isThreeDimensionalOffKeyword(std::string_view keyword) {
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF") return false;
  return keyword.substr(0, keyword.size() - 3).find_first_not_of("STCN") == std::string_view::npos;
}

std::size_t count(TextCursor& text, std::string_view what) {
  const long long value = text.toInteger(text.nextWord(), what);
  if (value < 0 || value > 0xffffffffLL) text.fail(std::string(what) + " out of range");
  return static_cast<std::size_t>(value);
}

}  // namespace

TriangleMesh readOff(const std::string& path, std::string_view text) {
  TextCursor cursor(text, path, {.hashComments = true, .commaIsSpace = false, .punctuation = {}});
  const std::string_view keyword = cursor.nextWord();
  if (!isThreeDimensionalOffKeyword(keyword)) {
    cursor.fail("expected 'OFF' header, found '" + std::string(keyword) + "'");
  }
  const std::size_t vertexCount = count(cursor, "vertex count");
  const std::size_t faceCount = count(cursor, "face count");
  count(cursor, "edge count");
  cursor.skipLine();

  TriangleMesh mesh;
  mesh.vertices.reserve(std::min(vertexCount, text.size() / 6));  // bounds bogus counts
  for (std::size_t v = 0; v < vertexCount; ++v) {
    cursor.skipWhitespace();
    if (cursor.atEnd())
      cursor.fail(cursor.here(), "file ends after " + std::to_string(v) + " of " +
                                     std::to_string(vertexCount) + " vertices");
    Vec3 p;
    for (int i = 0; i < 3; ++i) p[i] = cursor.number("vertex coordinate");
    mesh.vertices.push_back(p);
    cursor.skipLine();
  }
  mesh.triangles.reserve(std::min(faceCount, text.size() / 8));
  for (std::size_t f = 0; f < faceCount; ++f) {
    cursor.skipWhitespace();
    if (cursor.atEnd())
      cursor.fail(cursor.here(), "file ends after " + std::to_string(f) + " of " +
                                     std::to_string(faceCount) + " faces");
    const long long corners = cursor.integer("face vertex count");
    if (corners < 3) cursor.fail("face with fewer than 3 vertices");
    std::uint32_t first = 0, previous = 0;
    for (long long corner = 0; corner < corners; ++corner) {
      const long long index = cursor.integer("vertex index");
      if (index < 0 || static_cast<std::size_t>(index) >= vertexCount) {
        cursor.fail("vertex index " + std::to_string(index) + " out of range (" +
                    std::to_string(vertexCount) + " vertices)");
      }
      const auto current = static_cast<std::uint32_t>(index);
      if (corner == 0) first = current;
      if (corner >= 2) mesh.triangles.push_back({first, previous, current});
      previous = current;
    }
    cursor.skipLine();
  }
  return mesh;
}

void formatOff(const TriangleMesh& mesh, std::string& out) {
  out += "OFF\n" + std::to_string(mesh.vertices.size()) + ' ' +
         std::to_string(mesh.triangles.size()) + " 0\n";
  for (const Vec3& p : mesh.vertices) {
    for (int i = 0; i < 3; ++i) {
      if (i > 0) out += ' ';
      appendShortest(out, p[i]);
    }
    out += '\n';
  }
  for (const Triangle& t : mesh.triangles) {
    out += '3';
    for (const std::uint32_t v : t) {
      out += ' ';
      out += std::to_string(v);
    }
    out += '\n';
  }
}

}  // namespace kaboum::io

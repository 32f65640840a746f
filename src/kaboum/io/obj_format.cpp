// Wavefront OBJ: "v x y z" vertices and "f i[/t][/n] ..." polygons (1-based or negative relative
// indices), fan-triangulated. Other statements (vt, vn, g, o, s, usemtl, l, ...) are skipped.
#include <string>

#include "kaboum/io/mesh_formats.hpp"
#include "kaboum/io/text_cursor.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;

namespace {

// Resolves one face corner token to a 0-based index. Positive indices may refer to vertices
// defined later in the file; the largest one is checked once the file is read.
std::uint32_t faceIndex(TextCursor& text, std::string_view token, std::size_t vertexCount,
                        long long& largest, TextLocation& largestAt) {
  const std::string_view position = token.substr(0, token.find('/'));
  const long long index = text.toInteger(position, "vertex index");
  if (index == 0) text.fail("vertex index 0 is invalid (OBJ indices start at 1)");
  if (index < 0) {
    if (static_cast<unsigned long long>(-index) > vertexCount) {
      text.fail("relative vertex index " + std::to_string(index) + " out of range (" +
                std::to_string(vertexCount) + " vertices so far)");
    }
    return static_cast<std::uint32_t>(static_cast<long long>(vertexCount) + index);
  }
  if (index > largest) {
    largest = index;
    largestAt = text.wordLocation();
  }
  if (index > 0xffffffffLL) text.fail("vertex index " + std::to_string(index) + " out of range");
  return static_cast<std::uint32_t>(index - 1);
}

}  // namespace

TriangleMesh readObj(const std::string& path, std::string_view text) {
  TextCursor cursor(text, path, {.hashComments = true, .commaIsSpace = false, .punctuation = {}});
  TriangleMesh mesh;
  long long largestIndex = 0;
  TextLocation largestAt;
  while (!cursor.atEnd()) {
    const std::string_view keyword = cursor.word();
    if (keyword == "v") {
      Vec3 p;
      for (int i = 0; i < 3; ++i) p[i] = cursor.number("vertex coordinate");
      mesh.vertices.push_back(p);
    } else if (keyword == "f") {
      const TextLocation faceAt = cursor.wordLocation();
      std::uint32_t first = 0, previous = 0, corners = 0;
      for (std::string_view token = cursor.word(); !token.empty(); token = cursor.word()) {
        const std::uint32_t index =
            faceIndex(cursor, token, mesh.vertices.size(), largestIndex, largestAt);
        if (corners == 0) first = index;
        if (corners >= 2) mesh.triangles.push_back({first, previous, index});
        previous = index;
        ++corners;
      }
      if (corners < 3) cursor.fail(faceAt, "face with fewer than 3 vertices");
    }
    cursor.skipLine();
  }
  if (largestIndex > static_cast<long long>(mesh.vertices.size())) {
    cursor.fail(largestAt, "vertex index " + std::to_string(largestIndex) + " out of range (" +
                               std::to_string(mesh.vertices.size()) + " vertices)");
  }
  return mesh;
}

void formatObj(const TriangleMesh& mesh, std::string& out) {
  out += "# written by kaboum\n";
  for (const Vec3& p : mesh.vertices) {
    out += 'v';
    for (int i = 0; i < 3; ++i) {
      out += ' ';
      appendShortest(out, p[i]);
    }
    out += '\n';
  }
  for (const Triangle& t : mesh.triangles) {
    out += 'f';
    for (const std::uint32_t v : t) {
      out += ' ';
      out += std::to_string(v + 1);
    }
    out += '\n';
  }
}

}  // namespace kaboum::io

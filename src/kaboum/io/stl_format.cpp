// STL: binary (50-byte facets of 32-bit floats) and ascii ("facet ... vertex x y z ... endfacet").
#include <Eigen/Geometry>

#include "kaboum/core/error.hpp"
#include "kaboum/io/mesh_formats.hpp"
#include "kaboum/io/text_cursor.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;

namespace {

constexpr std::size_t kHeaderBytes = 80;
constexpr std::size_t kFacetBytes = 50;

std::uint32_t loadLittleU32(const char* bytes) {
  return loadScalar<std::uint32_t>(bytes, false);
}

float loadLittleFloat(const char* bytes) {
  return loadScalar<float>(bytes, false);
}

bool startsWithSolid(std::string_view bytes) {
  const std::size_t start = bytes.find_first_not_of(" \t\r\n");
  return start != std::string_view::npos && bytes.substr(start, 5) == "solid";
}

TriangleMesh readBinaryStl(std::string_view bytes) {
  const std::uint32_t facets = loadLittleU32(bytes.data() + kHeaderBytes);
  TriangleMesh mesh;
  mesh.vertices.reserve(3 * std::size_t{facets});
  mesh.triangles.reserve(facets);
  const char* facet = bytes.data() + kHeaderBytes + 4;
  for (std::uint32_t f = 0; f < facets; ++f, facet += kFacetBytes) {
    for (std::uint32_t corner = 0; corner < 3; ++corner) {
      const char* point = facet + 12 * (corner + 1);  // after the 12-byte normal
      mesh.vertices.emplace_back(loadLittleFloat(point), loadLittleFloat(point + 4),
                                 loadLittleFloat(point + 8));
    }
    mesh.triangles.push_back({3 * f, 3 * f + 1, 3 * f + 2});
  }
  return mesh;
}

void expectKeyword(TextCursor& text, std::string_view keyword) {
  const std::string_view token = text.nextWord();
  if (token != keyword) {
    text.fail("expected '" + std::string(keyword) + "', found " +
              (token.empty() ? std::string("end of file") : "'" + std::string(token) + "'"));
  }
}

// solid NAME { facet normal n n n / outer loop / vertex x y z (3 or more) / endloop / endfacet }
// endsolid NAME, possibly repeated. Loops of more than three vertices are fan-triangulated.
TriangleMesh readAsciiStl(const std::string& path, std::string_view text) {
  TextCursor cursor(text, path);
  TriangleMesh mesh;
  for (std::string_view token = cursor.nextWord(); !token.empty(); token = cursor.nextWord()) {
    if (token != "solid") cursor.fail("expected 'solid', found '" + std::string(token) + "'");
    cursor.skipLine();  // the solid's name
    for (token = cursor.nextWord(); token == "facet"; token = cursor.nextWord()) {
      expectKeyword(cursor, "normal");
      for (int i = 0; i < 3; ++i) cursor.toNumber(cursor.nextWord(), "normal component");
      expectKeyword(cursor, "outer");
      expectKeyword(cursor, "loop");
      const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
      std::uint32_t corners = 0;
      for (token = cursor.nextWord(); token == "vertex"; token = cursor.nextWord(), ++corners) {
        Vec3 p;
        for (int i = 0; i < 3; ++i) p[i] = cursor.toNumber(cursor.nextWord(), "vertex coordinate");
        mesh.vertices.push_back(p);
        if (corners >= 2) mesh.triangles.push_back({first, first + corners - 1, first + corners});
      }
      if (token != "endloop") cursor.fail("expected 'vertex' or 'endloop'");
      if (corners < 3) cursor.fail("facet with fewer than 3 vertices");
      expectKeyword(cursor, "endfacet");
    }
    if (token != "endsolid") cursor.fail("expected 'facet' or 'endsolid'");
    cursor.skipLine();
  }
  return mesh;
}

Vec3 facetNormal(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 normal = (b - a).cross(c - a);
  const double length = normal.norm();
  return length > 0.0 ? Vec3(normal / length) : Vec3::Zero();
}

}  // namespace

TriangleMesh readStl(const std::string& path, std::string_view bytes) {
  if (bytes.size() >= kHeaderBytes + 4) {
    const std::uint64_t facets = loadLittleU32(bytes.data() + kHeaderBytes);
    if (bytes.size() == kHeaderBytes + 4 + kFacetBytes * facets) return readBinaryStl(bytes);
  }
  if (startsWithSolid(bytes)) return readAsciiStl(path, bytes);
  if (bytes.size() < kHeaderBytes + 4) {
    throw InputError(
        locate(path, "not an STL file: " + std::to_string(bytes.size()) +
                         " bytes, too short for binary and not starting with 'solid'"));
  }
  const std::uint64_t facets = loadLittleU32(bytes.data() + kHeaderBytes);
  throw InputError(
      locate(path, "not a valid binary STL: header announces " + std::to_string(facets) +
                       " facets (" + std::to_string(kHeaderBytes + 4 + kFacetBytes * facets) +
                       " bytes) but the file has " + std::to_string(bytes.size()) + " bytes"));
}

void formatStl(const TriangleMesh& mesh, std::string& out) {
  std::string header = "binary STL written by kaboum";
  header.resize(kHeaderBytes, ' ');
  out.reserve(out.size() + kHeaderBytes + 4 + kFacetBytes * mesh.triangles.size());
  out += header;
  appendLittleEndian(out, static_cast<std::uint32_t>(mesh.triangles.size()));
  for (const Triangle& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    for (const Vec3& p : {facetNormal(a, b, c), a, b, c}) {
      for (int i = 0; i < 3; ++i) appendLittleEndian(out, static_cast<float>(p[i]));
    }
    out.append(2, '\0');  // attribute byte count
  }
}

}  // namespace kaboum::io

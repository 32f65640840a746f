// Stanford PLY: ascii, binary_little_endian and binary_big_endian. Reads x/y/z of "vertex", the
// "vertex_indices" (or "vertex_index") lists of "face" (fan-triangulated) and of "tristrips" (-1
// restarts a strip); every other element and property is skipped.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "kaboum/core/error.hpp"
#include "kaboum/io/mesh_formats.hpp"
#include "kaboum/io/text_cursor.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<PlyType> plyType(std::string_view name) {
  if (name == "char" || name == "int8") return PlyType::Int8;
  if (name == "uchar" || name == "uint8") return PlyType::UInt8;
  if (name == "short" || name == "int16") return PlyType::Int16;
  if (name == "ushort" || name == "uint16") return PlyType::UInt16;
  if (name == "int" || name == "int32") return PlyType::Int32;
  if (name == "uint" || name == "uint32") return PlyType::UInt32;
  if (name == "float" || name == "float32") return PlyType::Float32;
  if (name == "double" || name == "float64") return PlyType::Float64;
  return std::nullopt;
}

std::size_t sizeOf(PlyType type) {
  switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 0;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;
  std::optional<PlyType> listCountType;  // set for list properties
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
  TextLocation at;
};

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
};

PlyHeader readHeader(TextCursor& text) {
  if (text.word() != "ply") text.fail("not a PLY file: first line must be 'ply'");
  text.skipLine();
  PlyHeader header;
  bool sawFormat = false;
  for (;;) {
    const std::string_view keyword = text.word();
    if (keyword == "end_header") break;
    if (keyword.empty() && text.atEnd()) text.fail("header has no 'end_header'");
    if (keyword == "format") {
      const std::string_view format = text.word();
      if (format == "ascii") {
        header.format = PlyFormat::Ascii;
      } else if (format == "binary_little_endian") {
        header.format = PlyFormat::BinaryLittleEndian;
      } else if (format == "binary_big_endian") {
        header.format = PlyFormat::BinaryBigEndian;
      } else {
        text.fail("unknown PLY format '" + std::string(format) + "'");
      }
      sawFormat = true;
    } else if (keyword == "element") {
      PlyElement element;
      element.name = text.word();
      element.at = text.wordLocation();
      const long long count = text.integer("element count");
      if (count < 0) text.fail("negative element count");
      element.count = static_cast<std::size_t>(count);
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) text.fail("property before any element");
      PlyProperty property;
      std::string_view typeName = text.word();
      if (typeName == "list") {
        const std::string_view countName = text.word();
        property.listCountType = plyType(countName);
        if (!property.listCountType || *property.listCountType == PlyType::Float32 ||
            *property.listCountType == PlyType::Float64) {
          text.fail("invalid list count type '" + std::string(countName) + "'");
        }
        typeName = text.word();
      }
      const std::optional<PlyType> type = plyType(typeName);
      if (!type) text.fail("unknown property type '" + std::string(typeName) + "'");
      property.type = *type;
      property.name = text.word();
      if (property.name.empty()) text.fail("property without a name");
      header.elements.back().properties.push_back(std::move(property));
    } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
      text.fail("unknown header line '" + std::string(keyword) + "'");
    }
    text.skipLine();
  }
  if (!sawFormat) text.fail("header has no 'format' line");
  // The data starts after the end_header line end.
  text.restOfLine();
  if (!text.atEnd()) text.skipLine();
  return header;
}

// Reads property values one by one from ascii tokens or binary bytes, with error context.
class PlyValues {
 public:
  PlyValues(const std::string& path, TextCursor& text, PlyFormat format)
      : path_(path), text_(text), format_(format), pos_(text.position()) {}

  void setEnd(const char* end) { end_ = end; }
  void enter(const PlyElement& element, std::size_t instance) {
    element_ = &element;
    instance_ = instance;
  }

  double real(PlyType type) {
    if (format_ == PlyFormat::Ascii) return text_.toNumber(text_.nextWord(), "property value");
    switch (type) {
      case PlyType::Float32:
        return static_cast<double>(load<float>());
      case PlyType::Float64:
        return load<double>();
      default:
        return static_cast<double>(integer(type));
    }
  }

  long long integer(PlyType type) {
    if (format_ == PlyFormat::Ascii) return text_.toInteger(text_.nextWord(), "integer value");
    switch (type) {
      case PlyType::Int8:
        return load<std::int8_t>();
      case PlyType::UInt8:
        return load<std::uint8_t>();
      case PlyType::Int16:
        return load<std::int16_t>();
      case PlyType::UInt16:
        return load<std::uint16_t>();
      case PlyType::Int32:
        return load<std::int32_t>();
      case PlyType::UInt32:
        return load<std::uint32_t>();
      case PlyType::Float32:
      case PlyType::Float64:
        fail("index stored as floating point");
    }
    return 0;
  }

  void skip(const PlyProperty& property) {
    if (!property.listCountType) {
      skipScalar(property.type);
      return;
    }
    const long long count = listCount(property);
    for (long long i = 0; i < count; ++i) skipScalar(property.type);
  }

  long long listCount(const PlyProperty& property) {
    const long long count = integer(*property.listCountType);
    if (count < 0) fail("negative list length");
    return count;
  }

  // Where the last value came from: the ascii token, or the element instance in binary data.
  struct Spot {
    TextLocation at;
    const PlyElement* element = nullptr;
    std::size_t instance = 0;
  };
  Spot spot() const { return {text_.wordLocation(), element_, instance_}; }

  [[noreturn]] void fail(const Spot& spot, const std::string& what) const {
    if (format_ == PlyFormat::Ascii) text_.fail(spot.at, what);
    throw InputError(locate(path_, what + " (element '" + spot.element->name + "' " +
                                       std::to_string(spot.instance) + " of " +
                                       std::to_string(spot.element->count) + ")"));
  }
  [[noreturn]] void fail(const std::string& what) const { fail(spot(), what); }

 private:
  template <typename T>
  T load() {
    if (static_cast<std::size_t>(end_ - pos_) < sizeof(T)) fail("binary data ends early");
    const T value = loadScalar<T>(pos_, format_ == PlyFormat::BinaryBigEndian);
    pos_ += sizeof(T);
    return value;
  }

  void skipScalar(PlyType type) {
    if (format_ == PlyFormat::Ascii) {
      if (text_.nextWord().empty()) fail("data ends early");
      return;
    }
    if (static_cast<std::size_t>(end_ - pos_) < sizeOf(type)) fail("binary data ends early");
    pos_ += sizeOf(type);
  }

  const std::string& path_;
  TextCursor& text_;
  PlyFormat format_;
  const char* pos_;
  const char* end_ = nullptr;
  const PlyElement* element_ = nullptr;
  std::size_t instance_ = 0;
};

std::optional<std::size_t> findProperty(const PlyElement& element,
                                        std::initializer_list<std::string_view> names) {
  for (std::size_t i = 0; i < element.properties.size(); ++i) {
    for (const std::string_view name : names) {
      if (element.properties[i].name == name) return i;
    }
  }
  return std::nullopt;
}

// Collects triangles; indices are range-checked once all vertices are known.
struct TriangleSink {
  TriangleMesh& mesh;
  long long largestIndex = -1;
  PlyValues::Spot largestAt;

  std::uint32_t accept(PlyValues& values, long long index) {
    if (index < 0) values.fail("negative vertex index " + std::to_string(index));
    if (index > largestIndex) {
      if (index > 0xffffffffLL) values.fail("vertex index " + std::to_string(index) + " too large");
      largestIndex = index;
      largestAt = values.spot();
    }
    return static_cast<std::uint32_t>(index);
  }
};

void readFace(PlyValues& values, const PlyProperty& list, TriangleSink& sink) {
  const long long corners = values.listCount(list);
  if (corners < 3) values.fail("face with fewer than 3 vertices");
  std::uint32_t first = 0, previous = 0;
  for (long long corner = 0; corner < corners; ++corner) {
    const std::uint32_t current = sink.accept(values, values.integer(list.type));
    if (corner == 0) first = current;
    if (corner >= 2) sink.mesh.triangles.push_back({first, previous, current});
    previous = current;
  }
}

// A strip v0 v1 v2 v3 ... gives (v0 v1 v2), (v2 v1 v3), (v2 v3 v4), ...; -1 restarts. Triangles
// with a repeated index only join strips and are dropped.
void readStrip(PlyValues& values, const PlyProperty& list, TriangleSink& sink) {
  const long long length = values.listCount(list);
  std::uint32_t older = 0, newer = 0;
  long long position = 0;
  for (long long i = 0; i < length; ++i) {
    const long long index = values.integer(list.type);
    if (index == -1) {
      position = 0;
      continue;
    }
    const std::uint32_t current = sink.accept(values, index);
    if (position >= 2 && older != newer && newer != current && current != older) {
      sink.mesh.triangles.push_back(position % 2 == 0 ? Triangle{older, newer, current}
                                                      : Triangle{newer, older, current});
    }
    older = newer;
    newer = current;
    ++position;
  }
}

}  // namespace

TriangleMesh readPly(const std::string& path, std::string_view bytes) {
  TextCursor text(bytes, path);
  const PlyHeader header = readHeader(text);
  PlyValues values(path, text, header.format);
  values.setEnd(bytes.data() + bytes.size());

  TriangleMesh mesh;
  TriangleSink sink{mesh, -1, {}};
  bool sawVertices = false;
  for (const PlyElement& element : header.elements) {
    enum Role : int { kSkip = -1, kX = 0, kY = 1, kZ = 2, kFace = 3, kStrip = 4 };
    std::vector<int> roles(element.properties.size(), kSkip);
    const bool isVertex = element.name == "vertex";
    if (isVertex) {
      const char* names[3] = {"x", "y", "z"};
      for (int axis = kX; axis <= kZ; ++axis) {
        const auto found = findProperty(element, {names[axis]});
        if (!found || element.properties[*found].listCountType) {
          text.fail(element.at, std::string("vertex element has no scalar '") + names[axis] + "'");
        }
        roles[*found] = axis;
      }
      if (element.count > 0xffffffffULL) text.fail(element.at, "too many vertices");
      mesh.vertices.reserve(std::min(element.count, bytes.size() / 3));  // bounds bogus counts
      sawVertices = true;
    } else if (element.name == "face" || element.name == "tristrips") {
      const auto list = findProperty(element, {"vertex_indices", "vertex_index"});
      if (!list || !element.properties[*list].listCountType) {
        text.fail(element.at, "element '" + element.name + "' has no vertex_indices list");
      }
      roles[*list] = element.name == "face" ? kFace : kStrip;
    }
    if (element.properties.empty()) continue;  // nothing stored, whatever the count
    for (std::size_t instance = 0; instance < element.count; ++instance) {
      values.enter(element, instance);
      Vec3 p = Vec3::Zero();
      for (std::size_t i = 0; i < element.properties.size(); ++i) {
        const PlyProperty& property = element.properties[i];
        switch (roles[i]) {
          case kX:
          case kY:
          case kZ:
            p[roles[i]] = values.real(property.type);
            break;
          case kFace:
            readFace(values, property, sink);
            break;
          case kStrip:
            readStrip(values, property, sink);
            break;
          default:
            values.skip(property);
        }
      }
      if (isVertex) mesh.vertices.push_back(p);
    }
  }
  if (!sawVertices) throw InputError(locate(path, "PLY file has no 'vertex' element"));
  if (sink.largestIndex >= static_cast<long long>(mesh.vertices.size())) {
    values.fail(sink.largestAt, "vertex index " + std::to_string(sink.largestIndex) +
                                    " out of range (" + std::to_string(mesh.vertices.size()) +
                                    " vertices)");
  }
  return mesh;
}

void formatPly(const TriangleMesh& mesh, std::string& out) {
  out += "ply\nformat binary_little_endian 1.0\ncomment written by kaboum\nelement vertex " +
         std::to_string(mesh.vertices.size()) +
         "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
         std::to_string(mesh.triangles.size()) +
         "\nproperty list uchar uint vertex_indices\nend_header\n";
  out.reserve(out.size() + 24 * mesh.vertices.size() + 13 * mesh.triangles.size());
  for (const Vec3& p : mesh.vertices) {
    for (int i = 0; i < 3; ++i) appendLittleEndian(out, p[i]);
  }
  for (const Triangle& t : mesh.triangles) {
    appendLittleEndian(out, std::uint8_t{3});
    for (const std::uint32_t v : t) appendLittleEndian(out, v);
  }
}

}  // namespace kaboum::io

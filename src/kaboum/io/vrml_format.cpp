// VRML 2.0 (.wrl), the subset the Robotics Library scenes use: Transform (translation, rotation,
// scale, scaleOrientation, center), Group, Collision, Anchor, Shape, IndexedFaceSet (coord,
// coordIndex with -1 separators, ccw), Coordinate, Box, Inline (url relative to the file), DEF/USE,
// comments. Appearance, normals, colours, lights, viewpoints, line and point sets are skipped;
// any other node is an error, so no geometry is dropped silently.
#include <Eigen/Geometry>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "kaboum/core/error.hpp"
#include "kaboum/io/mesh_formats.hpp"
#include "kaboum/io/text_cursor.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;

namespace {

using Affine = Eigen::Affine3d;

// A parsed node that can carry geometry. Groups (Transform, Group, Shape, Inline) hold children
// under a local transform; face sets hold fan-triangulated faces into a Coordinate node.
struct VrmlNode {
  enum class Kind { Group, FaceSet, Coordinate };
  Kind kind = Kind::Group;
  Affine transform = Affine::Identity();
  std::vector<std::shared_ptr<const VrmlNode>> children;
  std::shared_ptr<const VrmlNode> coord;
  std::vector<Triangle> faces;
  bool ccw = true;
  std::vector<Vec3> points;
};
using NodePtr = std::shared_ptr<const VrmlNode>;

// Nodes without surface geometry, skipped wherever they appear.
bool isSkippedNode(std::string_view type) {
  static constexpr std::string_view kSkipped[] = {"Appearance",
                                                  "Material",
                                                  "ImageTexture",
                                                  "MovieTexture",
                                                  "PixelTexture",
                                                  "TextureTransform",
                                                  "TextureCoordinate",
                                                  "Normal",
                                                  "Color",
                                                  "FontStyle",
                                                  "NavigationInfo",
                                                  "Viewpoint",
                                                  "Background",
                                                  "Fog",
                                                  "WorldInfo",
                                                  "DirectionalLight",
                                                  "PointLight",
                                                  "SpotLight",
                                                  "Sound",
                                                  "AudioClip",
                                                  "Script",
                                                  "TimeSensor",
                                                  "TouchSensor",
                                                  "PlaneSensor",
                                                  "CylinderSensor",
                                                  "SphereSensor",
                                                  "ProximitySensor",
                                                  "VisibilitySensor",
                                                  "PositionInterpolator",
                                                  "OrientationInterpolator",
                                                  "ScalarInterpolator",
                                                  "ColorInterpolator",
                                                  "CoordinateInterpolator",
                                                  "NormalInterpolator",
                                                  "IndexedLineSet",
                                                  "PointSet"};
  for (const std::string_view skipped : kSkipped) {
    if (type == skipped) return true;
  }
  return false;
}

bool isNumberStart(std::string_view token) {
  if (token.empty()) return false;
  const char c = token.front();
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
}

// An axis-aligned box centred at the origin, 12 counter-clockwise triangles.
std::shared_ptr<VrmlNode> boxFaceSet(const Vec3& size) {
  auto coord = std::make_shared<VrmlNode>();
  coord->kind = VrmlNode::Kind::Coordinate;
  for (std::uint32_t corner = 0; corner < 8; ++corner) {  // bit 0: +x, bit 1: +y, bit 2: +z
    coord->points.emplace_back((corner & 1 ? 0.5 : -0.5) * size.x(),
                               (corner & 2 ? 0.5 : -0.5) * size.y(),
                               (corner & 4 ? 0.5 : -0.5) * size.z());
  }
  auto box = std::make_shared<VrmlNode>();
  box->kind = VrmlNode::Kind::FaceSet;
  box->coord = std::move(coord);
  constexpr std::uint32_t kQuads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                          {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : kQuads) {
    box->faces.push_back({q[0], q[1], q[2]});
    box->faces.push_back({q[0], q[2], q[3]});
  }
  return box;
}

// Parsed files by canonical path (a file inlined twice is read once), the chain of files being
// read (to reject Inline cycles) and the node nesting depth across them.
struct InlineContext {
  std::map<std::filesystem::path, NodePtr> parsed;
  std::vector<std::filesystem::path> reading;
  int depth = 0;
};

// Parses `file` (shown as `path` in errors), or returns it from the cache.
NodePtr parseVrmlFile(const std::string& path, const std::filesystem::path& file,
                      InlineContext& context);

class VrmlParser {
 public:
  VrmlParser(const std::string& path, std::string_view text, InlineContext& context)
      : path_(path),
        text_(text, path_, {.hashComments = true, .commaIsSpace = true, .punctuation = "{}[]\""}),
        context_(context) {
    if (text.substr(0, 10) != "#VRML V2.0") {
      const std::string found =
          text.substr(0, 10) == "#VRML V1.0" ? "VRML 1.0 is not supported" : "not a VRML 2.0 file";
      text_.fail({1, 1}, found + " (the first line must start with '#VRML V2.0')");
    }
  }

  NodePtr parseFile() {
    auto root = std::make_shared<VrmlNode>();
    for (std::string_view token = text_.nextWord(); !token.empty(); token = text_.nextWord()) {
      if (token == "ROUTE") {
        for (int i = 0; i < 3; ++i) expectWord("ROUTE statement");  // from TO to
      } else if (token == "PROTO" || token == "EXTERNPROTO") {
        text_.fail("unsupported VRML statement '" + std::string(token) + "'");
      } else if (NodePtr node = nodeStatement(token)) {
        root->children.push_back(std::move(node));
      }
    }
    return root;
  }

 private:
  std::string_view expectWord(std::string_view what) {
    const std::string_view token = text_.nextWord();
    if (token.empty()) text_.fail("unexpected end of file in " + std::string(what));
    return token;
  }

  void expect(std::string_view token, std::string_view what) {
    const std::string_view found = expectWord(what);
    if (found != token) {
      text_.fail("expected '" + std::string(token) + "' in " + std::string(what) + ", found '" +
                 std::string(found) + "'");
    }
  }

  // DEF name Node | USE name | NULL | Node, starting at `token`. Returns null for NULL and for
  // skipped nodes.
  NodePtr nodeStatement(std::string_view token) {
    if (token == "USE") {
      const std::string name(expectWord("USE"));
      const auto found = defined_.find(name);
      if (found == defined_.end()) text_.fail("USE of undefined name '" + name + "'");
      return found->second;
    }
    if (token == "NULL") return nullptr;
    if (token == "DEF") {
      const std::string name(expectWord("DEF"));
      NodePtr node = parseNode(expectWord("DEF " + name));
      defined_[name] = node;
      return node;
    }
    return parseNode(token);
  }

  NodePtr parseNode(std::string_view type) {
    if (isNumberStart(type) || type.size() == 1) {
      text_.fail("expected a node type, found '" + std::string(type) + "'");
    }
    const TextLocation at = text_.wordLocation();
    const std::string typeName(type);
    expect("{", typeName);
    if (context_.depth == kMaxDepth) text_.fail(at, "nodes nested too deeply");
    const NestingGuard nested(context_.depth);
    if (typeName == "Transform" || typeName == "Group" || typeName == "Collision" ||
        typeName == "Anchor") {
      return group();
    }
    if (typeName == "Shape") return shape();
    if (typeName == "IndexedFaceSet") return faceSet();
    if (typeName == "Coordinate") return coordinate();
    if (typeName == "Box") return box();
    if (typeName == "Inline") return inlineNode();
    if (isSkippedNode(typeName)) {
      skipBalanced("{", "}");
      return nullptr;
    }
    text_.fail(at, "unsupported VRML node '" + typeName + "'");
  }

  // Calls field(name) for each field until the closing brace.
  template <typename Field>
  void fields(std::string_view node, Field&& field) {
    for (std::string_view token = expectWord(node); token != "}"; token = expectWord(node)) {
      if (token.size() == 1 || isNumberStart(token)) {
        text_.fail("expected a field name in " + std::string(node) + ", found '" +
                   std::string(token) + "'");
      }
      field(token);
    }
  }

  Vec3 vec3(std::string_view what) {
    Vec3 v;
    for (int i = 0; i < 3; ++i) v[i] = text_.toNumber(expectWord(what), what);
    return v;
  }

  Eigen::AngleAxisd rotation(std::string_view what) {
    const Vec3 axis = vec3(what);
    const double angle = text_.toNumber(expectWord(what), what);
    if (axis.norm() == 0.0) {
      if (angle != 0.0) text_.fail("rotation about a zero axis");
      return Eigen::AngleAxisd(0.0, Vec3::UnitZ());
    }
    return Eigen::AngleAxisd(angle, axis.normalized());
  }

  bool boolean(std::string_view what) {
    const std::string_view token = expectWord(what);
    if (token == "TRUE") return true;
    if (token == "FALSE") return false;
    text_.fail("expected TRUE or FALSE for " + std::string(what) + ", found '" +
               std::string(token) + "'");
  }

  // MFNode: one node statement or a bracketed list of them.
  template <typename Visit>
  void nodes(std::string_view what, Visit&& visit) {
    std::string_view token = expectWord(what);
    if (token != "[") {
      visit(nodeStatement(token));
      return;
    }
    for (token = expectWord(what); token != "]"; token = expectWord(what)) {
      visit(nodeStatement(token));
    }
  }

  // MF values of one kind: a single value or a bracketed list.
  template <typename Visit>
  void values(std::string_view what, Visit&& visit) {
    std::string_view token = expectWord(what);
    if (token != "[") {
      visit(token);
      return;
    }
    for (token = expectWord(what); token != "]"; token = expectWord(what)) visit(token);
  }

  NodePtr group() {
    auto node = std::make_shared<VrmlNode>();
    Vec3 translation = Vec3::Zero(), scale = Vec3::Ones(), center = Vec3::Zero();
    Eigen::AngleAxisd orientation(0.0, Vec3::UnitZ()), scaleOrientation(0.0, Vec3::UnitZ());
    fields("Transform", [&](std::string_view field) {
      if (field == "translation") {
        translation = vec3("translation");
      } else if (field == "rotation") {
        orientation = rotation("rotation");
      } else if (field == "scale") {
        scale = vec3("scale");
      } else if (field == "scaleOrientation") {
        scaleOrientation = rotation("scaleOrientation");
      } else if (field == "center") {
        center = vec3("center");
      } else if (field == "children") {
        nodes("children", [&](NodePtr child) {
          if (child) node->children.push_back(std::move(child));
        });
      } else {
        skipFieldValue();
      }
    });
    // VRML 2.0: T * C * R * SR * S * -SR * -C.
    node->transform = Eigen::Translation3d(translation + center) * orientation * scaleOrientation *
                      Eigen::Scaling(scale) * scaleOrientation.inverse() *
                      Eigen::Translation3d(-center);
    return node;
  }

  NodePtr shape() {
    auto node = std::make_shared<VrmlNode>();
    fields("Shape", [&](std::string_view field) {
      if (field != "geometry") {
        skipFieldValue();
        return;
      }
      const TextLocation at = text_.here();
      NodePtr geometry = nodeStatement(expectWord("geometry"));
      if (geometry && geometry->kind != VrmlNode::Kind::FaceSet) {
        text_.fail(at, "Shape geometry must be an IndexedFaceSet or Box");
      }
      if (geometry) node->children.push_back(std::move(geometry));
    });
    return node;
  }

  NodePtr faceSet() {
    auto node = std::make_shared<VrmlNode>();
    node->kind = VrmlNode::Kind::FaceSet;
    long long largestIndex = -1;
    TextLocation largestAt, nodeAt = text_.wordLocation();
    fields("IndexedFaceSet", [&](std::string_view field) {
      if (field == "coord") {
        const TextLocation at = text_.here();
        node->coord = nodeStatement(expectWord("coord"));
        if (node->coord && node->coord->kind != VrmlNode::Kind::Coordinate) {
          text_.fail(at, "coord must be a Coordinate node");
        }
      } else if (field == "coordIndex") {
        coordIndex(*node, largestIndex, largestAt);
      } else if (field == "ccw") {
        node->ccw = boolean("ccw");
      } else {
        skipFieldValue();
      }
    });
    if (!node->faces.empty() && !node->coord) text_.fail(nodeAt, "IndexedFaceSet without coord");
    if (node->coord && largestIndex >= static_cast<long long>(node->coord->points.size())) {
      text_.fail(largestAt, "coordIndex " + std::to_string(largestIndex) + " out of range (" +
                                std::to_string(node->coord->points.size()) + " points)");
    }
    return node;
  }

  // Polygons separated by -1 (the last one may end without), fan-triangulated.
  void coordIndex(VrmlNode& node, long long& largestIndex, TextLocation& largestAt) {
    std::uint32_t first = 0, previous = 0, corners = 0;
    TextLocation polygonAt;
    const auto endPolygon = [&] {
      if (corners > 0 && corners < 3) text_.fail(polygonAt, "face with fewer than 3 vertices");
      corners = 0;
    };
    values("coordIndex", [&](std::string_view token) {
      const long long index = text_.toInteger(token, "coordIndex");
      if (index == -1) {
        endPolygon();
        return;
      }
      if (index < 0) text_.fail("negative coordIndex " + std::to_string(index));
      if (index > 0xffffffffLL) text_.fail("coordIndex " + std::to_string(index) + " too large");
      if (index > largestIndex) {
        largestIndex = index;
        largestAt = text_.wordLocation();
      }
      const auto current = static_cast<std::uint32_t>(index);
      if (corners == 0) {
        first = current;
        polygonAt = text_.wordLocation();
      }
      if (corners >= 2) node.faces.push_back({first, previous, current});
      previous = current;
      ++corners;
    });
    endPolygon();
  }

  NodePtr coordinate() {
    auto node = std::make_shared<VrmlNode>();
    node->kind = VrmlNode::Kind::Coordinate;
    fields("Coordinate", [&](std::string_view field) {
      if (field != "point") {
        skipFieldValue();
        return;
      }
      Vec3 p;
      int axis = 0;
      values("point", [&](std::string_view token) {
        p[axis] = text_.toNumber(token, "point coordinate");
        if (++axis == 3) {
          node->points.push_back(p);
          axis = 0;
        }
      });
      if (axis != 0) text_.fail("point list length is not a multiple of 3");
    });
    return node;
  }

  NodePtr box() {
    Vec3 size(2.0, 2.0, 2.0);
    fields("Box", [&](std::string_view field) {
      if (field == "size") {
        size = vec3("size");
      } else {
        skipFieldValue();
      }
    });
    return boxFaceSet(size);
  }

  NodePtr inlineNode() {
    std::vector<std::pair<std::string, TextLocation>> urls;
    fields("Inline", [&](std::string_view field) {
      if (field != "url") {
        skipFieldValue();
        return;
      }
      values("url", [&](std::string_view token) {
        if (token != "\"") text_.fail("expected a quoted url, found '" + std::string(token) + "'");
        const TextLocation at = text_.wordLocation();
        urls.emplace_back(text_.quoted(), at);
      });
    });
    if (urls.empty()) return nullptr;
    const std::filesystem::path directory = std::filesystem::path(path_).parent_path();
    for (const auto& [url, at] : urls) {
      const std::filesystem::path candidate = directory / url;
      std::error_code error;
      if (!std::filesystem::is_regular_file(candidate, error)) continue;
      const std::filesystem::path canonical = std::filesystem::weakly_canonical(candidate, error);
      for (const auto& reading : context_.reading) {
        if (reading == canonical) text_.fail(at, "Inline cycle: '" + url + "' includes itself");
      }
      return parseVrmlFile(candidate.lexically_normal().string(), canonical, context_);
    }
    text_.fail(urls.front().second, "Inline file not found: '" + urls.front().first +
                                        "' (looked for " +
                                        (directory / urls.front().first).string() + ")");
  }

  // Skips one field value of any type: numbers, strings, booleans, a node or a bracketed list.
  void skipFieldValue() {
    const std::string_view token = expectWord("field value");
    if (token == "[") {
      skipBalanced("[", "]");
    } else if (token == "\"") {
      text_.quoted();
    } else if (token == "DEF") {
      expectWord("DEF");
      expectWord("DEF");
      expect("{", "DEF");
      skipBalanced("{", "}");
    } else if (token == "USE") {
      expectWord("USE");
    } else if (isNumberStart(token)) {
      while (isNumberStart(text_.peekWord())) text_.nextWord();
    } else if (token != "TRUE" && token != "FALSE" && token != "NULL") {
      expect("{", std::string(token));  // a node type
      skipBalanced("{", "}");
    }
  }

  // After `open`: skips to the matching `close`, across nested brackets and strings.
  void skipBalanced(std::string_view open, std::string_view close) {
    const TextLocation openedAt = text_.wordLocation();
    std::vector<char> stack{close.front()};
    while (!stack.empty()) {
      const std::string_view token = text_.nextWord();
      if (token.empty()) text_.fail(openedAt, "unclosed '" + std::string(open) + "'");
      if (token == "\"") {
        text_.quoted();
      } else if (token == "{" || token == "[") {
        stack.push_back(token == "{" ? '}' : ']');
      } else if (token == "}" || token == "]") {
        if (token.front() != stack.back()) {
          text_.fail("mismatched '" + std::string(token) + "'");
        }
        stack.pop_back();
      }
    }
  }

  // Bounds the recursion of nested nodes (also through Inline), so hostile input cannot overflow
  // the stack; real scenes nest a few dozen levels at most.
  static constexpr int kMaxDepth = 200;
  struct NestingGuard {
    explicit NestingGuard(int& depth) : counter_(++depth) {}
    ~NestingGuard() { --counter_; }
    NestingGuard(const NestingGuard&) = delete;
    NestingGuard& operator=(const NestingGuard&) = delete;
    int& counter_;
  };

  const std::string path_;
  TextCursor text_;
  InlineContext& context_;
  std::map<std::string, NodePtr, std::less<>> defined_;
};

NodePtr parseVrmlFile(const std::string& path, const std::filesystem::path& file,
                      InlineContext& context) {
  if (const auto found = context.parsed.find(file); found != context.parsed.end()) {
    return found->second;
  }
  const std::string text = readFileBytes(path);
  context.reading.push_back(file);
  NodePtr root = VrmlParser(path, text, context).parseFile();
  context.reading.pop_back();
  context.parsed.emplace(file, root);
  return root;
}

// Appends the faces below `node`, placed by `world`. Faces flip when ccw is FALSE or the transform
// mirrors (negative determinant), so they stay counter-clockwise seen from outside.
void appendGeometry(const VrmlNode& node, const Affine& world, const std::string& path,
                    TriangleMesh& mesh) {
  if (node.kind == VrmlNode::Kind::Group) {
    const Affine placed = world * node.transform;
    for (const NodePtr& child : node.children) appendGeometry(*child, placed, path, mesh);
    return;
  }
  if (node.kind != VrmlNode::Kind::FaceSet || !node.coord || node.faces.empty()) return;
  if (mesh.vertices.size() + node.coord->points.size() > 0xffffffffULL) {
    throw InputError(locate(path, "more than 2^32 vertices once USE and Inline are expanded"));
  }
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  for (const Vec3& p : node.coord->points) mesh.vertices.push_back(world * p);
  const bool flip = !node.ccw != (world.linear().determinant() < 0.0);
  for (Triangle t : node.faces) {
    for (std::uint32_t& v : t) v += base;
    if (flip) std::swap(t[1], t[2]);
    mesh.triangles.push_back(t);
  }
}

}  // namespace

TriangleMesh readVrml(const std::string& path) {
  InlineContext context;
  std::error_code error;
  const NodePtr root = parseVrmlFile(path, std::filesystem::weakly_canonical(path, error), context);
  TriangleMesh mesh;
  appendGeometry(*root, Affine::Identity(), path, mesh);
  return mesh;
}

}  // namespace kaboum::io

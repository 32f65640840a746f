#include "rl_reference.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace kaboum::rl {

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// An XML element as the Robotics Library's files write it (no nesting of the same tag): its start
// tag's attributes, its content, and where it ends in the text.
struct Element {
  std::string attributes;
  std::string body;
  std::size_t end = 0;
};

// Whether `text` has the start of a `<tag` element at `at` (the tag name ends there).
bool startsElement(const std::string& text, std::size_t at, const std::string& tag) {
  if (text.compare(at, tag.size() + 1, "<" + tag) != 0) return false;
  const std::size_t after = at + tag.size() + 1;
  return after < text.size() && (std::isspace(static_cast<unsigned char>(text[after])) ||
                                 text[after] == '>' || text[after] == '/');
}

// The first `<tag …>…</tag>` (or `<tag …/>`) in `text` from `from`.
std::optional<Element> findElement(const std::string& text, const std::string& tag,
                                   std::size_t from = 0) {
  for (std::size_t at = text.find('<', from); at != std::string::npos;
       at = text.find('<', at + 1)) {
    if (!startsElement(text, at, tag)) continue;
    const std::size_t close = text.find('>', at);
    if (close == std::string::npos) return std::nullopt;
    Element element;
    element.attributes = text.substr(at + tag.size() + 1, close - at - tag.size() - 1);
    if (text[close - 1] == '/') {
      element.end = close + 1;
      return element;
    }
    const std::string endTag = "</" + tag + ">";
    const std::size_t end = text.find(endTag, close);
    if (end == std::string::npos) return std::nullopt;
    element.body = text.substr(close + 1, end - close - 1);
    element.end = end + endTag.size();
    return element;
  }
  return std::nullopt;
}

// The value of attribute `name` in a start tag's attributes, empty when absent.
std::string attribute(const std::string& attributes, const std::string& name) {
  const std::string key = name + "=\"";
  const std::size_t at = attributes.find(key);
  if (at == std::string::npos) return {};
  const std::size_t end = attributes.find('"', at + key.size());
  return end == std::string::npos ? std::string()
                                  : attributes.substr(at + key.size(), end - at - key.size());
}

// The text of `<tag>…</tag>` inside `element`, empty when absent.
std::string child(const std::string& element, const std::string& tag) {
  const std::optional<Element> found = findElement(element, tag);
  return found ? found->body : std::string();
}

// The vector of `<x>`, `<y>`, `<z>` inside `element`, `fallback` where one is absent.
Eigen::Vector3d xyz(const std::string& element, const Eigen::Vector3d& fallback) {
  Eigen::Vector3d v = fallback;
  for (int i = 0; i < 3; ++i) {
    const std::string text = child(element, std::string(1, static_cast<char>('x' + i)));
    if (!text.empty()) v[i] = std::stod(text);
  }
  return v;
}

// The Robotics Library's fixed transform: rotation Rz·Ry·Rx of angles in degrees, translation.
Pose fixedTransform(const std::string& element) {
  const Eigen::Vector3d degrees = xyz(child(element, "rotation"), Eigen::Vector3d::Zero());
  const Eigen::Vector3d radians = degrees * M_PI / 180;
  Pose pose = Pose::Identity();
  pose.linear() = (Eigen::AngleAxisd(radians.z(), Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(radians.y(), Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(radians.x(), Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  pose.translation() = xyz(child(element, "translation"), Eigen::Vector3d::Zero());
  return pose;
}

// The `idref` of the `<tag idref="…"/>` inside `element`, empty when absent.
std::string idref(const std::string& element, const std::string& tag) {
  const std::optional<Element> found = findElement(element, tag);
  return found ? attribute(found->attributes, "idref") : std::string();
}

// VRML tokens: braces, brackets, quoted strings (without quotes), and words; comments dropped.
std::vector<std::string> vrmlTokens(const std::string& text) {
  std::vector<std::string> tokens;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (std::isspace(static_cast<unsigned char>(c)) || c == ',') {
      ++i;
    } else if (c == '{' || c == '}' || c == '[' || c == ']') {
      tokens.emplace_back(1, c);
      ++i;
    } else if (c == '"') {
      const std::size_t end = text.find('"', i + 1);
      tokens.push_back(text.substr(i + 1, end - i - 1));
      i = end + 1;
    } else {
      const std::size_t start = i;
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i])) &&
             std::string_view("{}[],#\"").find(text[i]) == std::string_view::npos) {
        ++i;
      }
      tokens.push_back(text.substr(start, i - start));
    }
  }
  return tokens;
}

struct VrmlReader {
  std::vector<std::string> expand;
  std::vector<PlacedInline> placements;

  // The named Transform a node lies in: its DEF name (the nearest one; for the contents of an
  // expanded inline, the inline's) and its pose in the root frame.
  struct Named {
    std::string def;
    Pose pose = Pose::Identity();
    bool locked = false;  // inside an expanded inline: its DEF names do not count
  };

  void readFile(const std::string& path, const Pose& pose, const Named& named) {
    const std::vector<std::string> tokens = vrmlTokens(slurp(path));
    std::size_t i = 0;
    const std::string directory = std::filesystem::path(path).parent_path().string();
    while (i < tokens.size()) readNode(tokens, i, pose, named, directory);
  }

  // Skips a balanced {…} or […] starting at tokens[i].
  static void skipBlock(const std::vector<std::string>& tokens, std::size_t& i) {
    int depth = 0;
    do {
      if (tokens[i] == "{" || tokens[i] == "[") ++depth;
      if (tokens[i] == "}" || tokens[i] == "]") --depth;
      ++i;
    } while (depth > 0 && i < tokens.size());
  }

  void readNode(const std::vector<std::string>& tokens, std::size_t& i, const Pose& parent,
                Named named, const std::string& directory) {
    bool definesName = false;
    if (tokens[i] == "DEF") {
      if (!named.locked) {
        named.def = tokens[i + 1];
        definesName = true;
      }
      i += 2;
    }
    const std::string type = tokens[i++];
    if (i >= tokens.size() || tokens[i] != "{") return;  // the header line, a stray word
    if (type == "Shape") {
      placements.push_back({named.def, "Shape", parent, named.pose});
      skipBlock(tokens, i);
      return;
    }
    ++i;  // {
    Pose local = Pose::Identity();
    Eigen::AngleAxisd rotation(0, Eigen::Vector3d::UnitZ());
    std::size_t children = 0;
    std::string url;
    while (tokens[i] != "}") {
      const std::string& field = tokens[i];
      if (field == "translation") {
        local.translation() = Eigen::Vector3d(std::stod(tokens[i + 1]), std::stod(tokens[i + 2]),
                                              std::stod(tokens[i + 3]));
        i += 4;
      } else if (field == "rotation") {
        rotation =
            Eigen::AngleAxisd(std::stod(tokens[i + 4]),
                              Eigen::Vector3d(std::stod(tokens[i + 1]), std::stod(tokens[i + 2]),
                                              std::stod(tokens[i + 3]))
                                  .normalized());
        i += 5;
      } else if (field == "children") {
        children = ++i;
        skipBlock(tokens, i);
      } else if (field == "url") {
        url = tokens[i + 1] == "[" ? tokens[i + 2] : tokens[i + 1];
        i += tokens[i + 1] == "[" ? 4 : 2;
      } else if (tokens[i + 1] == "{" || tokens[i + 1] == "[") {
        ++i;
        skipBlock(tokens, i);
      } else {
        ++i;
      }
    }
    ++i;  // }
    local.linear() = rotation.toRotationMatrix();
    const Pose pose = parent * local;
    if (definesName) named.pose = pose;
    if (type == "Inline") {
      const std::string name = std::filesystem::path(url).filename().string();
      if (std::find(expand.begin(), expand.end(), name) != expand.end()) {
        readFile(directory + "/" + url, pose, Named{named.def, named.pose, true});
      } else {
        placements.push_back({named.def, name, pose, named.pose});
      }
      return;
    }
    if (children == 0) return;
    std::size_t c = children + 1;  // past [
    while (tokens[c] != "]") readNode(tokens, c, pose, named, directory);
  }
};

}  // namespace

std::vector<std::string> MdlModel::jointIds() const {
  std::vector<std::string> ids;
  for (const MdlTransform& t : transforms) {
    if (t.kind != MdlTransform::Kind::Fixed) ids.push_back(t.id);
  }
  return ids;
}

std::map<std::string, Pose> MdlModel::framePoses(const std::map<std::string, double>& q) const {
  std::map<std::string, Pose> poses{{worldId, world}};
  for (const MdlTransform& t : transforms) {
    Pose step = t.fixed;
    if (t.kind == MdlTransform::Kind::Revolute) {
      step = Pose(Eigen::AngleAxisd(q.at(t.id), t.axis.normalized()));
    } else if (t.kind == MdlTransform::Kind::Prismatic) {
      step = Pose(Eigen::Translation3d(q.at(t.id) * t.axis.normalized()));
    }
    poses[t.b] = poses.at(t.a) * step;
  }
  return poses;
}

MdlModel readMdl(const std::string& path) {
  const std::string text = slurp(path);
  MdlModel model;
  const std::optional<Element> world = findElement(text, "world");
  if (!world) throw std::runtime_error(path + ": no <world>");
  model.worldId = attribute(world->attributes, "id");
  model.world = fixedTransform(world->body);
  // The transforms in the order of the file.
  for (std::size_t at = text.find('<'); at != std::string::npos; at = text.find('<', at + 1)) {
    std::string kind;
    for (const char* tag : {"fixed", "revolute", "prismatic"}) {
      if (startsElement(text, at, tag)) kind = tag;
    }
    if (kind.empty()) continue;
    const std::optional<Element> element = findElement(text, kind, at);
    if (!element) throw std::runtime_error(path + ": an unterminated <" + kind + ">");
    MdlTransform t;
    t.kind = kind == "fixed"      ? MdlTransform::Kind::Fixed
             : kind == "revolute" ? MdlTransform::Kind::Revolute
                                  : MdlTransform::Kind::Prismatic;
    t.id = attribute(element->attributes, "id");
    const std::string& body = element->body;
    t.a = idref(body, "a");
    t.b = idref(body, "b");
    if (t.kind == MdlTransform::Kind::Fixed) {
      t.fixed = fixedTransform(body);
    } else {
      t.axis = xyz(child(body, "axis"), Eigen::Vector3d::UnitZ());
    }
    model.transforms.push_back(t);
    at = element->end - 1;
  }
  return model;
}

std::vector<PlacedInline> readVrmlPlacements(const std::string& path,
                                             const std::vector<std::string>& expand) {
  VrmlReader reader{expand, {}};
  reader.readFile(path, Pose::Identity(), {});
  return reader.placements;
}

}  // namespace kaboum::rl

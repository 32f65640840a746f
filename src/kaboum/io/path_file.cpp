#include "kaboum/io/path_file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <set>

#include "kaboum/core/error.hpp"
#include "kaboum/io/json_kinematics.hpp"

namespace kaboum::io {

namespace {

using nlohmann::json;

constexpr const char* kFormat = "kaboum-path";
constexpr int kVersion = 1;

// Checks a parsed path file, naming the file and the key path of every error.
class PathReader {
 public:
  explicit PathReader(std::string file) : file_(std::move(file)) {}

  PathFile read(const json& root) const {
    requireObject(root, "", {"format", "version", "scene", "robots", "waypoints", "held"});
    const json& format = member(root, "", "format");
    if (!format.is_string() || format.get<std::string>() != kFormat) {
      fail("format", fmt::format("expected \"{}\", got {}", kFormat, shown(format)));
    }
    const json& version = member(root, "", "version");
    if (!version.is_number_integer() || version.get<long>() != kVersion) {
      fail("version", fmt::format("expected {}, got {}", kVersion, shown(version)));
    }
    PathFile path;
    if (root.contains("scene")) path.scene = text(root.at("scene"), "scene");
    path.robots = robots(member(root, "", "robots"));
    path.waypoints = waypoints(member(root, "", "waypoints"));
    if (root.contains("held")) path.held = held(root.at("held"));
    return path;
  }

 private:
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(locate(file_, key.empty() ? what : key + ": " + what));
  }

  // A value in a message: its JSON, cut after 40 characters.
  static std::string shown(const json& value) {
    constexpr std::size_t kShown = 40;
    const std::string text = value.dump();
    return text.size() > kShown ? text.substr(0, kShown) + "..." : text;
  }

  static std::string child(const std::string& key, const std::string& name) {
    return key.empty() ? name : key + "." + name;
  }

  void requireObject(const json& value, const std::string& key,
                     const std::set<std::string>& allowed) const {
    if (!value.is_object()) fail(key, "expected an object, got " + shown(value));
    for (const auto& [name, entry] : value.items()) {
      if (!allowed.contains(name)) fail(child(key, name), "unknown key");
    }
  }

  const json& member(const json& object, const std::string& key, const std::string& name) const {
    if (!object.contains(name)) fail(child(key, name), "missing");
    return object.at(name);
  }

  const json& list(const json& value, const std::string& key) const {
    if (!value.is_array()) fail(key, "expected a list, got " + shown(value));
    return value;
  }

  std::string text(const json& value, const std::string& key) const {
    if (!value.is_string()) fail(key, "expected a string, got " + shown(value));
    return value.get<std::string>();
  }

  double number(const json& value, const std::string& key) const {
    if (!value.is_number()) fail(key, "expected a number, got " + shown(value));
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail(key, "not a finite number");
    return x;
  }

  std::vector<double> numbers(const json& value, const std::string& key, std::size_t count) const {
    list(value, key);
    if (value.size() != count) {
      fail(key, fmt::format("expected {} numbers, got {}", count, value.size()));
    }
    std::vector<double> result;
    for (std::size_t i = 0; i < count; ++i) {
      result.push_back(number(value[i], fmt::format("{}[{}]", key, i)));
    }
    return result;
  }

  std::vector<std::string> robots(const json& value) const {
    if (list(value, "robots").empty()) fail("robots", "no robot");
    std::vector<std::string> names;
    for (std::size_t r = 0; r < value.size(); ++r) {
      const std::string key = fmt::format("robots[{}]", r);
      names.push_back(text(value[r], key));
      if (names.back().empty()) fail(key, "empty name");
      for (std::size_t earlier = 0; earlier < r; ++earlier) {
        if (names[earlier] == names.back()) {
          fail(key, fmt::format("robot '{}' is already robots[{}]", names.back(), earlier));
        }
      }
    }
    return names;
  }

  std::vector<std::vector<double>> waypoints(const json& value) const {
    if (list(value, "waypoints").empty()) fail("waypoints", "no waypoint");
    std::vector<std::vector<double>> result;
    for (std::size_t w = 0; w < value.size(); ++w) {
      const std::string key = fmt::format("waypoints[{}]", w);
      const json& waypoint = list(value[w], key);
      if (w > 0 && waypoint.size() != result[0].size()) {
        fail(key, fmt::format("{} values, waypoints[0] has {}", waypoint.size(), result[0].size()));
      }
      result.push_back(numbers(waypoint, key, waypoint.size()));
    }
    return result;
  }

  Pose pose(const json& value, const std::string& key) const {
    requireObject(value, key, {"position", "quaternion_wxyz"});
    Pose result = Pose::Identity();
    if (value.contains("position")) {
      const std::vector<double> p = numbers(value.at("position"), child(key, "position"), 3);
      result.translation() = Vec3(p[0], p[1], p[2]);
    }
    if (value.contains("quaternion_wxyz")) {
      const std::string quaternionKey = child(key, "quaternion_wxyz");
      const std::vector<double> q = numbers(value.at("quaternion_wxyz"), quaternionKey, 4);
      const Eigen::Quaterniond rotation(q[0], q[1], q[2], q[3]);
      if (!(rotation.norm() > 1e-12)) fail(quaternionKey, "zero quaternion");
      result.linear() = rotation.normalized().toRotationMatrix();
    }
    return result;
  }

  std::vector<HeldObject> held(const json& value) const {
    std::vector<HeldObject> result;
    for (std::size_t h = 0; h < list(value, "held").size(); ++h) {
      const std::string key = fmt::format("held[{}]", h);
      requireObject(value[h], key, {"robot", "object", "link", "pose"});
      HeldObject object;
      object.robot = text(member(value[h], key, "robot"), child(key, "robot"));
      object.object = text(member(value[h], key, "object"), child(key, "object"));
      object.link = text(member(value[h], key, "link"), child(key, "link"));
      if (value[h].contains("pose")) object.objectInLink = pose(value[h].at("pose"), key + ".pose");
      result.push_back(std::move(object));
    }
    return result;
  }

  std::string file_;
};

// 1-based line and column of byte `offset` (1-based, as json::parse_error::byte) in `text`.
std::pair<long, long> lineAndColumn(const std::string& text, std::size_t offset) {
  long line = 1, column = 1;
  for (std::size_t i = 0; i + 1 < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// What a json::exception says after its "[json.exception.NAME] " prefix and, for a parse error,
// after "parse error at line L, column C: ".
std::string jsonErrorDetail(const std::string& message) {
  const std::size_t bracket = message.find("] ");
  std::string detail = bracket == std::string::npos ? message : message.substr(bracket + 2);
  const std::size_t colon = detail.find(": ");
  if (detail.starts_with("parse error") && colon != std::string::npos) detail.erase(0, colon + 2);
  return detail;
}

}  // namespace

json readJsonFile(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  if (!in || std::filesystem::is_directory(file))
    throw InputError(locate(name, "cannot open file"));
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(locate(name, "cannot read file"));
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    const auto [line, column] = lineAndColumn(text, e.byte);
    throw InputError(locate(name, "invalid JSON: " + jsonErrorDetail(e.what()), line, column));
  } catch (const json::exception& e) {  // a number too large for a double
    throw InputError(locate(name, "invalid JSON: " + jsonErrorDetail(e.what())));
  }
}

PathFile readPathFile(const std::filesystem::path& file) {
  return PathReader(file.string()).read(readJsonFile(file));
}

json toJson(const PathFile& path) {
  json held = json::array();
  for (const HeldObject& object : path.held) {
    held.push_back({{"robot", object.robot},
                    {"object", object.object},
                    {"link", object.link},
                    {"pose", toJson(object.objectInLink)}});
  }
  return {{"format", kFormat},     {"version", kVersion},         {"scene", path.scene},
          {"robots", path.robots}, {"waypoints", path.waypoints}, {"held", held}};
}

void writePathFile(const std::filesystem::path& file, const PathFile& path) {
  const json root = toJson(path);
  std::string text = "{\n";
  std::size_t written = 0;
  for (const auto& [key, value] : root.items()) {
    text += "  " + json(key).dump() + ": ";
    if (value.is_array() && !value.empty() && (key == "waypoints" || key == "held")) {
      text += "[\n";
      for (std::size_t i = 0; i < value.size(); ++i) {
        text += "    " + value[i].dump() + (i + 1 < value.size() ? ",\n" : "\n");
      }
      text += "  ]";
    } else {
      text += value.dump();
    }
    text += ++written < root.size() ? ",\n" : "\n";
  }
  text += "}\n";
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out.flush()) throw InputError(locate(file.string(), "cannot write file"));
}

}  // namespace kaboum::io

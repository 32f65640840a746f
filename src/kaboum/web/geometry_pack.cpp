#include "kaboum/web/geometry_pack.hpp"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

namespace kaboum::web {

namespace {

constexpr double kQuantizationSteps = 65535.0;

std::string base64(std::span<const std::uint8_t> bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t left = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t word = std::uint32_t{bytes[i]} << 16;
    if (left > 1) word |= std::uint32_t{bytes[i + 1]} << 8;
    if (left > 2) word |= bytes[i + 2];
    for (std::size_t k = 0; k < 4; ++k) {
      out.push_back(k <= left ? kAlphabet[(word >> (18 - 6 * k)) & 63] : '=');
    }
  }
  return out;
}

template <typename Value>
std::span<const std::uint8_t> bytesOf(const std::vector<Value>& values) {
  static_assert(std::endian::native == std::endian::little, "the page reads little-endian data");
  return {reinterpret_cast<const std::uint8_t*>(values.data()), values.size() * sizeof(Value)};
}

}  // namespace

std::string deflateBase64(std::span<const std::uint8_t> bytes) {
  uLongf size = compressBound(static_cast<uLong>(bytes.size()));
  std::vector<std::uint8_t> deflated(size);
  if (compress2(deflated.data(), &size, bytes.data(), static_cast<uLong>(bytes.size()),
                Z_BEST_COMPRESSION) != Z_OK) {
    throw std::runtime_error("zlib could not deflate the page's geometry");
  }
  deflated.resize(size);
  return base64(deflated);
}

std::size_t GeometryPack::addPositions(std::span<const Vec3> points) {
  Vec3 lower = Vec3::Zero();
  Vec3 upper = Vec3::Zero();
  if (!points.empty()) {
    lower = upper = points.front();
    for (const Vec3& point : points) {
      lower = lower.cwiseMin(point);
      upper = upper.cwiseMax(point);
    }
  }
  const Vec3 step = (upper - lower) / kQuantizationSteps;
  const std::size_t first = positions_.size() / 3;
  for (const Vec3& point : points) {
    for (int axis = 0; axis < 3; ++axis) {
      const double steps = step[axis] > 0 ? (point[axis] - lower[axis]) / step[axis] : 0.0;
      positions_.push_back(static_cast<std::uint16_t>(std::lround(steps)));
    }
  }
  entries_.push_back({{"min", {lower.x(), lower.y(), lower.z()}},
                      {"step", {step.x(), step.y(), step.z()}},
                      {"positions", {first, points.size()}},
                      {"indices", {indices_.size(), 0}}});
  return entries_.size() - 1;
}

std::size_t GeometryPack::addMesh(const geometry::TriangleMesh& mesh) {
  const std::size_t entry = addPositions(mesh.vertices);
  for (const geometry::Triangle& triangle : mesh.triangles) {
    indices_.insert(indices_.end(), triangle.begin(), triangle.end());
  }
  entries_[entry]["indices"][1] = mesh.triangles.size() * 3;
  return entry;
}

std::size_t GeometryPack::addPoints(std::span<const Vec3> points) {
  return addPositions(points);
}

nlohmann::json GeometryPack::json() const {
  return {{"entries", entries_},
          {"positions", deflateBase64(bytesOf(positions_))},
          {"indices", deflateBase64(bytesOf(indices_))}};
}

}  // namespace kaboum::web

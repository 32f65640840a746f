#include "kaboum/io/decomposition_cache.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <bit>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <string_view>
#include <system_error>
#include <type_traits>

#include "kaboum/core/error.hpp"

namespace kaboum::io {

namespace {

static_assert(std::endian::native == std::endian::little, "entries are little-endian");
// Every field of DecompositionOptions enters the key (appendOptions); a new field must too.
static_assert(sizeof(DecompositionOptions) == 7 * 8, "a new decomposition option needs a key");

constexpr std::string_view kMagic = "KBDCACHE";
constexpr std::string_view kEntrySuffix = ".decomposition";
constexpr std::size_t kDigestBytes = 16;
// magic, version, key, payload size; then the payload and its checksum.
constexpr std::size_t kHeaderBytes = kMagic.size() + 4 + kDigestBytes + 8;
constexpr std::size_t kChecksumBytes = 8;

using Digest = std::array<std::uint64_t, 2>;

std::uint64_t rotateLeft(std::uint64_t x, int r) {
  return (x << r) | (x >> (64 - r));
}

std::uint64_t finalMix(std::uint64_t k) {
  k ^= k >> 33;
  k *= 0xff51afd7ed558ccdULL;
  k ^= k >> 33;
  k *= 0xc4ceb9fe1a85ec53ULL;
  k ^= k >> 33;
  return k;
}

// MurmurHash3 x64_128 (seed 0) of `data`.
Digest murmurHash3(std::string_view data) {
  constexpr std::uint64_t c1 = 0x87c37b91114253d5ULL, c2 = 0x4cf5ad432745937fULL;
  const auto mix1 = [&](std::uint64_t k) { return rotateLeft(k * c1, 31) * c2; };
  const auto mix2 = [&](std::uint64_t k) { return rotateLeft(k * c2, 33) * c1; };
  std::uint64_t h1 = 0, h2 = 0;
  const std::size_t blocks = data.size() / 16;
  for (std::size_t b = 0; b < blocks; ++b) {
    std::uint64_t k1 = 0, k2 = 0;
    std::memcpy(&k1, data.data() + 16 * b, 8);
    std::memcpy(&k2, data.data() + 16 * b + 8, 8);
    h1 ^= mix1(k1);
    h1 = (rotateLeft(h1, 27) + h2) * 5 + 0x52dce729;
    h2 ^= mix2(k2);
    h2 = (rotateLeft(h2, 31) + h1) * 5 + 0x38495ab5;
  }
  const std::string_view tail = data.substr(16 * blocks);
  std::uint64_t k1 = 0, k2 = 0;
  for (std::size_t i = 0; i < tail.size(); ++i) {
    const auto byte = static_cast<std::uint64_t>(static_cast<unsigned char>(tail[i]));
    (i < 8 ? k1 : k2) |= byte << (8 * (i % 8));
  }
  if (tail.size() > 8) h2 ^= mix2(k2);
  if (!tail.empty()) h1 ^= mix1(k1);
  h1 ^= data.size();
  h2 ^= data.size();
  h1 += h2;
  h2 += h1;
  h1 = finalMix(h1);
  h2 = finalMix(h2);
  h1 += h2;
  h2 += h1;
  return {h1, h2};
}

// Appends values in their native (little-endian) bytes.
class ByteWriter {
 public:
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void putCount(std::size_t count) { put(static_cast<std::uint64_t>(count)); }
  void putVec3(const Vec3& v) {
    for (int i = 0; i < 3; ++i) put(v[i]);
  }
  void putMesh(const TriangleMesh& mesh) {
    putCount(mesh.vertices.size());
    for (const Vec3& v : mesh.vertices) putVec3(v);
    putCount(mesh.triangles.size());
    for (const Triangle& t : mesh.triangles) {
      for (const std::uint32_t index : t) put(index);
    }
  }
  void putText(const std::string& text) {
    putCount(text.size());
    bytes_ += text;
  }
  void append(std::string_view bytes) { bytes_ += bytes; }
  [[nodiscard]] const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

// Reads what ByteWriter wrote; ok() turns false (and stays so) at the first read past the end or
// a count larger than the bytes left could hold.
class ByteReader {
 public:
  explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}
  template <typename T>
  T get() {
    T value{};
    if (!ok_ || bytes_.size() - position_ < sizeof(T)) {
      ok_ = false;
      return value;
    }
    std::memcpy(&value, bytes_.data() + position_, sizeof(T));
    position_ += sizeof(T);
    return value;
  }
  // A count of items of at least `itemBytes` bytes each.
  std::size_t getCount(std::size_t itemBytes) {
    const auto count = get<std::uint64_t>();
    if (count > (bytes_.size() - position_) / itemBytes) ok_ = false;
    return ok_ ? static_cast<std::size_t>(count) : 0;
  }
  Vec3 getVec3() {
    Vec3 v;
    for (int i = 0; i < 3; ++i) v[i] = get<double>();
    return v;
  }
  TriangleMesh getMesh() {
    TriangleMesh mesh;
    mesh.vertices.resize(getCount(3 * sizeof(double)));
    for (Vec3& v : mesh.vertices) v = getVec3();
    mesh.triangles.resize(getCount(3 * sizeof(std::uint32_t)));
    for (Triangle& t : mesh.triangles) {
      for (std::uint32_t& index : t) index = get<std::uint32_t>();
    }
    return mesh;
  }
  std::string getText() {
    const std::size_t size = getCount(1);
    std::string text(bytes_.substr(position_, size));
    position_ += size;
    return text;
  }
  [[nodiscard]] bool ok() const { return ok_; }
  [[nodiscard]] bool atEnd() const { return position_ == bytes_.size(); }

 private:
  std::string_view bytes_;
  std::size_t position_ = 0;
  bool ok_ = true;
};

Digest entryKey(const TriangleMesh& mesh, const DecompositionOptions& options) {
  ByteWriter key;
  key.put(kDecompositionCacheVersion);
  key.put(options.epsilon);
  key.put(options.epsilonPercent);
  key.putCount(options.maxPieces);
  key.putCount(options.concavitySamples);
  key.putCount(options.bridgeSamples);
  key.putCount(options.refineRounds);
  key.put(options.seed);
  key.putMesh(mesh);
  return murmurHash3(key.bytes());
}

std::string encodeStats(const DecompositionStats& stats) {
  ByteWriter out;
  for (const std::size_t count :
       {stats.inputVertices, stats.inputTriangles, stats.holesFilled, stats.componentsKept,
        stats.boundedVertices, stats.hullVertices, stats.totalVertices, stats.splits, stats.merges,
        stats.refinements}) {
    out.putCount(count);
  }
  for (const double value : {stats.epsilon, stats.diagonal, stats.estimatedError, stats.seconds}) {
    out.put(value);
  }
  out.putText(stats.stopReason);
  return out.bytes();
}

DecompositionStats decodeStats(ByteReader& in) {
  DecompositionStats stats;
  for (std::size_t* count :
       {&stats.inputVertices, &stats.inputTriangles, &stats.holesFilled, &stats.componentsKept,
        &stats.boundedVertices, &stats.hullVertices, &stats.totalVertices, &stats.splits,
        &stats.merges, &stats.refinements}) {
    *count = static_cast<std::size_t>(in.get<std::uint64_t>());
  }
  for (double* value : {&stats.epsilon, &stats.diagonal, &stats.estimatedError, &stats.seconds}) {
    *value = in.get<double>();
  }
  stats.stopReason = in.getText();
  return stats;
}

std::string encodePayload(const Decomposition& decomposition) {
  ByteWriter out;
  out.append(encodeStats(decomposition.stats));
  out.putCount(decomposition.pieces.size());
  for (const ConvexPiece& piece : decomposition.pieces) {
    out.putMesh(piece.mesh);
    out.putCount(piece.planes.size());
    for (const HullPlane& plane : piece.planes) {
      out.putVec3(plane.normal);
      out.put(plane.offset);
    }
  }
  out.putMesh(decomposition.closedInput);
  return out.bytes();
}

std::optional<Decomposition> decodePayload(std::string_view payload) {
  ByteReader in(payload);
  Decomposition decomposition;
  decomposition.stats = decodeStats(in);
  // A piece takes at least its four counts.
  decomposition.pieces.resize(in.getCount(4 * sizeof(std::uint64_t)));
  for (ConvexPiece& piece : decomposition.pieces) {
    piece.mesh = in.getMesh();
    piece.planes.resize(in.getCount(4 * sizeof(double)));
    for (HullPlane& plane : piece.planes) {
      plane.normal = in.getVec3();
      plane.offset = in.get<double>();
    }
  }
  decomposition.closedInput = in.getMesh();
  if (!in.ok() || !in.atEnd()) return std::nullopt;
  return decomposition;
}

std::string encodeEntry(const Digest& key, const Decomposition& decomposition) {
  const std::string payload = encodePayload(decomposition);
  ByteWriter out;
  out.append(kMagic);
  out.put(kDecompositionCacheVersion);
  out.put(key);
  out.putCount(payload.size());
  out.append(payload);
  out.put(murmurHash3(payload)[0]);
  return out.bytes();
}

// The decomposition in `entry`, or what is wrong with it.
struct DecodedEntry {
  std::optional<Decomposition> decomposition;
  std::string problem;
};

DecodedEntry decodeEntry(std::string_view entry, const Digest& key) {
  if (entry.size() < kHeaderBytes + kChecksumBytes) return {std::nullopt, "truncated"};
  if (entry.substr(0, kMagic.size()) != kMagic) return {std::nullopt, "bad magic"};
  ByteReader header(entry.substr(kMagic.size(), kHeaderBytes - kMagic.size()));
  const auto version = header.get<std::uint32_t>();
  const auto storedKey = header.get<Digest>();
  const auto payloadSize = header.get<std::uint64_t>();
  if (version != kDecompositionCacheVersion) {
    return {std::nullopt, "format version " + std::to_string(version) + " instead of " +
                              std::to_string(kDecompositionCacheVersion)};
  }
  if (storedKey != key) return {std::nullopt, "key does not match its file name"};
  if (payloadSize != entry.size() - kHeaderBytes - kChecksumBytes) {
    return {std::nullopt, "truncated or too long"};
  }
  const std::string_view payload = entry.substr(kHeaderBytes, payloadSize);
  ByteReader trailer(entry.substr(kHeaderBytes + payloadSize));
  if (trailer.get<std::uint64_t>() != murmurHash3(payload)[0]) {
    return {std::nullopt, "checksum mismatch"};
  }
  std::optional<Decomposition> decomposition = decodePayload(payload);
  if (!decomposition) return {std::nullopt, "malformed payload"};
  return {std::move(decomposition), {}};
}

std::string hex(const Digest& digest) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text;
  for (const std::uint64_t word : digest) {
    for (int shift = 60; shift >= 0; shift -= 4) text += kDigits[(word >> shift) & 0xf];
  }
  return text;
}

std::optional<std::string> readWhole(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Writes `bytes` to a unique temporary file in the entry's directory and renames it to `path`
// (atomic: readers see the old file or the whole new one). Returns the error, if any.
std::optional<std::string> writeAtomically(const std::filesystem::path& path,
                                           const std::string& bytes) {
  std::string temporary = (path.parent_path() / (".entry-XXXXXX")).string();
  const int fd = ::mkstemp(temporary.data());
  if (fd < 0) return std::string(std::strerror(errno));
  ::fchmod(fd, 0644);  // mkstemp makes it private; entries are shared like any cache file
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    written += static_cast<std::size_t>(n);
  }
  const int writeError = written == bytes.size() ? 0 : errno;
  if (::close(fd) != 0 || writeError != 0 || ::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string error = std::strerror(writeError != 0 ? writeError : errno);
    ::unlink(temporary.c_str());
    return error;
  }
  return std::nullopt;
}

}  // namespace

DecompositionCache::DecompositionCache(std::filesystem::path directory)
    : directory_(std::move(directory)) {
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  if (!error && !std::filesystem::is_directory(directory_, error)) {
    error = std::make_error_code(std::errc::not_a_directory);
  }
  if (error) {
    throw InputError(
        locate(directory_.string(), "cannot create the cache directory: " + error.message()));
  }
}

std::filesystem::path DecompositionCache::entryPath(const TriangleMesh& mesh,
                                                    const DecompositionOptions& options) const {
  return directory_ / (hex(entryKey(mesh, options)) + std::string(kEntrySuffix));
}

Decomposition DecompositionCache::decompose(const TriangleMesh& mesh,
                                            const DecompositionOptions& options,
                                            WorkerPool* workers) {
  const Digest key = entryKey(mesh, options);
  const std::filesystem::path path = directory_ / (hex(key) + std::string(kEntrySuffix));
  std::string problem;
  if (const std::optional<std::string> entry = readWhole(path)) {
    DecodedEntry decoded = decodeEntry(*entry, key);
    if (decoded.decomposition) {
      const std::lock_guard lock(mutex_);
      ++report_.hits;
      return std::move(*decoded.decomposition);
    }
    problem = std::move(decoded.problem);
  }
  Decomposition decomposition =
      workers ? decomposeBounding(mesh, options, *workers) : decomposeBounding(mesh, options);
  const std::optional<std::string> writeError =
      writeAtomically(path, encodeEntry(key, decomposition));
  const std::lock_guard lock(mutex_);
  if (problem.empty()) {
    ++report_.misses;
  } else {
    ++report_.rebuilt;
    report_.warnings.push_back(
        locate(path.string(), "corrupt decomposition cache entry (" + problem + "), rebuilt"));
  }
  if (writeError) {
    report_.warnings.push_back(
        locate(path.string(), "cannot write the decomposition cache entry: " + *writeError));
  }
  return decomposition;
}

DecompositionCacheReport DecompositionCache::report() const {
  const std::lock_guard lock(mutex_);
  return report_;
}

}  // namespace kaboum::io

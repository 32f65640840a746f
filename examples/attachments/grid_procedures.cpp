// Semantic attachments for grid-domain.pddl, built as a shared library that `kaboum plan` loads
// with dlopen (`name@libgrid_procedures.so`). Each procedure has kaboum's C ABI:
//   int proc(const char* const* args, size_t argCount, const double* reads, size_t readCount,
//            double* writes, size_t writeCount)   -> nonzero for true / success.
#include <cstddef>
#include <cstring>

namespace {

// 8x8 occupancy map, row y = 0 at the top; '#' is a wall, 'k' the key.
constexpr const char* kMap[8] = {
    "..#.....",  //
    "..#.##..",  //
    "..#..#..",  //
    "..##.#..",  //
    ".....#..",  //
    ".###.#..",  //
    "...#....",  //
    "k..#....",  //
};

bool freeCell(long x, long y) {
  return x >= 0 && y >= 0 && x < 8 && y < 8 && kMap[y][x] != '#';
}

// Target cell of a step from (x, y) in the named direction.
void target(const char* direction, long& x, long& y) {
  if (std::strcmp(direction, "north") == 0) --y;
  if (std::strcmp(direction, "south") == 0) ++y;
  if (std::strcmp(direction, "east") == 0) ++x;
  if (std::strcmp(direction, "west") == 0) --x;
}

}  // namespace

extern "C" int canMove(const char* const* args, std::size_t, const double* reads, std::size_t,
                       double*, std::size_t) {
  long x = static_cast<long>(reads[0]);
  long y = static_cast<long>(reads[1]);
  target(args[0], x, y);
  return freeCell(x, y) ? 1 : 0;
}

extern "C" int applyMove(const char* const* args, std::size_t, const double* reads, std::size_t,
                         double* writes, std::size_t) {
  long x = static_cast<long>(reads[0]);
  long y = static_cast<long>(reads[1]);
  target(args[0], x, y);
  if (!freeCell(x, y)) return 0;
  writes[0] = static_cast<double>(x);
  writes[1] = static_cast<double>(y);
  return 1;
}

extern "C" int atKey(const char* const*, std::size_t, const double* reads, std::size_t, double*,
                     std::size_t) {
  const long x = static_cast<long>(reads[0]);
  const long y = static_cast<long>(reads[1]);
  return freeCell(x, y) && kMap[y][x] == 'k' ? 1 : 0;
}

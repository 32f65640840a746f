// `kaboum-compare`: kaboum's collision engine side by side with the reference libraries (FCL,
// Bullet, libccd) on identical queries. A benchmark program, not part of the shipped tool.
#include "verb.hpp"

int main(int argc, char** argv) {
  return kaboum::cli::runVerbs(
      argc, argv, "kaboum-compare",
      "kaboum-compare: kaboum's collision queries against FCL, Bullet and libccd.");
}

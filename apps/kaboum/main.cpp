// The `kaboum` command-line tool: one verb per verb_*.cpp, registered at start-up.
#include "verb.hpp"

int main(int argc, char** argv) {
  return kaboum::cli::runVerbs(
      argc, argv, "kaboum",
      "kaboum: knowledge-level task and motion planning with bounding geometry.");
}

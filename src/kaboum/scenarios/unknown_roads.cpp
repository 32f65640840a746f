#include "kaboum/scenarios/unknown_roads.hpp"

#include "kaboum/core/error.hpp"

namespace kaboum::scenarios {

std::string unknownRoadsDomain() {
  return R"((define (domain unknown-roads)
  (:requirements :strips :typing)
  (:types place road)
  (:predicates (at ?p - place) (connects ?r - road ?from ?to - place) (clear ?r - road))
  (:action sense-road
    :parameters (?r - road ?from ?to - place)
    :precondition (and (at ?from) (connects ?r ?from ?to))
    :observe (clear ?r))
  (:action drive
    :parameters (?r - road ?from ?to - place)
    :precondition (and (at ?from) (connects ?r ?from ?to) (clear ?r))
    :effect (and (not (at ?from)) (at ?to))))
)";
}

std::string unknownRoadsProblem(int n) {
  if (n < 1) throw InputError("unknown roads: n must be at least 1, got " + std::to_string(n));
  std::string places = "l0";
  std::string roads;
  std::string init = "    (at l0)\n";
  for (int i = 1; i <= n; ++i) {
    const std::string leg = std::to_string(i);
    const std::string from = "l" + std::to_string(i - 1);
    places += " l" + leg + " s" + leg;
    roads += " r" + leg + " a" + leg + " b" + leg;
    init += "    (connects r" + leg + " " + from + " l" + leg + ") (unknown (clear r" + leg +
            "))\n    (connects a" + leg + " " + from + " s" + leg + ") (clear a" + leg +
            ")\n    (connects b" + leg + " s" + leg + " l" + leg + ") (clear b" + leg + ")\n";
  }
  return "(define (problem unknown-roads-" + std::to_string(n) +
         ")\n  (:domain unknown-roads)\n  (:objects " + places + " - place\n   " + roads +
         " - road)\n  (:init\n" + init + "  )\n  (:goal (at l" + std::to_string(n) + ")))\n";
}

}  // namespace kaboum::scenarios

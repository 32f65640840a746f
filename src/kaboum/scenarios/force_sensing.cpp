#include "kaboum/scenarios/force_sensing.hpp"

#include "kaboum/core/error.hpp"

namespace kaboum::scenarios {

std::string forceSensingDomain() {
  // Table 3.1. K(φ) is written φ, K(¬φ) as (not φ), Kw(φ) as (kw φ); add(Kw, φ) is the effect
  // (kw φ). The optional ¬Kw(isSpillable) and isRemoved preconditions of the thesis are kept.
  return R"((define (domain force-sensing)
  (:requirements :strips :typing :negative-preconditions)
  (:types container)
  (:predicates (isgrasped ?o - container) (isspillable ?o - container)
               (isremoved ?o - container) (emptygripper))
  (:action senseweight
    :parameters (?o - container)
    :precondition (and (isgrasped ?o) (not (kw (isspillable ?o))))
    :effect (kw (isspillable ?o)))
  (:action transferfast
    :parameters (?o - container)
    :precondition (and (isgrasped ?o) (not (isspillable ?o)) (not (isremoved ?o)))
    :effect (isremoved ?o))
  (:action transferupright
    :parameters (?o - container)
    :precondition (and (isgrasped ?o) (isspillable ?o) (not (isremoved ?o)))
    :effect (isremoved ?o))
  (:action grasp
    :parameters (?o - container)
    :precondition (and (emptygripper) (not (isremoved ?o)))
    :effect (and (isgrasped ?o) (not (emptygripper))))
  (:action ungrasp
    :parameters (?o - container)
    :precondition (and (isgrasped ?o) (isremoved ?o))
    :effect (and (not (isgrasped ?o)) (emptygripper))))
)";
}

std::string forceSensingProblem(int n) {
  if (n < 1) throw InputError("force sensing: n must be at least 1, got " + std::to_string(n));
  std::string objects;
  std::string unknown;
  std::string goal;
  for (int i = 1; i <= n; ++i) {
    const std::string o = "o" + std::to_string(i);
    objects += o + " ";
    unknown += "    (unknown (isspillable " + o + "))\n";
    goal += " (isremoved " + o + ")";
  }
  return "(define (problem force-sensing-" + std::to_string(n) +
         ")\n  (:domain force-sensing)\n  (:objects " + objects +
         "- container)\n  (:init\n    (emptygripper)\n" + unknown +
         "  )\n  (:goal (and (emptygripper)" + goal + ")))\n";
}

}  // namespace kaboum::scenarios

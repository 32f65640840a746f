// What the PDDL fuzz target does with one input, shared with the corpus regression test: parse it
// as a domain, as a problem and as a plan of a fixed blocks task. Only InputError may escape.
#pragma once

#include <string_view>

#include "kaboum/core/error.hpp"
#include "kaboum/symbolic/pddl.hpp"
#include "kaboum/symbolic/task.hpp"
#include "kaboum/symbolic/validator.hpp"

namespace kaboum::symbolic::fuzz {

inline const char* kBlocksDomain = R"((define (domain blocks)
  (:requirements :strips :typing :equality :object-fluents :numeric-fluents)
  (:types block)
  (:predicates (on ?x ?y - block) (clear ?x - block) (holding ?x - block))
  (:functions (below ?x - block) - block (weight ?x - block))
  (:action take :parameters (?x ?y - block)
    :precondition (and (on ?x ?y) (clear ?x) (not (= ?x ?y)) (< (weight ?x) 3))
    :effect (and (holding ?x) (not (on ?x ?y)) (assign (below ?x) ?x)))))";

inline const char* kBlocksProblem = R"((define (problem p) (:domain blocks)
  (:objects a b c - block) (:init (on a b) (clear a) (= (weight a) 1))
  (:goal (holding a))))";

inline void parseAnyInput(std::string_view input) {
  try {
    const Domain domain = parseDomain(input, "fuzz.pddl");
    (void)domain;
  } catch (const InputError&) {
  }
  static const Domain blocks = parseDomain(kBlocksDomain, "blocks.pddl");
  static const Problem problem = parseProblem(kBlocksProblem, "p.pddl", blocks);
  try {
    const Problem parsed = parseProblem(input, "fuzz.pddl", blocks);
    // Small problems are also grounded (grounding is polynomial in the object count).
    if (parsed.objectNames.size() <= 8) ground(blocks, parsed);
  } catch (const InputError&) {
  }
  try {
    const std::vector<PlanStep> steps = parsePlan(input, "fuzz.plan", blocks, problem);
    AttachmentRuntime attachments(blocks, problem, ProcedureRegistry{});
    validatePlan(blocks, problem, steps, attachments);
  } catch (const InputError&) {
  }
}

}  // namespace kaboum::symbolic::fuzz

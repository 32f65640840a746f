#include "kaboum/scenarios/stacked_objects.hpp"

#include "kaboum/core/error.hpp"

namespace kaboum::scenarios {

std::string stackedObjectsDomain() {
  // Table 6.3, with one addition: moving an object onto the object it already stands on is
  // excluded (the thesis's effects would otherwise mark that object as highest).
  return R"((define (domain stacked-objects)
  (:requirements :typing :negative-preconditions :equality :conditional-effects
                 :universal-preconditions :object-fluents)
  (:types object)
  (:predicates (isastack ?o - object) (ishighest ?o - object))
  (:functions (getonebelow ?o - object) - object)
  (:action move
    :parameters (?this - object ?other - object)
    :precondition (and (ishighest ?this) (ishighest ?other) (not (isastack ?this))
                       (not (= ?this ?other)) (not (= (getonebelow ?this) ?other)))
    :effect (and (not (ishighest ?other))
                 (forall (?o - object) (when (= (getonebelow ?this) ?o) (ishighest ?o)))
                 (assign (getonebelow ?this) ?other))))
)";
}

std::string stackedObjectsProblem(int n) {
  if (n < 2) throw InputError("stacked objects: n must be at least 2, got " + std::to_string(n));
  const auto o = [](int i) { return "o" + std::to_string(i); };
  std::string objects;
  for (int i = 1; i <= n; ++i) objects += o(i) + " ";
  std::string init = "    (isastack stack1) (isastack stack2) (isastack stack3)\n";
  init += "    (ishighest " + o(n) + ") (ishighest o1) (ishighest stack3)\n";
  init += "    (= (getonebelow o2) stack1) (= (getonebelow o1) stack2)\n";
  std::string goal = "(= (getonebelow o1) stack1)";
  for (int i = 3; i <= n; ++i) init += "    (= (getonebelow " + o(i) + ") " + o(i - 1) + ")\n";
  for (int i = 2; i <= n; ++i) goal += " (= (getonebelow " + o(i) + ") " + o(i - 1) + ")";
  return "(define (problem stacked-" + std::to_string(n) + ")\n  (:domain stacked-objects)\n" +
         "  (:objects " + objects + "stack1 stack2 stack3 - object)\n  (:init\n" + init +
         "  )\n  (:goal (and " + goal + ")))\n";
}

}  // namespace kaboum::scenarios

#include "kaboum/scenarios/bartender.hpp"

#include "kaboum/core/error.hpp"

namespace kaboum::scenarios {

std::string bartenderDomain() {
  return R"(; Bartender, symbolic part (thesis §6.2.1, Table 6.1): two robots move bottles; only empty bottles
; go to the dishwasher; senseIfEmpty adds Kw(isEmptyBottle o). Geometry is stubbed by the toy
; attachment `reaches` (which locations a robot's workspace covers); pickUp and putDown name the
; location so the stub can decide reachability.
(define (domain bartender)
  (:requirements :strips :typing :negative-preconditions :semantic-attachments)
  (:types object robot location)
  (:predicates (isgrasped ?o - object) (isrobotgrasps ?r - robot ?o - object)
               (ishandempty ?r - robot) (isatlocation ?o - object ?l - location)
               (isemptybottle ?o - object))
  (:modules (reaches ?r - robot ?l - location conditionchecker reaches))
  (:action move
    :parameters (?r - robot))
  (:action pickup
    :parameters (?r - robot ?o - object ?l - location)
    :precondition (and (ishandempty ?r) (not (isgrasped ?o)) (isatlocation ?o ?l) [reaches ?r ?l])
    :effect (and (not (ishandempty ?r)) (isgrasped ?o) (isrobotgrasps ?r ?o)
                 (not (isatlocation ?o ?l))))
  (:action putdown
    :parameters (?r - robot ?o - object ?l - location)
    :precondition (and (isrobotgrasps ?r ?o) (isgrasped ?o) [reaches ?r ?l])
    :effect (and (ishandempty ?r) (not (isgrasped ?o)) (isatlocation ?o ?l)
                 (not (isrobotgrasps ?r ?o))))
  (:action senseifempty
    :parameters (?o - object)
    :observe (isemptybottle ?o)))
)";
}

std::string bartenderProblem(int n) {
  if (n < 1) throw InputError("bartender: n must be at least 1, got " + std::to_string(n));
  std::string bottles;
  std::string init = "    (ishandempty robot1) (ishandempty robot2)\n";
  for (int i = 1; i <= n; ++i) {
    const std::string bottle = "o" + std::to_string(i);
    bottles += " " + bottle;
    init += "    (isatlocation " + bottle + (i % 2 == 1 ? " left" : " right") +
            ") (unknown (isemptybottle " + bottle + "))\n";
  }
  return "; Bartender with " + std::to_string(n) +
         " bottles (kaboum bartender N): odd bottles stand where only robot1 reaches, even\n"
         "; ones where only robot2 reaches; whether each bottle is empty is unknown. Goal of "
         "Table 6.1:\n; forall o: (K(isAtLocation(o, dishwasher)) ∧ K(¬isGrasped(o))) ⊕ "
         "K(¬isEmptyBottle(o)).\n(define (problem bartender-" +
         std::to_string(n) + ")\n  (:domain bartender)\n  (:objects" + bottles +
         " - object robot1 robot2 - robot left right any dishwasher - location)\n  (:init\n" +
         init +
         "  )\n  (:goal (forall (?o - object)\n"
         "           (or (and (isatlocation ?o dishwasher) (not (isgrasped ?o)) (isemptybottle "
         "?o))\n"
         "               (and (not (isemptybottle ?o))\n"
         "                    (or (not (isatlocation ?o dishwasher)) (isgrasped ?o)))))))\n";
}

}  // namespace kaboum::scenarios

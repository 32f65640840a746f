; A domain whose only geometric effect is written in Python (tests/python/test_geometric_effects.py):
; reach moves the robot to a configuration that pyReach finds, writing the geometric state fluent.
(define (domain reach)
  (:requirements :strips :typing :negative-preconditions :numeric-fluents :semantic-attachments)
  (:types robot)
  (:predicates (reached ?r - robot))
  (:functions (geometry))
  (:modules (arrive ?r - robot (geometry) effect pyReach :reads ((geometry))))
  (:action reach
    :parameters (?r - robot)
    :precondition (not (reached ?r))
    :effect (and (reached ?r) [arrive ?r])))

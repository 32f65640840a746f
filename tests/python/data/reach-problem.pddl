; The robot of examples/pick-and-place reaches a point above the table (reach-domain.pddl).
(define (problem reach-above-table)
  (:domain reach)
  (:objects kr5 - robot)
  (:init (= (geometry) 0))
  (:goal (reached kr5)))

; examples/pick-and-place/problem.pddl with the fluent (picks) of guarded-domain.pddl.
(define (problem move-block)
  (:domain pick-and-place)
  (:objects kr5 - robot block - object left right - location)
  (:init (handempty kr5) (at block left) (= (geometry) 0) (= (picks) 0))
  (:goal (and (at block right) (handempty kr5))))

; examples/python/guarded-problem.pddl with a goal no plan reaches (the hand both holds the block
; and is empty) in a state space without end (every pick counts into (picks)): only a limit or a
; cancel ends its search.
(define (problem hold-and-release)
  (:domain pick-and-place)
  (:objects kr5 - robot block - object left right - location)
  (:init (handempty kr5) (at block left) (= (geometry) 0) (= (picks) 0))
  (:goal (and (holding kr5 block) (handempty kr5))))

; Bimanual Circular Rearrange with 3 bottles (thesis Table 6.1): bottle oi stands at loci; the goal
; moves each to the next location, the last to loc1. Written by `kaboum circular-rearrange 3`.
(define (problem circular-rearrange-3)
  (:domain circular-rearrange)
  (:objects o1 o2 o3 - bottle robot1 robot2 - robot any loc1 loc2 loc3 - location)
  (:init (ishandempty robot1) (ishandempty robot2)
         (isatlocation o1 loc1)
         (isatlocation o2 loc2)
         (isatlocation o3 loc3)
         (= (geometry) 0))
  (:goal (and (isatlocation o1 loc2) (isatlocation o2 loc3) (isatlocation o3 loc1))))

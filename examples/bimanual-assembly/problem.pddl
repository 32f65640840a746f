; The Bimanual Assembly problem (thesis Table 6.5): two bearings, a pipe and a tree on the table,
; both hands empty; the goal, some part is a gearbox and not grasped (assemblePipeTree leaves it
; standing on the table).
(define (problem bimanual-assembly)
  (:domain bimanual-assembly)
  (:objects comau-left comau-right - robot bearing1 bearing2 pipe tree - part table - location)
  (:init (isabearing bearing1) (isabearing bearing2) (isapipe pipe) (isatree tree)
         (ishandempty comau-left) (ishandempty comau-right) (= (geometry) 0))
  (:goal (exists (?o - part) (and (isagearbox ?o) (not (isgrasped ?o))))))

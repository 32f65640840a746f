; Table 6.5's instance with the minimum set of objects: bearings o1 and o2, pipe o3, tree o4.
(define (problem bimanual-assembly)
  (:domain bimanual-assembly)
  (:objects o1 o2 o3 o4 - object robot1 robot2 - robot)
  (:init (isabearing o1) (isabearing o2) (isapipe o3) (isatree o4)
         (ishandempty robot1) (ishandempty robot2))
  (:goal (exists (?o - object) (and (isagearbox ?o) (not (isgrasped ?o))))))

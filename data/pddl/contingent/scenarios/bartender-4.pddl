; Figure 6.2's instance: four bottles; o1 and o3 stand where only robot1 reaches, o2 and o4 where
; only robot2 reaches; whether each bottle is empty is unknown (open world). Goal of Table 6.1:
; forall o: (K(isAtLocation(o, dishwasher)) ∧ K(¬isGrasped(o))) ⊕ K(¬isEmptyBottle(o)).
(define (problem bartender-4)
  (:domain bartender)
  (:objects o1 o2 o3 o4 - object robot1 robot2 - robot left right any dishwasher - location)
  (:init (ishandempty robot1) (ishandempty robot2)
         (isatlocation o1 left) (isatlocation o3 left)
         (isatlocation o2 right) (isatlocation o4 right)
         (unknown (isemptybottle o1)) (unknown (isemptybottle o2))
         (unknown (isemptybottle o3)) (unknown (isemptybottle o4)))
  (:goal (forall (?o - object)
           (or (and (isatlocation ?o dishwasher) (not (isgrasped ?o)) (isemptybottle ?o))
               (and (not (isemptybottle ?o))
                    (or (not (isatlocation ?o dishwasher)) (isgrasped ?o)))))))

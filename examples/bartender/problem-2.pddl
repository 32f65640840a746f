; Two bottles of unknown content: o1 on robot1's side, o2 on robot2's side. Goal of Table 6.1:
; every empty bottle in the dishwasher and not grasped; full bottles anywhere but the dishwasher.
(define (problem bartender-2)
  (:domain bartender)
  (:objects o1 o2 - bottle robot1 robot2 - robot left shared right dishwasher - location)
  (:init (ishandempty robot1) (ishandempty robot2)
         (isatlocation o1 left) (isatlocation o2 right)
         (unknown (isemptybottle o1)) (unknown (isemptybottle o2))
         (= (geometry) 0))
  (:goal (forall (?o - bottle)
           (or (and (isatlocation ?o dishwasher) (not (isgrasped ?o)) (isemptybottle ?o))
               (and (not (isemptybottle ?o))
                    (or (not (isatlocation ?o dishwasher)) (isgrasped ?o)))))))

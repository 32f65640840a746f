; Two bottles of unknown content, o1 on robot1's side and o2 on robot2's.
; Goal of Table 6.1 for each bottle: if it is empty, it is in the dishwasher and not grasped.
(define (problem bartender-2)
  (:domain bartender)
  (:objects o1 o2 - bottle robot1 robot2 - robot left shared right dishwasher - location)
  (:init (ishandempty robot1) (ishandempty robot2)
         (isatlocation o1 left) (unknown (isemptybottle o1))
         (isatlocation o2 right) (unknown (isemptybottle o2))
         (= (geometry) 0))
  (:goal (and (or (and (isatlocation o1 dishwasher) (not (isgrasped o1)) (isemptybottle o1))
                 (and (not (isemptybottle o1)) (or (not (isatlocation o1 dishwasher)) (isgrasped o1))))
             (or (and (isatlocation o2 dishwasher) (not (isgrasped o2)) (isemptybottle o2))
                 (and (not (isemptybottle o2)) (or (not (isatlocation o2 dishwasher)) (isgrasped o2)))))))

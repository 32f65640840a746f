; One bottle of unknown content on robot1's side (o1); the other bottles stand where they are.
; Goal of Table 6.1: if o1 is empty, it is in the dishwasher (only robot2 reaches it, so robot1
; hands it over through the shared middle of the table), and not grasped.
(define (problem bartender-1)
  (:domain bartender)
  (:objects o1 - bottle robot1 robot2 - robot left shared right dishwasher - location)
  (:init (ishandempty robot1) (ishandempty robot2) (isatlocation o1 left)
         (unknown (isemptybottle o1))
         (= (geometry) 0))
  (:goal (or (and (isatlocation o1 dishwasher) (not (isgrasped o1)) (isemptybottle o1))
             (and (not (isemptybottle o1))
                  (or (not (isatlocation o1 dishwasher)) (isgrasped o1))))))

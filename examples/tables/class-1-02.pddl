; Seed 004 Table I, Class I, a simple pick and place: a cereal box from the left table to the right one.
(define (problem tables-class-1-02)
  (:domain tables)
  (:objects mobile - robot bottle1 bottle2 bottle3 cereal1 cereal2 cereal3 - item
            left-1 left-2 left-3 front-1 front-2 front-3 right-1 right-2 right-3 - place)
  (:init (handempty mobile) (= (geometry) 0)
         (at bottle1 left-1) (at cereal1 left-2) (at bottle2 front-1) (at cereal2 front-3)
         (at cereal3 right-1) (at bottle3 right-2))
  (:goal (and (at cereal1 right-3) [inside cereal1 right-3]
              (handempty mobile))))

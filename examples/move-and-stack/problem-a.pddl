; Seed 003 Table I, variant A: K(isInside(bB, depot)) ∧ K(¬isInside(gB, tray)), and the hand empty.
(define (problem move-and-stack-a)
  (:domain move-and-stack)
  (:objects kr5 - robot bluebottle greenbottle turquoisebottle can - item
            tray depot counter - location)
  (:init (handempty kr5) (at greenbottle tray) (at bluebottle counter)
         (at turquoisebottle counter) (at can counter) (= (geometry) 0))
  (:goal (and (at bluebottle depot) [inside bluebottle depot]
              (not (at greenbottle tray)) (not [inside greenbottle tray])
              (handempty kr5))))

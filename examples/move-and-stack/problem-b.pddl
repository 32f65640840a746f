; Seed 003 Table I, variant B: K(isInside(bB, depot)) ∧ K(isInside(tB, tray)) ∧ K(¬isInside(gB, tray)), and the hand empty.
(define (problem move-and-stack-b)
  (:domain move-and-stack)
  (:objects kr5 - robot bluebottle greenbottle turquoisebottle can - item
            tray depot counter - location)
  (:init (handempty kr5) (at greenbottle tray) (at bluebottle counter)
         (at turquoisebottle counter) (at can counter) (= (geometry) 0))
  (:goal (and (at bluebottle depot) [inside bluebottle depot]
              (at turquoisebottle tray) [inside turquoisebottle tray]
              (not (at greenbottle tray)) (not [inside greenbottle tray])
              (handempty kr5))))

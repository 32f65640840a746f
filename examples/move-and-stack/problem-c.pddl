; Seed 003 Table I, variant C: K(isInside(tB, tray)) ∧ K(isInside(can, tray)), and the hand empty.
(define (problem move-and-stack-c)
  (:domain move-and-stack)
  (:objects kr5 - robot bluebottle greenbottle turquoisebottle can - item
            tray depot counter - location)
  (:init (handempty kr5) (at greenbottle tray) (at bluebottle counter)
         (at turquoisebottle counter) (at can counter) (= (geometry) 0))
  (:goal (and (at turquoisebottle tray) [inside turquoisebottle tray]
              (at can tray) [inside can tray]
              (handempty kr5))))

; Seed 003 Table I, the full scenario: K(isInside(bB, tray)) ∧ K(isInside(tB, tray)) ∧ K(isInside(can, tray)), and the hand empty.
(define (problem move-and-stack-full)
  (:domain move-and-stack)
  (:objects kr5 - robot bluebottle greenbottle turquoisebottle can - item
            tray depot counter - location)
  (:init (handempty kr5) (at greenbottle tray) (at bluebottle counter)
         (at turquoisebottle counter) (at can counter) (= (geometry) 0))
  (:goal (and (at bluebottle tray) [inside bluebottle tray]
              (at turquoisebottle tray) [inside turquoisebottle tray]
              (at can tray) [inside can tray]
              (handempty kr5))))

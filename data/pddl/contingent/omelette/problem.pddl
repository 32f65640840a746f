; Written for kaboum's tests: three eggs into bowl2 with the published domain beside it. An egg
; broken into a bowl may spoil it (nondet), so the plan breaks each egg into bowl1 and pours it
; over; pouring cleans the bowl poured from.
(define (problem omelette-3)
  (:domain omlette)
  (:objects bowl1 bowl2 n0 n1 n2 n3)
  (:init (bowl bowl1) (bowl bowl2) (no n0) (no n1) (no n2) (no n3)
         (add-one n0 n1) (add-one n1 n2) (add-one n2 n3)
         (sum n1 n0 n1) (sum n1 n1 n2) (sum n1 n2 n3)
         (has bowl1 n0) (has bowl2 n0) (unspoiled bowl1) (unspoiled bowl2))
  (:goal (and (has bowl2 n3) (unspoiled bowl2))))

; Written for kaboum's tests: one egg in the only bowl. Breaking it in loses the knowledge that the
; bowl is unspoiled, and nothing senses it: no plan exists.
(define (problem omelette-one-bowl)
  (:domain omlette)
  (:objects bowl1 n0 n1)
  (:init (bowl bowl1) (no n0) (no n1) (add-one n0 n1) (has bowl1 n0) (unspoiled bowl1))
  (:goal (and (has bowl1 n1) (unspoiled bowl1))))

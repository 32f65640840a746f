; The counter from 0 until `finished` holds: the search runs until its node limit.
(define (problem count)
  (:domain counter)
  (:init (= (n) 0))
  (:goal (done)))

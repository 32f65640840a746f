(define (problem fetch-key-then-exit)
  (:domain grid-attachments)
  (:init (= (x) 0) (= (y) 0))
  (:goal (and (has-key) (= (x) 7) (= (y) 0))))

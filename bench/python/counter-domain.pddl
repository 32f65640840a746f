; The Python attachment benchmark's domain (bench/python/attachment_overhead.py): one action whose
; precondition is a Python condition checker and whose effect is a Python effect applicator on the
; counter (n), and one that ends the count when the checker `finished` says so. Each expansion
; calls each procedure once with a new value of (n), so no call is answered from the memo.
(define (domain counter)
  (:requirements :strips :numeric-fluents :semantic-attachments)
  (:predicates (done))
  (:functions (n))
  (:modules
    (allowed conditionchecker allow :reads ((n)))
    (increment (n) effect next :reads ((n)))
    (finished conditionchecker atEnd :reads ((n))))
  (:action step
    :parameters ()
    :precondition [allowed]
    :effect [increment])
  (:action finish
    :parameters ()
    :precondition [finished]
    :effect (done)))

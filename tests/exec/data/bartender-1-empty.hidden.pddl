; A true initial state of examples/bartender/problem-1.pddl: bottle o1 is empty.
(define (problem bartender-1-empty) (:hidden (isemptybottle o1)))

; A true initial state of examples/bartender/problem-1.pddl: bottle o1 is full.
(define (problem bartender-1-full) (:hidden))

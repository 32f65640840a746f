; Grid world whose geometry lives in C++ (semantic attachments, PDDL/M modules): the robot's
; position is the numeric fluents (x) and (y); whether a step is free and where it leads are
; computed by procedures in libgrid_procedures.so (see grid_procedures.cpp and README.md).
(define (domain grid-attachments)
  (:requirements :typing :negative-preconditions :numeric-fluents)
  (:types direction)
  (:constants north south east west - direction)
  (:predicates (has-key))
  (:functions (x) (y))
  (:modules
    (free ?d - direction conditionchecker canMove@libgrid_procedures.so :reads ((x) (y)))
    (step ?d - direction (x) (y) effect applyMove@libgrid_procedures.so :reads ((x) (y)))
    (at-key conditionchecker atKey@libgrid_procedures.so :reads ((x) (y))))
  (:action move
    :parameters (?d - direction)
    :precondition [free ?d]
    :effect [step ?d])
  (:action pick-key
    :parameters ()
    :precondition (and (not (has-key)) [at-key])
    :effect (has-key)))

; examples/pick-and-place/domain.pddl with the pick written in Python (python_pick.py,
; docs/python.md): the geometric effect pyPick plans the motions to the grasp, records them and
; returns the state it reaches; putdown stays the C++ attachment putDown.
(define (domain pick-and-place)
  (:requirements :strips :typing :negative-preconditions :numeric-fluents :semantic-attachments)
  (:types robot object location)
  (:predicates (handempty ?r - robot) (holding ?r - robot ?o - object)
               (at ?o - object ?l - location))
  (:functions (geometry))
  (:modules
    (grasp ?r - robot ?o - object (geometry) effect pyPick :reads ((geometry)))
    (place ?r - robot ?o - object ?l - location (geometry) effect putDown :reads ((geometry))))
  (:action pickup
    :parameters (?r - robot ?o - object ?l - location)
    :precondition (and (handempty ?r) (at ?o ?l))
    :effect (and (not (handempty ?r)) (holding ?r ?o) (not (at ?o ?l)) [grasp ?r ?o]))
  (:action putdown
    :parameters (?r - robot ?o - object ?l - location)
    :precondition (holding ?r ?o)
    :effect (and (handempty ?r) (not (holding ?r ?o)) (at ?o ?l) [place ?r ?o ?l])))

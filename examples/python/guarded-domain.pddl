; examples/pick-and-place/domain.pddl with two procedures written in Python (docs/python.md): the
; condition checker mayPick guards pickup, and the effect applicator countPicks counts picks into
; the numeric fluent (picks).
(define (domain pick-and-place)
  (:requirements :strips :typing :negative-preconditions :numeric-fluents :semantic-attachments)
  (:types robot object location)
  (:predicates (handempty ?r - robot) (holding ?r - robot ?o - object)
               (at ?o - object ?l - location))
  (:functions (geometry) (picks))
  (:modules
    (grasp ?r - robot ?o - object (geometry) effect pickUp :reads ((geometry)))
    (place ?r - robot ?o - object ?l - location (geometry) effect putDown :reads ((geometry)))
    (allowed ?r - robot ?o - object conditionchecker mayPick :reads ((geometry)))
    (count ?r - robot (picks) effect countPicks :reads ((picks))))
  (:action pickup
    :parameters (?r - robot ?o - object ?l - location)
    :precondition (and (handempty ?r) (at ?o ?l) [allowed ?r ?o])
    :effect (and (not (handempty ?r)) (holding ?r ?o) (not (at ?o ?l)) [grasp ?r ?o] [count ?r]))
  (:action putdown
    :parameters (?r - robot ?o - object ?l - location)
    :precondition (holding ?r ?o)
    :effect (and (handempty ?r) (not (holding ?r ?o)) (at ?o ?l) [place ?r ?o ?l])))

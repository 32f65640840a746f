; Pick and place with geometry (thesis Chapter 6, Table 6.1's actions): the geometric state is the
; numeric fluent (geometry), an identifier of the symbolic–geometric map; each action's geometric
; precondition and effect is one of kaboum's geometric attachments (docs/tamp.md), which fails when
; no grasp, placement or certified path is found and otherwise returns the new state's identifier.
(define (domain pick-and-place)
  (:requirements :strips :typing :negative-preconditions :numeric-fluents :semantic-attachments)
  (:types robot object location)
  (:predicates (handempty ?r - robot) (holding ?r - robot ?o - object)
               (at ?o - object ?l - location))
  (:functions (geometry))
  (:modules
    (transit ?r - robot (geometry) effect move :reads ((geometry)))
    (grasp ?r - robot ?o - object (geometry) effect pickUp :reads ((geometry)))
    (place ?r - robot ?o - object ?l - location (geometry) effect putDown :reads ((geometry))))
  (:action pickup
    :parameters (?r - robot ?o - object ?l - location)
    :precondition (and (handempty ?r) (at ?o ?l))
    :effect (and (not (handempty ?r)) (holding ?r ?o) (not (at ?o ?l)) [grasp ?r ?o]))
  (:action putdown
    :parameters (?r - robot ?o - object ?l - location)
    :precondition (holding ?r ?o)
    :effect (and (handempty ?r) (not (holding ?r ?o)) (at ?o ?l) [place ?r ?o ?l])))

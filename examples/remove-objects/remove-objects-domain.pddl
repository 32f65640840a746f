; Remove n Objects (seed 003 §IV-A, Table II): pickup and putdown whose geometric effects are
; kaboum's attachments pickUp and putDown on the geometric state fluent (geometry) (docs/tamp.md);
; an action whose grasp, placement or certified path is not found is not applicable.
(define (domain remove-objects)
  (:requirements :strips :typing :negative-preconditions :numeric-fluents :semantic-attachments)
  (:types robot object location)
  (:predicates (handempty ?r - robot) (holding ?r - robot ?o - object)
               (at ?o - object ?l - location))
  (:functions (geometry))
  (:modules
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

; Seed 003's MOVE AND STACK domain (§IV): one robot picks up and puts down objects in locations.
; Nothing here speaks of stacking: putDown (docs/tamp.md) puts an object where freeSpaceFound finds
; room in the location — on the table, or on the top of another object standing there when the
; location is full side by side (isOnSupportSurface: "the top of the can is semantically the same
; as the tabletop"). (at ?o ?l) records where the planner put each object, for the heuristic; the
; goals test the geometry itself with isInside.
(define (domain move-and-stack)
  (:requirements :strips :typing :negative-preconditions :numeric-fluents :semantic-attachments)
  (:types robot item location)
  (:predicates (handempty ?r - robot) (holding ?r - robot ?o - item) (at ?o - item ?l - location))
  (:functions (geometry))
  (:modules
    (grasp ?r - robot ?o - item (geometry) effect pickUp :reads ((geometry)))
    (place ?r - robot ?o - item ?l - location (geometry) effect putDown :reads ((geometry)))
    (inside ?o - item ?l - location conditionchecker isInside :reads ((geometry))))
  (:action pickup
    :parameters (?r - robot ?o - item ?l - location)
    :precondition (and (handempty ?r) (at ?o ?l))
    :effect (and (not (handempty ?r)) (holding ?r ?o) (not (at ?o ?l)) [grasp ?r ?o]))
  (:action putdown
    :parameters (?r - robot ?o - item ?l - location)
    :precondition (holding ?r ?o)
    :effect (and (handempty ?r) (not (holding ?r ?o)) (at ?o ?l) [place ?r ?o ?l])))

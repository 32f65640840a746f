; The Tables domain (seed 004 §V, Table I): one robot picks up and puts down items in the places on
; three tables. Nothing here says that a place holds one item: putDown (docs/tamp.md) puts an item
; where freeSpaceFound finds room in the place, and an occupied place has none, so a goal that
; names an occupied place makes the planner move the occupant first. (at ?o ?l) records where the
; planner put each item, for the heuristic; the goals test the geometry itself with isInside.
(define (domain tables)
  (:requirements :strips :typing :negative-preconditions :numeric-fluents :semantic-attachments)
  (:types robot item place)
  (:predicates (handempty ?r - robot) (holding ?r - robot ?o - item) (at ?o - item ?l - place))
  (:functions (geometry))
  (:modules
    (grasp ?r - robot ?o - item (geometry) effect pickUp :reads ((geometry)))
    (put ?r - robot ?o - item ?l - place (geometry) effect putDown :reads ((geometry)))
    (inside ?o - item ?l - place conditionchecker isInside :reads ((geometry))))
  (:action pickup
    :parameters (?r - robot ?o - item ?l - place)
    :precondition (and (handempty ?r) (at ?o ?l))
    :effect (and (not (handempty ?r)) (holding ?r ?o) (not (at ?o ?l)) [grasp ?r ?o]))
  (:action putdown
    :parameters (?r - robot ?o - item ?l - place)
    :precondition (holding ?r ?o)
    :effect (and (handempty ?r) (not (holding ?r ?o)) (at ?o ?l) [put ?r ?o ?l])))

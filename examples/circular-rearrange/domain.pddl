; The Bimanual Circular Rearrange scenario (thesis §6.2.1, Table 6.1) with geometry: two robots
; move bottles between locations. Which robot reaches which location is not written here: the
; geometric attachments pickUp and putDown (docs/tamp.md) find grasps, placements and certified
; paths, or fail; retract takes a robot home, out of the other's way (the thesis's move samples a
; random configuration instead).
(define (domain circular-rearrange)
  (:requirements :strips :typing :negative-preconditions :numeric-fluents :semantic-attachments)
  (:types bottle robot location)
  (:predicates (isgrasped ?o - bottle) (isrobotgrasps ?r - robot ?o - bottle)
               (ishandempty ?r - robot) (isatlocation ?o - bottle ?l - location))
  (:functions (geometry))
  (:modules
    (home ?r - robot (geometry) effect moveHome :reads ((geometry)))
    (grasp ?r - robot ?o - bottle (geometry) effect pickUp :reads ((geometry)))
    (place ?r - robot ?o - bottle ?l - location (geometry) effect putDown :reads ((geometry))))
  (:action pickup
    :parameters (?r - robot ?o - bottle ?l - location)
    :precondition (and (ishandempty ?r) (not (isgrasped ?o)) (isatlocation ?o ?l))
    :effect (and (not (ishandempty ?r)) (isgrasped ?o) (isrobotgrasps ?r ?o)
                 (not (isatlocation ?o ?l)) [grasp ?r ?o]))
  (:action putdown
    :parameters (?r - robot ?o - bottle ?l - location)
    :precondition (and (isrobotgrasps ?r ?o) (isgrasped ?o))
    :effect (and (ishandempty ?r) (not (isgrasped ?o)) (isatlocation ?o ?l)
                 (not (isrobotgrasps ?r ?o)) [place ?r ?o ?l]))
  (:action retract
    :parameters (?r - robot)
    :effect [home ?r]))

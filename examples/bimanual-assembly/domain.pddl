; The Bimanual Assembly scenario (thesis §6.2.3, Tables 6.5 and 6.6): two arms assemble a gearbox
; component from two bearings, a pipe and a mechanical tree. Every action has exactly one geometric
; function: the standard attachments move, pickUp, putDown and handover, and the scenario's
; assembly effects assemblePipeBearing, assembleBearingTree and assemblePipeTree (docs/tamp.md,
; "Assembly actions"). Which arm can grasp which part how is not written here: the grasps of
; scene.yaml and the geometry decide.
(define (domain bimanual-assembly)
  (:requirements :strips :typing :negative-preconditions :existential-preconditions
                 :numeric-fluents :semantic-attachments)
  (:types robot part location)
  (:predicates (ishandempty ?r - robot) (isgrasped ?o - part) (isrobotgrasps ?r - robot ?o - part)
               (iscontained ?o - part) (containsbearing ?o - part)
               (isabearing ?o - part) (isapipe ?o - part) (isatree ?o - part)
               (isagearbox ?o - part))
  (:functions (geometry))
  (:modules
    (transit ?r - robot (geometry) effect move :reads ((geometry)))
    (grasp ?r - robot ?o - part (geometry) effect pickUp :reads ((geometry)))
    (place ?r - robot ?o - part ?l - location (geometry) effect putDown :reads ((geometry)))
    (pipebearing ?r - robot ?o - part ?r2 - robot ?o2 - part (geometry)
                 effect assemblePipeBearing :reads ((geometry)))
    (hand ?r - robot ?o - part ?r2 - robot (geometry) effect handover :reads ((geometry)))
    (bearingtree ?r - robot ?o - part ?o2 - part (geometry)
                 effect assembleBearingTree :reads ((geometry)))
    (pipetree ?r - robot ?o - part ?o2 - part (geometry)
              effect assemblePipeTree :reads ((geometry))))
  (:action move
    :parameters (?r - robot)
    :effect [transit ?r])
  (:action pickup
    :parameters (?r - robot ?o - part)
    :precondition (and (ishandempty ?r) (not (isgrasped ?o)) (not (iscontained ?o)))
    :effect (and (not (ishandempty ?r)) (isgrasped ?o) (isrobotgrasps ?r ?o) [grasp ?r ?o]))
  (:action putdown
    :parameters (?r - robot ?o - part ?l - location)
    :precondition (and (isrobotgrasps ?r ?o) (isgrasped ?o) (not (iscontained ?o)))
    :effect (and (ishandempty ?r) (not (isgrasped ?o)) (not (isrobotgrasps ?r ?o))
                 [place ?r ?o ?l]))
  (:action assemblepipebearing
    :parameters (?r - robot ?o - part ?r2 - robot ?o2 - part)
    :precondition (and (isrobotgrasps ?r ?o) (isrobotgrasps ?r2 ?o2) (isapipe ?o)
                       (isabearing ?o2) (not (iscontained ?o)) (not (iscontained ?o2)))
    :effect (and (ishandempty ?r2) (iscontained ?o2) (containsbearing ?o)
                 (not (isrobotgrasps ?r2 ?o2)) [pipebearing ?r ?o ?r2 ?o2]))
  (:action handoverbearing
    :parameters (?r - robot ?o - part ?r2 - robot)
    :precondition (and (isrobotgrasps ?r ?o) (isabearing ?o) (not (iscontained ?o))
                       (ishandempty ?r2))
    :effect (and (not (isrobotgrasps ?r ?o)) (isrobotgrasps ?r2 ?o) (ishandempty ?r)
                 (not (ishandempty ?r2)) [hand ?r ?o ?r2]))
  (:action assemblebearingtree
    :parameters (?r - robot ?o - part ?o2 - part)
    :precondition (and (isrobotgrasps ?r ?o) (not (isgrasped ?o2)) (isabearing ?o) (isatree ?o2)
                       (not (iscontained ?o)) (not (iscontained ?o2)))
    :effect (and (not (isrobotgrasps ?r ?o)) (not (isgrasped ?o)) (iscontained ?o)
                 (ishandempty ?r) (containsbearing ?o2) [bearingtree ?r ?o ?o2]))
  (:action assemblepipetree
    :parameters (?r - robot ?o - part ?o2 - part)
    :precondition (and (isrobotgrasps ?r ?o) (not (isgrasped ?o2)) (isapipe ?o) (isatree ?o2)
                       (containsbearing ?o) (containsbearing ?o2) (not (iscontained ?o))
                       (not (iscontained ?o2)))
    :effect (and (not (isrobotgrasps ?r ?o)) (not (isgrasped ?o)) (iscontained ?o2)
                 (ishandempty ?r) (isagearbox ?o) [pipetree ?r ?o ?o2])))

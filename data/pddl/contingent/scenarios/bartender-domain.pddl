; Bartender, symbolic part (thesis §6.2.1, Table 6.1): two robots move bottles; only empty bottles
; go to the dishwasher; senseIfEmpty adds Kw(isEmptyBottle o). Geometry is stubbed by the toy
; attachment `reaches` (which locations a robot's workspace covers); pickUp and putDown name the
; location so the stub can decide reachability.
(define (domain bartender)
  (:requirements :strips :typing :negative-preconditions :semantic-attachments)
  (:types object robot location)
  (:predicates (isgrasped ?o - object) (isrobotgrasps ?r - robot ?o - object)
               (ishandempty ?r - robot) (isatlocation ?o - object ?l - location)
               (isemptybottle ?o - object))
  (:modules (reaches ?r - robot ?l - location conditionchecker reaches))
  (:action move
    :parameters (?r - robot))
  (:action pickup
    :parameters (?r - robot ?o - object ?l - location)
    :precondition (and (ishandempty ?r) (not (isgrasped ?o)) (isatlocation ?o ?l) [reaches ?r ?l])
    :effect (and (not (ishandempty ?r)) (isgrasped ?o) (isrobotgrasps ?r ?o)
                 (not (isatlocation ?o ?l))))
  (:action putdown
    :parameters (?r - robot ?o - object ?l - location)
    :precondition (and (isrobotgrasps ?r ?o) (isgrasped ?o) [reaches ?r ?l])
    :effect (and (ishandempty ?r) (not (isgrasped ?o)) (isatlocation ?o ?l)
                 (not (isrobotgrasps ?r ?o))))
  (:action senseifempty
    :parameters (?o - object)
    :observe (isemptybottle ?o)))

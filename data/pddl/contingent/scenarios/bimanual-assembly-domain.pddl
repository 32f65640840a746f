; Bimanual Assembly, symbolic part (thesis §6.2.3, Tables 6.5 and 6.6): two robots assemble a
; gearbox from two bearings, a pipe and a mechanical tree. Every action has one geometric
; precondition, stubbed here by the toy attachment `reaches` (robot r can reach object o).
(define (domain bimanual-assembly)
  (:requirements :strips :typing :negative-preconditions :equality :existential-preconditions
                 :semantic-attachments)
  (:types object robot)
  (:predicates (isgrasped ?o - object) (isrobotgrasps ?r - robot ?o - object)
               (ishandempty ?r - robot) (iscontained ?o - object) (isabearing ?o - object)
               (isapipe ?o - object) (isatree ?o - object) (isagearbox ?o - object)
               (containsbearing ?o - object))
  (:modules (reaches ?r - robot ?o - object conditionchecker reaches))
  (:action move
    :parameters (?r - robot))
  (:action pickup
    :parameters (?r - robot ?o - object)
    :precondition (and (ishandempty ?r) (not (isgrasped ?o)) (not (iscontained ?o))
                       [reaches ?r ?o])
    :effect (and (not (ishandempty ?r)) (isgrasped ?o) (isrobotgrasps ?r ?o)))
  (:action putdown
    :parameters (?r - robot ?o - object)
    :precondition (and (isrobotgrasps ?r ?o) (isgrasped ?o) (not (iscontained ?o))
                       [reaches ?r ?o])
    :effect (and (ishandempty ?r) (not (isgrasped ?o)) (not (isrobotgrasps ?r ?o))))
  (:action assemblepipebearing
    :parameters (?r - robot ?o - object ?r2 - robot ?o2 - object)
    :precondition (and (not (= ?r ?r2)) (isrobotgrasps ?r ?o) (isrobotgrasps ?r2 ?o2)
                       (isapipe ?o) (isabearing ?o2) (not (iscontained ?o))
                       (not (iscontained ?o2)) [reaches ?r ?o])
    :effect (and (ishandempty ?r2) (iscontained ?o2) (containsbearing ?o)
                 (not (isrobotgrasps ?r2 ?o2))))
  (:action handoverbearing
    :parameters (?r - robot ?o - object ?r2 - robot)
    :precondition (and (not (= ?r ?r2)) (isrobotgrasps ?r ?o) (isabearing ?o)
                       (not (iscontained ?o)) (ishandempty ?r2) [reaches ?r2 ?o])
    :effect (and (not (isrobotgrasps ?r ?o)) (isrobotgrasps ?r2 ?o) (ishandempty ?r)
                 (not (ishandempty ?r2))))
  (:action assemblebearingtree
    :parameters (?r - robot ?o - object ?o2 - object)
    :precondition (and (isrobotgrasps ?r ?o) (not (isgrasped ?o2)) (isabearing ?o)
                       (isatree ?o2) (not (iscontained ?o)) (not (iscontained ?o2))
                       [reaches ?r ?o2])
    :effect (and (not (isrobotgrasps ?r ?o)) (not (isgrasped ?o)) (iscontained ?o)
                 (ishandempty ?r) (containsbearing ?o2)))
  (:action assemblepipetree
    :parameters (?r - robot ?o - object ?o2 - object)
    :precondition (and (isrobotgrasps ?r ?o) (not (isgrasped ?o2)) (isapipe ?o) (isatree ?o2)
                       (containsbearing ?o) (containsbearing ?o2) (not (iscontained ?o))
                       (not (iscontained ?o2)) [reaches ?r ?o2])
    :effect (and (not (isrobotgrasps ?r ?o)) (not (isgrasped ?o)) (iscontained ?o2)
                 (ishandempty ?r) (isagearbox ?o))))

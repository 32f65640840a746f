; Robot that drives, carries items and paints rooms. Exercises the ADL subset: typing with a
; hierarchy, constants, equality, negative/disjunctive/existential/universal preconditions
; (with imply) and conditional effects under forall.
(define (domain adl-robot)
  (:requirements :typing :negative-preconditions :equality :disjunctive-preconditions
                 :existential-preconditions :universal-preconditions :conditional-effects)
  (:types location item - object
          tool - item)
  (:constants home - location)
  (:predicates (at-robot ?l - location) (at ?i - item ?l - location) (carrying ?i - item)
               (road ?a ?b - location) (painted ?l - location))
  (:action drive
    :parameters (?from ?to - location)
    :precondition (and (at-robot ?from) (not (= ?from ?to))
                       (or (road ?from ?to) (road ?to ?from)))
    :effect (and (not (at-robot ?from)) (at-robot ?to)
                 (forall (?i - item)
                   (when (carrying ?i) (and (not (at ?i ?from)) (at ?i ?to))))))
  (:action pick
    :parameters (?i - item ?l - location)
    :precondition (and (at-robot ?l) (at ?i ?l) (not (carrying ?i)))
    :effect (carrying ?i))
  (:action drop
    :parameters (?i - item ?l - location)
    :precondition (and (at-robot ?l) (carrying ?i))
    :effect (not (carrying ?i)))
  (:action paint
    :parameters (?l - location)
    :precondition (and (at-robot ?l) (exists (?t - tool) (carrying ?t))
                       (forall (?i - item) (imply (at ?i ?l) (carrying ?i))))
    :effect (painted ?l)))

(define (domain stacked-objects-geometry)
  (:requirements :typing :negative-preconditions :equality :conditional-effects
                 :object-fluents :numeric-fluents :semantic-attachments)
  (:types object robot)
  (:predicates (isastack ?o - object) (ishighest ?o - object) (instack ?o - object ?s - object)
               (handempty ?r - robot) (holding ?r - robot ?o - object))
  (:functions (getonebelow ?o - object) - object (geometry))
  (:modules
    (grasp ?r - robot ?o - object (geometry) effect pickUp :reads ((geometry)))
    (place ?r - robot ?o - object ?s - object (geometry) effect putDown :reads ((geometry))))
  (:action pickup
    :parameters (?r - robot ?this - object ?s - object)
    :precondition (and (handempty ?r) (ishighest ?this) (not (isastack ?this)) (instack ?this ?s))
    :effect (and (not (handempty ?r)) (holding ?r ?this) (not (ishighest ?this))
                 (not (instack ?this ?s))
                 (forall (?o - object) (when (= (getonebelow ?this) ?o) (ishighest ?o)))
                 [grasp ?r ?this]))
  (:action putdown
    :parameters (?r - robot ?this - object ?other - object ?s - object)
    :precondition (and (holding ?r ?this) (ishighest ?other) (instack ?other ?s) (isastack ?s))
    :effect (and (handempty ?r) (not (holding ?r ?this)) (ishighest ?this)
                 (not (ishighest ?other)) (assign (getonebelow ?this) ?other) (instack ?this ?s)
                 [place ?r ?this ?s])))

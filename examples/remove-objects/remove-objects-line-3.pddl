; Remove 3 objects from the table into the bin, the hand empty at the end.
(define (problem remove-line-3)
  (:domain remove-objects)
  (:objects kr5 - robot o1 o2 o3 - object table-top bin - location)
  (:init (handempty kr5) (at o1 table-top) (at o2 table-top) (at o3 table-top) (= (geometry) 0))
  (:goal (and (at o1 bin) (at o2 bin) (at o3 bin) (handempty kr5))))

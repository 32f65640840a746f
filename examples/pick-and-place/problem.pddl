; Move the block from the table's left region to its right region and leave the hand empty.
(define (problem move-block)
  (:domain pick-and-place)
  (:objects kr5 - robot block - object left right - location)
  (:init (handempty kr5) (at block left) (= (geometry) 0))
  (:goal (and (at block right) (handempty kr5))))

; Unsolvable only after search: the driver needs 'path_a' and the logger needs 'path_b', and
; only the two mutually exclusive candidates of the one planner role offer them. Relaxed
; reachability (which ignores that a role is filled once) sees both services as reachable.
(define (problem pick-dead-end)
  (:domain pick-components)
  (:objects
    sensor planner driver logger - role
    cam_a nav_a nav_b base_a log_a - component
    power image path_a path_b motion record - service)
  (:init
    (open sensor) (open planner) (open driver) (open logger)
    (available power)
    (candidate sensor cam_a) (needs cam_a power) (offers cam_a image) (= (price cam_a) 1)
    (candidate planner nav_a) (needs nav_a image) (offers nav_a path_a) (= (price nav_a) 1)
    (candidate planner nav_b) (needs nav_b image) (offers nav_b path_b) (= (price nav_b) 1)
    (candidate driver base_a) (needs base_a path_a) (offers base_a motion) (= (price base_a) 1)
    (candidate logger log_a) (needs log_a path_b) (offers log_a record) (= (price log_a) 1)
    (= (total-cost) 0))
  (:goal (and (filled sensor) (filled planner) (filled driver) (filled logger)))
  (:metric minimize (total-cost)))

; Three roles, two candidates each. The cheapest configuration is cam_b + nav_b + base_a
; (cost 1 + 1 + 4 = 6); every configuration is three picks long.
(define (problem pick-three-roles)
  (:domain pick-components)
  (:objects
    sensor planner driver - role
    cam_a cam_b nav_a nav_b base_a base_b - component
    power image path motion - service)
  (:init
    (open sensor) (open planner) (open driver)
    (available power)
    (candidate sensor cam_a) (needs cam_a power) (offers cam_a image) (= (price cam_a) 5)
    (candidate sensor cam_b) (needs cam_b power) (offers cam_b image) (= (price cam_b) 1)
    (candidate planner nav_a) (needs nav_a image) (offers nav_a path) (= (price nav_a) 2)
    (candidate planner nav_b) (needs nav_b image) (offers nav_b path) (= (price nav_b) 1)
    (candidate driver base_a) (needs base_a path) (offers base_a motion) (= (price base_a) 4)
    (candidate driver base_b) (needs base_b path) (offers base_b motion) (= (price base_b) 10)
    (= (total-cost) 0))
  (:goal (and (filled sensor) (filled planner) (filled driver)))
  (:metric minimize (total-cost)))

; Unsolvable at first sight: the only driver needs the service 'odometry', which no
; component offers.
(define (problem pick-no-provider)
  (:domain pick-components)
  (:objects
    sensor driver - role
    cam_a base_a - component
    power image odometry motion - service)
  (:init
    (open sensor) (open driver)
    (available power)
    (candidate sensor cam_a) (needs cam_a power) (offers cam_a image) (= (price cam_a) 1)
    (candidate driver base_a) (needs base_a odometry) (offers base_a motion) (= (price base_a) 1)
    (= (total-cost) 0))
  (:goal (and (filled sensor) (filled driver)))
  (:metric minimize (total-cost)))

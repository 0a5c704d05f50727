;; rosreconf: Indoor Navigation (indoor_navigation).
;; Skill: Drive to a goal pose in a known indoor map, avoiding obstacles seen by the range sensor.
;; running now: range_sensor = HOKUYO_UST10
;; running now: odometry = EKF_ODOM
;; running now: localisation = AMCL
;; running now: local_planner = TEB_PLANNER
;; running now: base = DIFF_DRIVE
(define (problem rosreconf-indoor_navigation-task)
  (:domain rosreconf-indoor_navigation)
  (:init
    (choosing range_sensor)
    (= (total-cost) 0)
  )
  (:goal (and
    (finished)
  ))
  (:metric minimize (total-cost))
)

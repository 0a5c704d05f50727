;; rosreconf: Indoor Navigation (indoor_navigation), pre-grounded STRIPS with action costs.
;; choose-ROLE-COMPONENT fills a role (roles in schema order); connect-ROLE-REQUIREMENT-PROVIDERROLE
;; meets a requirement along an edge; finish-ROLE-COMPONENT checks requirements and couplings;
;; restart-ROLE-COMPONENT finishes a kept component that must restart to be rewired (one change).
;; Generated from the templates in rosreconf; see docs/pddl.md.
(define (domain rosreconf-indoor_navigation)
  (:requirements :strips :typing :negative-preconditions :action-costs)
  (:types role component requirement)
  (:constants
    range_sensor
    odometry
    localisation
    local_planner
    base
    - role
    amcl
    diff_drive
    dwa_planner
    ekf_odom
    hokuyo_ust10
    roboclaw_base
    sick_tim571
    slam_toolbox
    sonar_ring
    teb_planner
    wheel_odom
    - component
    cmd_vel
    joint_states
    odom
    pose
    scan
    scan-or-sonar
    - requirement
  )
  (:predicates
    (choosing ?r - role)
    (checking ?r - role)
    (finished)
    (uses ?r - role ?c - component)
    (chosen ?c - component)
    (serves ?p - role ?r - role ?q - requirement)
    (met ?r - role ?q - requirement)
    (failed ?c - component)
  )
  (:functions (total-cost) - number)

  ;; keep HOKUYO_UST10 as range_sensor
  (:action choose-range_sensor-hokuyo_ust10
    :parameters ()
    :precondition (and
      (choosing range_sensor)
    )
    :effect (and
      (not (choosing range_sensor))
      (choosing odometry)
      (uses range_sensor hokuyo_ust10)
      (serves range_sensor localisation scan)
      (serves range_sensor local_planner scan-or-sonar)
      (serves range_sensor local_planner scan)
      (increase (total-cost) 0)
    )
  )

  ;; start SICK_TIM571 as range_sensor
  (:action choose-range_sensor-sick_tim571
    :parameters ()
    :precondition (and
      (choosing range_sensor)
    )
    :effect (and
      (not (choosing range_sensor))
      (choosing odometry)
      (uses range_sensor sick_tim571)
      (serves range_sensor localisation scan)
      (serves range_sensor local_planner scan-or-sonar)
      (serves range_sensor local_planner scan)
      (increase (total-cost) 1)
    )
  )

  ;; start SONAR_RING as range_sensor
  (:action choose-range_sensor-sonar_ring
    :parameters ()
    :precondition (and
      (choosing range_sensor)
    )
    :effect (and
      (not (choosing range_sensor))
      (choosing odometry)
      (uses range_sensor sonar_ring)
      (serves range_sensor local_planner scan-or-sonar)
      (increase (total-cost) 1)
    )
  )

  ;; start WHEEL_ODOM as odometry
  (:action choose-odometry-wheel_odom
    :parameters ()
    :precondition (and
      (choosing odometry)
    )
    :effect (and
      (not (choosing odometry))
      (choosing localisation)
      (uses odometry wheel_odom)
      (serves odometry localisation odom)
      (increase (total-cost) 1)
    )
  )

  ;; keep EKF_ODOM as odometry
  (:action choose-odometry-ekf_odom
    :parameters ()
    :precondition (and
      (choosing odometry)
    )
    :effect (and
      (not (choosing odometry))
      (choosing localisation)
      (uses odometry ekf_odom)
      (chosen ekf_odom)
      (serves odometry localisation odom)
      (increase (total-cost) 0)
    )
  )

  ;; keep AMCL as localisation
  (:action choose-localisation-amcl
    :parameters ()
    :precondition (and
      (choosing localisation)
      (not (uses range_sensor sonar_ring))
    )
    :effect (and
      (not (choosing localisation))
      (choosing local_planner)
      (uses localisation amcl)
      (serves localisation local_planner pose)
      (increase (total-cost) 0)
    )
  )

  ;; start SLAM_TOOLBOX as localisation
  (:action choose-localisation-slam_toolbox
    :parameters ()
    :precondition (and
      (choosing localisation)
      (not (uses range_sensor sonar_ring))
    )
    :effect (and
      (not (choosing localisation))
      (choosing local_planner)
      (uses localisation slam_toolbox)
      (serves localisation local_planner pose)
      (increase (total-cost) 1)
    )
  )

  ;; start DWA_PLANNER as local_planner
  (:action choose-local_planner-dwa_planner
    :parameters ()
    :precondition (and
      (choosing local_planner)
    )
    :effect (and
      (not (choosing local_planner))
      (choosing base)
      (uses local_planner dwa_planner)
      (serves local_planner base cmd_vel)
      (increase (total-cost) 1)
    )
  )

  ;; keep TEB_PLANNER as local_planner
  (:action choose-local_planner-teb_planner
    :parameters ()
    :precondition (and
      (choosing local_planner)
      (not (uses range_sensor sonar_ring))
    )
    :effect (and
      (not (choosing local_planner))
      (choosing base)
      (uses local_planner teb_planner)
      (serves local_planner base cmd_vel)
      (increase (total-cost) 0)
    )
  )

  ;; keep DIFF_DRIVE as base
  (:action choose-base-diff_drive
    :parameters ()
    :precondition (and
      (choosing base)
    )
    :effect (and
      (not (choosing base))
      (checking range_sensor)
      (uses base diff_drive)
      (serves base odometry joint_states)
      (increase (total-cost) 0)
    )
  )

  ;; start ROBOCLAW_BASE as base
  (:action choose-base-roboclaw_base
    :parameters ()
    :precondition (and
      (choosing base)
    )
    :effect (and
      (not (choosing base))
      (checking range_sensor)
      (uses base roboclaw_base)
      (serves base odometry joint_states)
      (increase (total-cost) 1)
    )
  )

  ;; base meets odometry's need for topic 'joint_states' (sensor_msgs/msg/JointState)
  (:action connect-odometry-joint_states-base
    :parameters ()
    :precondition (and
      (checking odometry)
      (not (met odometry joint_states))
      (serves base odometry joint_states)
    )
    :effect (and
      (met odometry joint_states)
      (increase (total-cost) 0)
    )
  )

  ;; range_sensor meets localisation's need for topic 'scan' (sensor_msgs/msg/LaserScan)
  (:action connect-localisation-scan-range_sensor
    :parameters ()
    :precondition (and
      (checking localisation)
      (not (met localisation scan))
      (serves range_sensor localisation scan)
    )
    :effect (and
      (met localisation scan)
      (increase (total-cost) 0)
    )
  )

  ;; odometry meets localisation's need for topic 'odom' (nav_msgs/msg/Odometry)
  (:action connect-localisation-odom-odometry
    :parameters ()
    :precondition (and
      (checking localisation)
      (not (met localisation odom))
      (serves odometry localisation odom)
    )
    :effect (and
      (met localisation odom)
      (increase (total-cost) 0)
    )
  )

  ;; localisation meets local_planner's need for topic 'pose' (geometry_msgs/msg/PoseWithCovarianceStamped)
  (:action connect-local_planner-pose-localisation
    :parameters ()
    :precondition (and
      (checking local_planner)
      (not (met local_planner pose))
      (serves localisation local_planner pose)
    )
    :effect (and
      (met local_planner pose)
      (increase (total-cost) 0)
    )
  )

  ;; range_sensor meets local_planner's need for any one of topic 'scan' (sensor_msgs/msg/LaserScan), topic 'sonar' (sensor_msgs/msg/Range)
  (:action connect-local_planner-scan-or-sonar-range_sensor
    :parameters ()
    :precondition (and
      (checking local_planner)
      (not (met local_planner scan-or-sonar))
      (serves range_sensor local_planner scan-or-sonar)
    )
    :effect (and
      (met local_planner scan-or-sonar)
      (increase (total-cost) 0)
    )
  )

  ;; range_sensor meets local_planner's need for topic 'scan' (sensor_msgs/msg/LaserScan)
  (:action connect-local_planner-scan-range_sensor
    :parameters ()
    :precondition (and
      (checking local_planner)
      (not (met local_planner scan))
      (serves range_sensor local_planner scan)
    )
    :effect (and
      (met local_planner scan)
      (increase (total-cost) 0)
    )
  )

  ;; local_planner meets base's need for topic 'cmd_vel' (geometry_msgs/msg/Twist)
  (:action connect-base-cmd_vel-local_planner
    :parameters ()
    :precondition (and
      (checking base)
      (not (met base cmd_vel))
      (serves local_planner base cmd_vel)
    )
    :effect (and
      (met base cmd_vel)
      (increase (total-cost) 0)
    )
  )

  ;; HOKUYO_UST10 has all it requires and needs
  (:action finish-range_sensor-hokuyo_ust10
    :parameters ()
    :precondition (and
      (checking range_sensor)
      (uses range_sensor hokuyo_ust10)
    )
    :effect (and
      (not (checking range_sensor))
      (checking odometry)
      (increase (total-cost) 0)
    )
  )

  ;; SICK_TIM571 has all it requires and needs
  (:action finish-range_sensor-sick_tim571
    :parameters ()
    :precondition (and
      (checking range_sensor)
      (uses range_sensor sick_tim571)
    )
    :effect (and
      (not (checking range_sensor))
      (checking odometry)
      (increase (total-cost) 0)
    )
  )

  ;; SONAR_RING has all it requires and needs
  (:action finish-range_sensor-sonar_ring
    :parameters ()
    :precondition (and
      (checking range_sensor)
      (uses range_sensor sonar_ring)
    )
    :effect (and
      (not (checking range_sensor))
      (checking odometry)
      (increase (total-cost) 0)
    )
  )

  ;; WHEEL_ODOM has all it requires and needs
  (:action finish-odometry-wheel_odom
    :parameters ()
    :precondition (and
      (checking odometry)
      (uses odometry wheel_odom)
      (met odometry joint_states)
    )
    :effect (and
      (not (checking odometry))
      (checking localisation)
      (increase (total-cost) 0)
    )
  )

  ;; EKF_ODOM has all it requires and needs
  (:action finish-odometry-ekf_odom
    :parameters ()
    :precondition (and
      (checking odometry)
      (uses odometry ekf_odom)
      (met odometry joint_states)
    )
    :effect (and
      (not (checking odometry))
      (checking localisation)
      (increase (total-cost) 0)
    )
  )

  ;; AMCL has all it requires and needs
  (:action finish-localisation-amcl
    :parameters ()
    :precondition (and
      (checking localisation)
      (uses localisation amcl)
      (met localisation scan)
      (met localisation odom)
    )
    :effect (and
      (not (checking localisation))
      (checking local_planner)
      (increase (total-cost) 0)
    )
  )

  ;; SLAM_TOOLBOX has all it requires and needs
  (:action finish-localisation-slam_toolbox
    :parameters ()
    :precondition (and
      (checking localisation)
      (uses localisation slam_toolbox)
      (met localisation scan)
      (met localisation odom)
    )
    :effect (and
      (not (checking localisation))
      (checking local_planner)
      (increase (total-cost) 0)
    )
  )

  ;; DWA_PLANNER has all it requires and needs
  (:action finish-local_planner-dwa_planner
    :parameters ()
    :precondition (and
      (checking local_planner)
      (uses local_planner dwa_planner)
      (met local_planner pose)
      (met local_planner scan-or-sonar)
    )
    :effect (and
      (not (checking local_planner))
      (checking base)
      (increase (total-cost) 0)
    )
  )

  ;; TEB_PLANNER has all it requires and needs
  (:action finish-local_planner-teb_planner
    :parameters ()
    :precondition (and
      (checking local_planner)
      (uses local_planner teb_planner)
      (met local_planner pose)
      (met local_planner scan)
      (chosen ekf_odom)
    )
    :effect (and
      (not (checking local_planner))
      (checking base)
      (increase (total-cost) 0)
    )
  )

  ;; DIFF_DRIVE has all it requires and needs
  (:action finish-base-diff_drive
    :parameters ()
    :precondition (and
      (checking base)
      (uses base diff_drive)
      (met base cmd_vel)
    )
    :effect (and
      (not (checking base))
      (finished)
      (increase (total-cost) 0)
    )
  )

  ;; ROBOCLAW_BASE has all it requires and needs
  (:action finish-base-roboclaw_base
    :parameters ()
    :precondition (and
      (checking base)
      (uses base roboclaw_base)
      (met base cmd_vel)
    )
    :effect (and
      (not (checking base))
      (finished)
      (increase (total-cost) 0)
    )
  )
)

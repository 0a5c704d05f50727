;; rosreconf: Indoor Navigation (indoor_navigation), pre-grounded STRIPS with action costs.
;; choose-ROLE-COMPONENT fills a role; connect-ROLE-REQUIREMENT-PROVIDERROLE-PROVIDER meets a
;; requirement along an edge; finish-ROLE-COMPONENT checks requirements and couplings.
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
    (filled ?r - role)
    (uses ?r - role ?c - component)
    (chosen ?c - component)
    (met ?r - role ?q - requirement)
    (done ?r - role)
    (failed ?c - component)
  )
  (:functions (total-cost) - number)

  ;; keep HOKUYO_UST10 as range_sensor
  (:action choose-range_sensor-hokuyo_ust10
    :parameters ()
    :precondition (and
      (not (filled range_sensor))
      (not (chosen hokuyo_ust10))
    )
    :effect (and
      (filled range_sensor)
      (uses range_sensor hokuyo_ust10)
      (chosen hokuyo_ust10)
      (increase (total-cost) 0)
    )
  )

  ;; start SICK_TIM571 as range_sensor
  (:action choose-range_sensor-sick_tim571
    :parameters ()
    :precondition (and
      (not (filled range_sensor))
      (not (chosen sick_tim571))
    )
    :effect (and
      (filled range_sensor)
      (uses range_sensor sick_tim571)
      (chosen sick_tim571)
      (increase (total-cost) 1)
    )
  )

  ;; start SONAR_RING as range_sensor
  (:action choose-range_sensor-sonar_ring
    :parameters ()
    :precondition (and
      (not (filled range_sensor))
      (not (chosen sonar_ring))
      (not (uses localisation amcl))
      (not (uses localisation slam_toolbox))
      (not (uses local_planner teb_planner))
    )
    :effect (and
      (filled range_sensor)
      (uses range_sensor sonar_ring)
      (chosen sonar_ring)
      (increase (total-cost) 1)
    )
  )

  ;; start WHEEL_ODOM as odometry
  (:action choose-odometry-wheel_odom
    :parameters ()
    :precondition (and
      (not (filled odometry))
      (not (chosen wheel_odom))
      (filled range_sensor)
    )
    :effect (and
      (filled odometry)
      (uses odometry wheel_odom)
      (chosen wheel_odom)
      (increase (total-cost) 1)
    )
  )

  ;; keep EKF_ODOM as odometry
  (:action choose-odometry-ekf_odom
    :parameters ()
    :precondition (and
      (not (filled odometry))
      (not (chosen ekf_odom))
      (filled range_sensor)
    )
    :effect (and
      (filled odometry)
      (uses odometry ekf_odom)
      (chosen ekf_odom)
      (increase (total-cost) 0)
    )
  )

  ;; keep AMCL as localisation
  (:action choose-localisation-amcl
    :parameters ()
    :precondition (and
      (not (filled localisation))
      (not (chosen amcl))
      (filled odometry)
      (not (uses range_sensor sonar_ring))
    )
    :effect (and
      (filled localisation)
      (uses localisation amcl)
      (chosen amcl)
      (increase (total-cost) 0)
    )
  )

  ;; start SLAM_TOOLBOX as localisation
  (:action choose-localisation-slam_toolbox
    :parameters ()
    :precondition (and
      (not (filled localisation))
      (not (chosen slam_toolbox))
      (filled odometry)
      (not (uses range_sensor sonar_ring))
    )
    :effect (and
      (filled localisation)
      (uses localisation slam_toolbox)
      (chosen slam_toolbox)
      (increase (total-cost) 1)
    )
  )

  ;; start DWA_PLANNER as local_planner
  (:action choose-local_planner-dwa_planner
    :parameters ()
    :precondition (and
      (not (filled local_planner))
      (not (chosen dwa_planner))
      (filled localisation)
    )
    :effect (and
      (filled local_planner)
      (uses local_planner dwa_planner)
      (chosen dwa_planner)
      (increase (total-cost) 1)
    )
  )

  ;; keep TEB_PLANNER as local_planner
  (:action choose-local_planner-teb_planner
    :parameters ()
    :precondition (and
      (not (filled local_planner))
      (not (chosen teb_planner))
      (filled localisation)
      (not (uses range_sensor sonar_ring))
    )
    :effect (and
      (filled local_planner)
      (uses local_planner teb_planner)
      (chosen teb_planner)
      (increase (total-cost) 0)
    )
  )

  ;; keep DIFF_DRIVE as base
  (:action choose-base-diff_drive
    :parameters ()
    :precondition (and
      (not (filled base))
      (not (chosen diff_drive))
      (filled local_planner)
    )
    :effect (and
      (filled base)
      (uses base diff_drive)
      (chosen diff_drive)
      (increase (total-cost) 0)
    )
  )

  ;; start ROBOCLAW_BASE as base
  (:action choose-base-roboclaw_base
    :parameters ()
    :precondition (and
      (not (filled base))
      (not (chosen roboclaw_base))
      (filled local_planner)
    )
    :effect (and
      (filled base)
      (uses base roboclaw_base)
      (chosen roboclaw_base)
      (increase (total-cost) 1)
    )
  )

  ;; DIFF_DRIVE (base) meets odometry's need for topic 'joint_states' (sensor_msgs/JointState)
  (:action connect-odometry-joint_states-base-diff_drive
    :parameters ()
    :precondition (and
      (filled base)
      (done range_sensor)
      (not (met odometry joint_states))
      (uses base diff_drive)
    )
    :effect (and
      (met odometry joint_states)
      (increase (total-cost) 0)
    )
  )

  ;; ROBOCLAW_BASE (base) meets odometry's need for topic 'joint_states' (sensor_msgs/JointState)
  (:action connect-odometry-joint_states-base-roboclaw_base
    :parameters ()
    :precondition (and
      (filled base)
      (done range_sensor)
      (not (met odometry joint_states))
      (uses base roboclaw_base)
    )
    :effect (and
      (met odometry joint_states)
      (increase (total-cost) 0)
    )
  )

  ;; HOKUYO_UST10 (range_sensor) meets localisation's need for topic 'scan' (sensor_msgs/LaserScan)
  (:action connect-localisation-scan-range_sensor-hokuyo_ust10
    :parameters ()
    :precondition (and
      (filled base)
      (done odometry)
      (not (met localisation scan))
      (uses range_sensor hokuyo_ust10)
    )
    :effect (and
      (met localisation scan)
      (increase (total-cost) 0)
    )
  )

  ;; SICK_TIM571 (range_sensor) meets localisation's need for topic 'scan' (sensor_msgs/LaserScan)
  (:action connect-localisation-scan-range_sensor-sick_tim571
    :parameters ()
    :precondition (and
      (filled base)
      (done odometry)
      (not (met localisation scan))
      (uses range_sensor sick_tim571)
    )
    :effect (and
      (met localisation scan)
      (increase (total-cost) 0)
    )
  )

  ;; WHEEL_ODOM (odometry) meets localisation's need for topic 'odom' (nav_msgs/Odometry)
  (:action connect-localisation-odom-odometry-wheel_odom
    :parameters ()
    :precondition (and
      (filled base)
      (done odometry)
      (not (met localisation odom))
      (uses odometry wheel_odom)
    )
    :effect (and
      (met localisation odom)
      (increase (total-cost) 0)
    )
  )

  ;; EKF_ODOM (odometry) meets localisation's need for topic 'odom' (nav_msgs/Odometry)
  (:action connect-localisation-odom-odometry-ekf_odom
    :parameters ()
    :precondition (and
      (filled base)
      (done odometry)
      (not (met localisation odom))
      (uses odometry ekf_odom)
    )
    :effect (and
      (met localisation odom)
      (increase (total-cost) 0)
    )
  )

  ;; AMCL (localisation) meets local_planner's need for topic 'pose' (geometry_msgs/PoseWithCovarianceStamped)
  (:action connect-local_planner-pose-localisation-amcl
    :parameters ()
    :precondition (and
      (filled base)
      (done localisation)
      (not (met local_planner pose))
      (uses localisation amcl)
    )
    :effect (and
      (met local_planner pose)
      (increase (total-cost) 0)
    )
  )

  ;; SLAM_TOOLBOX (localisation) meets local_planner's need for topic 'pose' (geometry_msgs/PoseWithCovarianceStamped)
  (:action connect-local_planner-pose-localisation-slam_toolbox
    :parameters ()
    :precondition (and
      (filled base)
      (done localisation)
      (not (met local_planner pose))
      (uses localisation slam_toolbox)
    )
    :effect (and
      (met local_planner pose)
      (increase (total-cost) 0)
    )
  )

  ;; HOKUYO_UST10 (range_sensor) meets local_planner's need for any one of topic 'scan' (sensor_msgs/LaserScan), topic 'sonar' (sensor_msgs/Range)
  (:action connect-local_planner-scan-or-sonar-range_sensor-hokuyo_ust10
    :parameters ()
    :precondition (and
      (filled base)
      (done localisation)
      (not (met local_planner scan-or-sonar))
      (uses range_sensor hokuyo_ust10)
    )
    :effect (and
      (met local_planner scan-or-sonar)
      (increase (total-cost) 0)
    )
  )

  ;; SICK_TIM571 (range_sensor) meets local_planner's need for any one of topic 'scan' (sensor_msgs/LaserScan), topic 'sonar' (sensor_msgs/Range)
  (:action connect-local_planner-scan-or-sonar-range_sensor-sick_tim571
    :parameters ()
    :precondition (and
      (filled base)
      (done localisation)
      (not (met local_planner scan-or-sonar))
      (uses range_sensor sick_tim571)
    )
    :effect (and
      (met local_planner scan-or-sonar)
      (increase (total-cost) 0)
    )
  )

  ;; SONAR_RING (range_sensor) meets local_planner's need for any one of topic 'scan' (sensor_msgs/LaserScan), topic 'sonar' (sensor_msgs/Range)
  (:action connect-local_planner-scan-or-sonar-range_sensor-sonar_ring
    :parameters ()
    :precondition (and
      (filled base)
      (done localisation)
      (not (met local_planner scan-or-sonar))
      (uses range_sensor sonar_ring)
    )
    :effect (and
      (met local_planner scan-or-sonar)
      (increase (total-cost) 0)
    )
  )

  ;; HOKUYO_UST10 (range_sensor) meets local_planner's need for topic 'scan' (sensor_msgs/LaserScan)
  (:action connect-local_planner-scan-range_sensor-hokuyo_ust10
    :parameters ()
    :precondition (and
      (filled base)
      (done localisation)
      (not (met local_planner scan))
      (uses range_sensor hokuyo_ust10)
    )
    :effect (and
      (met local_planner scan)
      (increase (total-cost) 0)
    )
  )

  ;; SICK_TIM571 (range_sensor) meets local_planner's need for topic 'scan' (sensor_msgs/LaserScan)
  (:action connect-local_planner-scan-range_sensor-sick_tim571
    :parameters ()
    :precondition (and
      (filled base)
      (done localisation)
      (not (met local_planner scan))
      (uses range_sensor sick_tim571)
    )
    :effect (and
      (met local_planner scan)
      (increase (total-cost) 0)
    )
  )

  ;; DWA_PLANNER (local_planner) meets base's need for topic 'cmd_vel' (geometry_msgs/Twist)
  (:action connect-base-cmd_vel-local_planner-dwa_planner
    :parameters ()
    :precondition (and
      (filled base)
      (done local_planner)
      (not (met base cmd_vel))
      (uses local_planner dwa_planner)
    )
    :effect (and
      (met base cmd_vel)
      (increase (total-cost) 0)
    )
  )

  ;; TEB_PLANNER (local_planner) meets base's need for topic 'cmd_vel' (geometry_msgs/Twist)
  (:action connect-base-cmd_vel-local_planner-teb_planner
    :parameters ()
    :precondition (and
      (filled base)
      (done local_planner)
      (not (met base cmd_vel))
      (uses local_planner teb_planner)
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
      (uses range_sensor hokuyo_ust10)
      (filled base)
    )
    :effect (and
      (done range_sensor)
      (increase (total-cost) 0)
    )
  )

  ;; SICK_TIM571 has all it requires and needs
  (:action finish-range_sensor-sick_tim571
    :parameters ()
    :precondition (and
      (uses range_sensor sick_tim571)
      (filled base)
    )
    :effect (and
      (done range_sensor)
      (increase (total-cost) 0)
    )
  )

  ;; SONAR_RING has all it requires and needs
  (:action finish-range_sensor-sonar_ring
    :parameters ()
    :precondition (and
      (uses range_sensor sonar_ring)
      (filled base)
    )
    :effect (and
      (done range_sensor)
      (increase (total-cost) 0)
    )
  )

  ;; WHEEL_ODOM has all it requires and needs
  (:action finish-odometry-wheel_odom
    :parameters ()
    :precondition (and
      (uses odometry wheel_odom)
      (filled base)
      (done range_sensor)
      (met odometry joint_states)
    )
    :effect (and
      (done odometry)
      (increase (total-cost) 0)
    )
  )

  ;; EKF_ODOM has all it requires and needs
  (:action finish-odometry-ekf_odom
    :parameters ()
    :precondition (and
      (uses odometry ekf_odom)
      (filled base)
      (done range_sensor)
      (met odometry joint_states)
    )
    :effect (and
      (done odometry)
      (increase (total-cost) 0)
    )
  )

  ;; AMCL has all it requires and needs
  (:action finish-localisation-amcl
    :parameters ()
    :precondition (and
      (uses localisation amcl)
      (filled base)
      (done odometry)
      (met localisation scan)
      (met localisation odom)
    )
    :effect (and
      (done localisation)
      (increase (total-cost) 0)
    )
  )

  ;; SLAM_TOOLBOX has all it requires and needs
  (:action finish-localisation-slam_toolbox
    :parameters ()
    :precondition (and
      (uses localisation slam_toolbox)
      (filled base)
      (done odometry)
      (met localisation scan)
      (met localisation odom)
    )
    :effect (and
      (done localisation)
      (increase (total-cost) 0)
    )
  )

  ;; DWA_PLANNER has all it requires and needs
  (:action finish-local_planner-dwa_planner
    :parameters ()
    :precondition (and
      (uses local_planner dwa_planner)
      (filled base)
      (done localisation)
      (met local_planner pose)
      (met local_planner scan-or-sonar)
    )
    :effect (and
      (done local_planner)
      (increase (total-cost) 0)
    )
  )

  ;; TEB_PLANNER has all it requires and needs
  (:action finish-local_planner-teb_planner
    :parameters ()
    :precondition (and
      (uses local_planner teb_planner)
      (filled base)
      (done localisation)
      (met local_planner pose)
      (met local_planner scan)
      (chosen ekf_odom)
    )
    :effect (and
      (done local_planner)
      (increase (total-cost) 0)
    )
  )

  ;; DIFF_DRIVE has all it requires and needs
  (:action finish-base-diff_drive
    :parameters ()
    :precondition (and
      (uses base diff_drive)
      (filled base)
      (done local_planner)
      (met base cmd_vel)
    )
    :effect (and
      (done base)
      (increase (total-cost) 0)
    )
  )

  ;; ROBOCLAW_BASE has all it requires and needs
  (:action finish-base-roboclaw_base
    :parameters ()
    :precondition (and
      (uses base roboclaw_base)
      (filled base)
      (done local_planner)
      (met base cmd_vel)
    )
    :effect (and
      (done base)
      (increase (total-cost) 0)
    )
  )
)

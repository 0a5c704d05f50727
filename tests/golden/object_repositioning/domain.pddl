;; rosreconf: Object Repositioning (object_repositioning), pre-grounded STRIPS with action costs.
;; choose-ROLE-COMPONENT fills a role (roles in schema order); connect-ROLE-REQUIREMENT-PROVIDERROLE
;; meets a requirement along an edge; finish-ROLE-COMPONENT checks requirements and couplings;
;; restart-ROLE-COMPONENT finishes a kept component that must restart to be rewired (one change).
;; Generated from the templates in rosreconf; see docs/pddl.md.
(define (domain rosreconf-object_repositioning)
  (:requirements :strips :typing :negative-preconditions :action-costs)
  (:types role component requirement)
  (:constants
    base_joint
    shoulder_joint
    elbow_joint
    wrist_joint
    gripper_joint
    camera
    gripper_sensor
    perception
    positioning
    grasping
    carrying
    placing
    reasoner
    - role
    nca1
    nca2
    nco1
    nco2
    ndc1
    ndc2
    ndc3
    ndc4
    ndc5
    nfb11
    nfb12
    nfb13
    nfb14
    nfb21
    nfb22
    nfb23
    nfb24
    nrea
    nsm1
    nsm2
    nsm3
    nsm4
    nsm5
    nvp1
    nvp2
    - component
    base__dc_servo_command
    base__dc_servo_command-or-base__digital_servo_command
    base__digital_servo_command
    camera_image
    elbow__dc_servo_command
    elbow__dc_servo_command-or-elbow__digital_servo_command
    elbow__digital_servo_command
    gripper__dc_servo_command
    gripper__dc_servo_command-or-gripper__digital_servo_command
    gripper__digital_servo_command
    gripper_feeling
    shoulder__dc_servo_command
    shoulder__dc_servo_command-or-shoulder__digital_servo_command
    shoulder__digital_servo_command
    visual_perception
    wrist__dc_servo_command
    wrist__dc_servo_command-or-wrist__digital_servo_command
    wrist__digital_servo_command
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

  ;; start NDC1 as base_joint
  (:action choose-base_joint-ndc1
    :parameters ()
    :precondition (and
      (choosing base_joint)
    )
    :effect (and
      (not (choosing base_joint))
      (choosing shoulder_joint)
      (uses base_joint ndc1)
      (serves base_joint positioning base__dc_servo_command)
      (serves base_joint grasping base__dc_servo_command)
      (serves base_joint carrying base__dc_servo_command)
      (serves base_joint placing base__dc_servo_command)
      (serves base_joint reasoner base__dc_servo_command-or-base__digital_servo_command)
      (increase (total-cost) 1)
    )
  )

  ;; keep NSM1 as base_joint
  (:action choose-base_joint-nsm1
    :parameters ()
    :precondition (and
      (choosing base_joint)
    )
    :effect (and
      (not (choosing base_joint))
      (choosing shoulder_joint)
      (uses base_joint nsm1)
      (serves base_joint positioning base__digital_servo_command)
      (serves base_joint grasping base__digital_servo_command)
      (serves base_joint carrying base__digital_servo_command)
      (serves base_joint placing base__digital_servo_command)
      (serves base_joint reasoner base__dc_servo_command-or-base__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; start NDC2 as shoulder_joint
  (:action choose-shoulder_joint-ndc2
    :parameters ()
    :precondition (and
      (choosing shoulder_joint)
    )
    :effect (and
      (not (choosing shoulder_joint))
      (choosing elbow_joint)
      (uses shoulder_joint ndc2)
      (serves shoulder_joint positioning shoulder__dc_servo_command)
      (serves shoulder_joint grasping shoulder__dc_servo_command)
      (serves shoulder_joint carrying shoulder__dc_servo_command)
      (serves shoulder_joint placing shoulder__dc_servo_command)
      (serves shoulder_joint reasoner shoulder__dc_servo_command-or-shoulder__digital_servo_command)
      (increase (total-cost) 1)
    )
  )

  ;; keep NSM2 as shoulder_joint
  (:action choose-shoulder_joint-nsm2
    :parameters ()
    :precondition (and
      (choosing shoulder_joint)
    )
    :effect (and
      (not (choosing shoulder_joint))
      (choosing elbow_joint)
      (uses shoulder_joint nsm2)
      (serves shoulder_joint positioning shoulder__digital_servo_command)
      (serves shoulder_joint grasping shoulder__digital_servo_command)
      (serves shoulder_joint carrying shoulder__digital_servo_command)
      (serves shoulder_joint placing shoulder__digital_servo_command)
      (serves shoulder_joint reasoner shoulder__dc_servo_command-or-shoulder__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; start NDC3 as elbow_joint
  (:action choose-elbow_joint-ndc3
    :parameters ()
    :precondition (and
      (choosing elbow_joint)
    )
    :effect (and
      (not (choosing elbow_joint))
      (choosing wrist_joint)
      (uses elbow_joint ndc3)
      (serves elbow_joint positioning elbow__dc_servo_command)
      (serves elbow_joint grasping elbow__dc_servo_command)
      (serves elbow_joint carrying elbow__dc_servo_command)
      (serves elbow_joint placing elbow__dc_servo_command)
      (serves elbow_joint reasoner elbow__dc_servo_command-or-elbow__digital_servo_command)
      (increase (total-cost) 1)
    )
  )

  ;; keep NSM3 as elbow_joint
  (:action choose-elbow_joint-nsm3
    :parameters ()
    :precondition (and
      (choosing elbow_joint)
    )
    :effect (and
      (not (choosing elbow_joint))
      (choosing wrist_joint)
      (uses elbow_joint nsm3)
      (serves elbow_joint positioning elbow__digital_servo_command)
      (serves elbow_joint grasping elbow__digital_servo_command)
      (serves elbow_joint carrying elbow__digital_servo_command)
      (serves elbow_joint placing elbow__digital_servo_command)
      (serves elbow_joint reasoner elbow__dc_servo_command-or-elbow__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; start NDC4 as wrist_joint
  (:action choose-wrist_joint-ndc4
    :parameters ()
    :precondition (and
      (choosing wrist_joint)
    )
    :effect (and
      (not (choosing wrist_joint))
      (choosing gripper_joint)
      (uses wrist_joint ndc4)
      (serves wrist_joint positioning wrist__dc_servo_command)
      (serves wrist_joint grasping wrist__dc_servo_command)
      (serves wrist_joint carrying wrist__dc_servo_command)
      (serves wrist_joint placing wrist__dc_servo_command)
      (serves wrist_joint reasoner wrist__dc_servo_command-or-wrist__digital_servo_command)
      (increase (total-cost) 1)
    )
  )

  ;; keep NSM4 as wrist_joint
  (:action choose-wrist_joint-nsm4
    :parameters ()
    :precondition (and
      (choosing wrist_joint)
    )
    :effect (and
      (not (choosing wrist_joint))
      (choosing gripper_joint)
      (uses wrist_joint nsm4)
      (serves wrist_joint positioning wrist__digital_servo_command)
      (serves wrist_joint grasping wrist__digital_servo_command)
      (serves wrist_joint carrying wrist__digital_servo_command)
      (serves wrist_joint placing wrist__digital_servo_command)
      (serves wrist_joint reasoner wrist__dc_servo_command-or-wrist__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; start NDC5 as gripper_joint
  (:action choose-gripper_joint-ndc5
    :parameters ()
    :precondition (and
      (choosing gripper_joint)
    )
    :effect (and
      (not (choosing gripper_joint))
      (choosing camera)
      (uses gripper_joint ndc5)
      (serves gripper_joint positioning gripper__dc_servo_command)
      (serves gripper_joint grasping gripper__dc_servo_command)
      (serves gripper_joint carrying gripper__dc_servo_command)
      (serves gripper_joint placing gripper__dc_servo_command)
      (serves gripper_joint reasoner gripper__dc_servo_command-or-gripper__digital_servo_command)
      (increase (total-cost) 1)
    )
  )

  ;; keep NSM5 as gripper_joint
  (:action choose-gripper_joint-nsm5
    :parameters ()
    :precondition (and
      (choosing gripper_joint)
    )
    :effect (and
      (not (choosing gripper_joint))
      (choosing camera)
      (uses gripper_joint nsm5)
      (serves gripper_joint positioning gripper__digital_servo_command)
      (serves gripper_joint grasping gripper__digital_servo_command)
      (serves gripper_joint carrying gripper__digital_servo_command)
      (serves gripper_joint placing gripper__digital_servo_command)
      (serves gripper_joint reasoner gripper__dc_servo_command-or-gripper__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; keep NCA1 as camera
  (:action choose-camera-nca1
    :parameters ()
    :precondition (and
      (choosing camera)
    )
    :effect (and
      (not (choosing camera))
      (choosing gripper_sensor)
      (uses camera nca1)
      (chosen nca1)
      (serves camera perception camera_image)
      (increase (total-cost) 0)
    )
  )

  ;; start NCA2 as camera
  (:action choose-camera-nca2
    :parameters ()
    :precondition (and
      (choosing camera)
    )
    :effect (and
      (not (choosing camera))
      (choosing gripper_sensor)
      (uses camera nca2)
      (chosen nca2)
      (serves camera perception camera_image)
      (increase (total-cost) 1)
    )
  )

  ;; keep NCO1 as gripper_sensor
  (:action choose-gripper_sensor-nco1
    :parameters ()
    :precondition (and
      (choosing gripper_sensor)
    )
    :effect (and
      (not (choosing gripper_sensor))
      (choosing perception)
      (uses gripper_sensor nco1)
      (chosen nco1)
      (serves gripper_sensor perception gripper_feeling)
      (serves gripper_sensor positioning gripper_feeling)
      (serves gripper_sensor grasping gripper_feeling)
      (serves gripper_sensor carrying gripper_feeling)
      (serves gripper_sensor placing gripper_feeling)
      (serves gripper_sensor reasoner gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; start NCO2 as gripper_sensor
  (:action choose-gripper_sensor-nco2
    :parameters ()
    :precondition (and
      (choosing gripper_sensor)
    )
    :effect (and
      (not (choosing gripper_sensor))
      (choosing perception)
      (uses gripper_sensor nco2)
      (chosen nco2)
      (serves gripper_sensor perception gripper_feeling)
      (serves gripper_sensor positioning gripper_feeling)
      (serves gripper_sensor grasping gripper_feeling)
      (serves gripper_sensor carrying gripper_feeling)
      (serves gripper_sensor placing gripper_feeling)
      (serves gripper_sensor reasoner gripper_feeling)
      (increase (total-cost) 1)
    )
  )

  ;; keep NVP1 as perception
  (:action choose-perception-nvp1
    :parameters ()
    :precondition (and
      (choosing perception)
    )
    :effect (and
      (not (choosing perception))
      (choosing positioning)
      (uses perception nvp1)
      (serves perception positioning visual_perception)
      (serves perception grasping visual_perception)
      (serves perception carrying visual_perception)
      (serves perception placing visual_perception)
      (serves perception reasoner visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; start NVP2 as perception
  (:action choose-perception-nvp2
    :parameters ()
    :precondition (and
      (choosing perception)
    )
    :effect (and
      (not (choosing perception))
      (choosing positioning)
      (uses perception nvp2)
      (serves perception positioning visual_perception)
      (serves perception grasping visual_perception)
      (serves perception carrying visual_perception)
      (serves perception placing visual_perception)
      (serves perception reasoner visual_perception)
      (increase (total-cost) 1)
    )
  )

  ;; start NFB11 as positioning
  (:action choose-positioning-nfb11
    :parameters ()
    :precondition (and
      (choosing positioning)
      (not (uses base_joint nsm1))
      (not (uses shoulder_joint nsm2))
      (not (uses elbow_joint nsm3))
      (not (uses wrist_joint nsm4))
      (not (uses gripper_joint nsm5))
    )
    :effect (and
      (not (choosing positioning))
      (choosing grasping)
      (uses positioning nfb11)
      (increase (total-cost) 1)
    )
  )

  ;; keep NFB21 as positioning
  (:action choose-positioning-nfb21
    :parameters ()
    :precondition (and
      (choosing positioning)
      (not (uses base_joint ndc1))
      (not (uses shoulder_joint ndc2))
      (not (uses elbow_joint ndc3))
      (not (uses wrist_joint ndc4))
      (not (uses gripper_joint ndc5))
    )
    :effect (and
      (not (choosing positioning))
      (choosing grasping)
      (uses positioning nfb21)
      (increase (total-cost) 0)
    )
  )

  ;; start NFB12 as grasping
  (:action choose-grasping-nfb12
    :parameters ()
    :precondition (and
      (choosing grasping)
      (not (uses base_joint nsm1))
      (not (uses shoulder_joint nsm2))
      (not (uses elbow_joint nsm3))
      (not (uses wrist_joint nsm4))
      (not (uses gripper_joint nsm5))
    )
    :effect (and
      (not (choosing grasping))
      (choosing carrying)
      (uses grasping nfb12)
      (increase (total-cost) 1)
    )
  )

  ;; keep NFB22 as grasping
  (:action choose-grasping-nfb22
    :parameters ()
    :precondition (and
      (choosing grasping)
      (not (uses base_joint ndc1))
      (not (uses shoulder_joint ndc2))
      (not (uses elbow_joint ndc3))
      (not (uses wrist_joint ndc4))
      (not (uses gripper_joint ndc5))
    )
    :effect (and
      (not (choosing grasping))
      (choosing carrying)
      (uses grasping nfb22)
      (increase (total-cost) 0)
    )
  )

  ;; start NFB13 as carrying
  (:action choose-carrying-nfb13
    :parameters ()
    :precondition (and
      (choosing carrying)
      (not (uses base_joint nsm1))
      (not (uses shoulder_joint nsm2))
      (not (uses elbow_joint nsm3))
      (not (uses wrist_joint nsm4))
      (not (uses gripper_joint nsm5))
    )
    :effect (and
      (not (choosing carrying))
      (choosing placing)
      (uses carrying nfb13)
      (increase (total-cost) 1)
    )
  )

  ;; keep NFB23 as carrying
  (:action choose-carrying-nfb23
    :parameters ()
    :precondition (and
      (choosing carrying)
      (not (uses base_joint ndc1))
      (not (uses shoulder_joint ndc2))
      (not (uses elbow_joint ndc3))
      (not (uses wrist_joint ndc4))
      (not (uses gripper_joint ndc5))
    )
    :effect (and
      (not (choosing carrying))
      (choosing placing)
      (uses carrying nfb23)
      (increase (total-cost) 0)
    )
  )

  ;; start NFB14 as placing
  (:action choose-placing-nfb14
    :parameters ()
    :precondition (and
      (choosing placing)
      (not (uses base_joint nsm1))
      (not (uses shoulder_joint nsm2))
      (not (uses elbow_joint nsm3))
      (not (uses wrist_joint nsm4))
      (not (uses gripper_joint nsm5))
    )
    :effect (and
      (not (choosing placing))
      (choosing reasoner)
      (uses placing nfb14)
      (increase (total-cost) 1)
    )
  )

  ;; keep NFB24 as placing
  (:action choose-placing-nfb24
    :parameters ()
    :precondition (and
      (choosing placing)
      (not (uses base_joint ndc1))
      (not (uses shoulder_joint ndc2))
      (not (uses elbow_joint ndc3))
      (not (uses wrist_joint ndc4))
      (not (uses gripper_joint ndc5))
    )
    :effect (and
      (not (choosing placing))
      (choosing reasoner)
      (uses placing nfb24)
      (increase (total-cost) 0)
    )
  )

  ;; keep NREA as reasoner
  (:action choose-reasoner-nrea
    :parameters ()
    :precondition (and
      (choosing reasoner)
    )
    :effect (and
      (not (choosing reasoner))
      (checking base_joint)
      (uses reasoner nrea)
      (increase (total-cost) 0)
    )
  )

  ;; camera meets perception's need for service 'camera_image' (robot_arm_msgs/CameraImage)
  (:action connect-perception-camera_image-camera
    :parameters ()
    :precondition (and
      (checking perception)
      (not (met perception camera_image))
      (serves camera perception camera_image)
    )
    :effect (and
      (met perception camera_image)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_sensor meets perception's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-perception-gripper_feeling-gripper_sensor
    :parameters ()
    :precondition (and
      (checking perception)
      (not (met perception gripper_feeling))
      (serves gripper_sensor perception gripper_feeling)
    )
    :effect (and
      (met perception gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_sensor meets positioning's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-positioning-gripper_feeling-gripper_sensor
    :parameters ()
    :precondition (and
      (checking positioning)
      (not (met positioning gripper_feeling))
      (serves gripper_sensor positioning gripper_feeling)
    )
    :effect (and
      (met positioning gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; perception meets positioning's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-positioning-visual_perception-perception
    :parameters ()
    :precondition (and
      (checking positioning)
      (not (met positioning visual_perception))
      (serves perception positioning visual_perception)
    )
    :effect (and
      (met positioning visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; base_joint meets positioning's need for service 'base/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-positioning-base__dc_servo_command-base_joint
    :parameters ()
    :precondition (and
      (checking positioning)
      (not (met positioning base__dc_servo_command))
      (serves base_joint positioning base__dc_servo_command)
    )
    :effect (and
      (met positioning base__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; shoulder_joint meets positioning's need for service 'shoulder/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-positioning-shoulder__dc_servo_command-shoulder_joint
    :parameters ()
    :precondition (and
      (checking positioning)
      (not (met positioning shoulder__dc_servo_command))
      (serves shoulder_joint positioning shoulder__dc_servo_command)
    )
    :effect (and
      (met positioning shoulder__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; elbow_joint meets positioning's need for service 'elbow/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-positioning-elbow__dc_servo_command-elbow_joint
    :parameters ()
    :precondition (and
      (checking positioning)
      (not (met positioning elbow__dc_servo_command))
      (serves elbow_joint positioning elbow__dc_servo_command)
    )
    :effect (and
      (met positioning elbow__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; wrist_joint meets positioning's need for service 'wrist/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-positioning-wrist__dc_servo_command-wrist_joint
    :parameters ()
    :precondition (and
      (checking positioning)
      (not (met positioning wrist__dc_servo_command))
      (serves wrist_joint positioning wrist__dc_servo_command)
    )
    :effect (and
      (met positioning wrist__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_joint meets positioning's need for service 'gripper/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-positioning-gripper__dc_servo_command-gripper_joint
    :parameters ()
    :precondition (and
      (checking positioning)
      (not (met positioning gripper__dc_servo_command))
      (serves gripper_joint positioning gripper__dc_servo_command)
    )
    :effect (and
      (met positioning gripper__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; base_joint meets positioning's need for service 'base/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-positioning-base__digital_servo_command-base_joint
    :parameters ()
    :precondition (and
      (checking positioning)
      (not (met positioning base__digital_servo_command))
      (serves base_joint positioning base__digital_servo_command)
    )
    :effect (and
      (met positioning base__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; shoulder_joint meets positioning's need for service 'shoulder/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-positioning-shoulder__digital_servo_command-shoulder_joint
    :parameters ()
    :precondition (and
      (checking positioning)
      (not (met positioning shoulder__digital_servo_command))
      (serves shoulder_joint positioning shoulder__digital_servo_command)
    )
    :effect (and
      (met positioning shoulder__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; elbow_joint meets positioning's need for service 'elbow/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-positioning-elbow__digital_servo_command-elbow_joint
    :parameters ()
    :precondition (and
      (checking positioning)
      (not (met positioning elbow__digital_servo_command))
      (serves elbow_joint positioning elbow__digital_servo_command)
    )
    :effect (and
      (met positioning elbow__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; wrist_joint meets positioning's need for service 'wrist/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-positioning-wrist__digital_servo_command-wrist_joint
    :parameters ()
    :precondition (and
      (checking positioning)
      (not (met positioning wrist__digital_servo_command))
      (serves wrist_joint positioning wrist__digital_servo_command)
    )
    :effect (and
      (met positioning wrist__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_joint meets positioning's need for service 'gripper/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-positioning-gripper__digital_servo_command-gripper_joint
    :parameters ()
    :precondition (and
      (checking positioning)
      (not (met positioning gripper__digital_servo_command))
      (serves gripper_joint positioning gripper__digital_servo_command)
    )
    :effect (and
      (met positioning gripper__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_sensor meets grasping's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-grasping-gripper_feeling-gripper_sensor
    :parameters ()
    :precondition (and
      (checking grasping)
      (not (met grasping gripper_feeling))
      (serves gripper_sensor grasping gripper_feeling)
    )
    :effect (and
      (met grasping gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; perception meets grasping's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-grasping-visual_perception-perception
    :parameters ()
    :precondition (and
      (checking grasping)
      (not (met grasping visual_perception))
      (serves perception grasping visual_perception)
    )
    :effect (and
      (met grasping visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; base_joint meets grasping's need for service 'base/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-grasping-base__dc_servo_command-base_joint
    :parameters ()
    :precondition (and
      (checking grasping)
      (not (met grasping base__dc_servo_command))
      (serves base_joint grasping base__dc_servo_command)
    )
    :effect (and
      (met grasping base__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; shoulder_joint meets grasping's need for service 'shoulder/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-grasping-shoulder__dc_servo_command-shoulder_joint
    :parameters ()
    :precondition (and
      (checking grasping)
      (not (met grasping shoulder__dc_servo_command))
      (serves shoulder_joint grasping shoulder__dc_servo_command)
    )
    :effect (and
      (met grasping shoulder__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; elbow_joint meets grasping's need for service 'elbow/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-grasping-elbow__dc_servo_command-elbow_joint
    :parameters ()
    :precondition (and
      (checking grasping)
      (not (met grasping elbow__dc_servo_command))
      (serves elbow_joint grasping elbow__dc_servo_command)
    )
    :effect (and
      (met grasping elbow__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; wrist_joint meets grasping's need for service 'wrist/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-grasping-wrist__dc_servo_command-wrist_joint
    :parameters ()
    :precondition (and
      (checking grasping)
      (not (met grasping wrist__dc_servo_command))
      (serves wrist_joint grasping wrist__dc_servo_command)
    )
    :effect (and
      (met grasping wrist__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_joint meets grasping's need for service 'gripper/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-grasping-gripper__dc_servo_command-gripper_joint
    :parameters ()
    :precondition (and
      (checking grasping)
      (not (met grasping gripper__dc_servo_command))
      (serves gripper_joint grasping gripper__dc_servo_command)
    )
    :effect (and
      (met grasping gripper__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; base_joint meets grasping's need for service 'base/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-grasping-base__digital_servo_command-base_joint
    :parameters ()
    :precondition (and
      (checking grasping)
      (not (met grasping base__digital_servo_command))
      (serves base_joint grasping base__digital_servo_command)
    )
    :effect (and
      (met grasping base__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; shoulder_joint meets grasping's need for service 'shoulder/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-grasping-shoulder__digital_servo_command-shoulder_joint
    :parameters ()
    :precondition (and
      (checking grasping)
      (not (met grasping shoulder__digital_servo_command))
      (serves shoulder_joint grasping shoulder__digital_servo_command)
    )
    :effect (and
      (met grasping shoulder__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; elbow_joint meets grasping's need for service 'elbow/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-grasping-elbow__digital_servo_command-elbow_joint
    :parameters ()
    :precondition (and
      (checking grasping)
      (not (met grasping elbow__digital_servo_command))
      (serves elbow_joint grasping elbow__digital_servo_command)
    )
    :effect (and
      (met grasping elbow__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; wrist_joint meets grasping's need for service 'wrist/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-grasping-wrist__digital_servo_command-wrist_joint
    :parameters ()
    :precondition (and
      (checking grasping)
      (not (met grasping wrist__digital_servo_command))
      (serves wrist_joint grasping wrist__digital_servo_command)
    )
    :effect (and
      (met grasping wrist__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_joint meets grasping's need for service 'gripper/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-grasping-gripper__digital_servo_command-gripper_joint
    :parameters ()
    :precondition (and
      (checking grasping)
      (not (met grasping gripper__digital_servo_command))
      (serves gripper_joint grasping gripper__digital_servo_command)
    )
    :effect (and
      (met grasping gripper__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_sensor meets carrying's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-carrying-gripper_feeling-gripper_sensor
    :parameters ()
    :precondition (and
      (checking carrying)
      (not (met carrying gripper_feeling))
      (serves gripper_sensor carrying gripper_feeling)
    )
    :effect (and
      (met carrying gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; perception meets carrying's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-carrying-visual_perception-perception
    :parameters ()
    :precondition (and
      (checking carrying)
      (not (met carrying visual_perception))
      (serves perception carrying visual_perception)
    )
    :effect (and
      (met carrying visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; base_joint meets carrying's need for service 'base/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-carrying-base__dc_servo_command-base_joint
    :parameters ()
    :precondition (and
      (checking carrying)
      (not (met carrying base__dc_servo_command))
      (serves base_joint carrying base__dc_servo_command)
    )
    :effect (and
      (met carrying base__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; shoulder_joint meets carrying's need for service 'shoulder/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-carrying-shoulder__dc_servo_command-shoulder_joint
    :parameters ()
    :precondition (and
      (checking carrying)
      (not (met carrying shoulder__dc_servo_command))
      (serves shoulder_joint carrying shoulder__dc_servo_command)
    )
    :effect (and
      (met carrying shoulder__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; elbow_joint meets carrying's need for service 'elbow/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-carrying-elbow__dc_servo_command-elbow_joint
    :parameters ()
    :precondition (and
      (checking carrying)
      (not (met carrying elbow__dc_servo_command))
      (serves elbow_joint carrying elbow__dc_servo_command)
    )
    :effect (and
      (met carrying elbow__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; wrist_joint meets carrying's need for service 'wrist/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-carrying-wrist__dc_servo_command-wrist_joint
    :parameters ()
    :precondition (and
      (checking carrying)
      (not (met carrying wrist__dc_servo_command))
      (serves wrist_joint carrying wrist__dc_servo_command)
    )
    :effect (and
      (met carrying wrist__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_joint meets carrying's need for service 'gripper/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-carrying-gripper__dc_servo_command-gripper_joint
    :parameters ()
    :precondition (and
      (checking carrying)
      (not (met carrying gripper__dc_servo_command))
      (serves gripper_joint carrying gripper__dc_servo_command)
    )
    :effect (and
      (met carrying gripper__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; base_joint meets carrying's need for service 'base/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-carrying-base__digital_servo_command-base_joint
    :parameters ()
    :precondition (and
      (checking carrying)
      (not (met carrying base__digital_servo_command))
      (serves base_joint carrying base__digital_servo_command)
    )
    :effect (and
      (met carrying base__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; shoulder_joint meets carrying's need for service 'shoulder/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-carrying-shoulder__digital_servo_command-shoulder_joint
    :parameters ()
    :precondition (and
      (checking carrying)
      (not (met carrying shoulder__digital_servo_command))
      (serves shoulder_joint carrying shoulder__digital_servo_command)
    )
    :effect (and
      (met carrying shoulder__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; elbow_joint meets carrying's need for service 'elbow/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-carrying-elbow__digital_servo_command-elbow_joint
    :parameters ()
    :precondition (and
      (checking carrying)
      (not (met carrying elbow__digital_servo_command))
      (serves elbow_joint carrying elbow__digital_servo_command)
    )
    :effect (and
      (met carrying elbow__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; wrist_joint meets carrying's need for service 'wrist/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-carrying-wrist__digital_servo_command-wrist_joint
    :parameters ()
    :precondition (and
      (checking carrying)
      (not (met carrying wrist__digital_servo_command))
      (serves wrist_joint carrying wrist__digital_servo_command)
    )
    :effect (and
      (met carrying wrist__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_joint meets carrying's need for service 'gripper/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-carrying-gripper__digital_servo_command-gripper_joint
    :parameters ()
    :precondition (and
      (checking carrying)
      (not (met carrying gripper__digital_servo_command))
      (serves gripper_joint carrying gripper__digital_servo_command)
    )
    :effect (and
      (met carrying gripper__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_sensor meets placing's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-placing-gripper_feeling-gripper_sensor
    :parameters ()
    :precondition (and
      (checking placing)
      (not (met placing gripper_feeling))
      (serves gripper_sensor placing gripper_feeling)
    )
    :effect (and
      (met placing gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; perception meets placing's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-placing-visual_perception-perception
    :parameters ()
    :precondition (and
      (checking placing)
      (not (met placing visual_perception))
      (serves perception placing visual_perception)
    )
    :effect (and
      (met placing visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; base_joint meets placing's need for service 'base/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-placing-base__dc_servo_command-base_joint
    :parameters ()
    :precondition (and
      (checking placing)
      (not (met placing base__dc_servo_command))
      (serves base_joint placing base__dc_servo_command)
    )
    :effect (and
      (met placing base__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; shoulder_joint meets placing's need for service 'shoulder/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-placing-shoulder__dc_servo_command-shoulder_joint
    :parameters ()
    :precondition (and
      (checking placing)
      (not (met placing shoulder__dc_servo_command))
      (serves shoulder_joint placing shoulder__dc_servo_command)
    )
    :effect (and
      (met placing shoulder__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; elbow_joint meets placing's need for service 'elbow/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-placing-elbow__dc_servo_command-elbow_joint
    :parameters ()
    :precondition (and
      (checking placing)
      (not (met placing elbow__dc_servo_command))
      (serves elbow_joint placing elbow__dc_servo_command)
    )
    :effect (and
      (met placing elbow__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; wrist_joint meets placing's need for service 'wrist/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-placing-wrist__dc_servo_command-wrist_joint
    :parameters ()
    :precondition (and
      (checking placing)
      (not (met placing wrist__dc_servo_command))
      (serves wrist_joint placing wrist__dc_servo_command)
    )
    :effect (and
      (met placing wrist__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_joint meets placing's need for service 'gripper/dc_servo_command' (robot_arm_msgs/DcServoCommand)
  (:action connect-placing-gripper__dc_servo_command-gripper_joint
    :parameters ()
    :precondition (and
      (checking placing)
      (not (met placing gripper__dc_servo_command))
      (serves gripper_joint placing gripper__dc_servo_command)
    )
    :effect (and
      (met placing gripper__dc_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; base_joint meets placing's need for service 'base/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-placing-base__digital_servo_command-base_joint
    :parameters ()
    :precondition (and
      (checking placing)
      (not (met placing base__digital_servo_command))
      (serves base_joint placing base__digital_servo_command)
    )
    :effect (and
      (met placing base__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; shoulder_joint meets placing's need for service 'shoulder/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-placing-shoulder__digital_servo_command-shoulder_joint
    :parameters ()
    :precondition (and
      (checking placing)
      (not (met placing shoulder__digital_servo_command))
      (serves shoulder_joint placing shoulder__digital_servo_command)
    )
    :effect (and
      (met placing shoulder__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; elbow_joint meets placing's need for service 'elbow/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-placing-elbow__digital_servo_command-elbow_joint
    :parameters ()
    :precondition (and
      (checking placing)
      (not (met placing elbow__digital_servo_command))
      (serves elbow_joint placing elbow__digital_servo_command)
    )
    :effect (and
      (met placing elbow__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; wrist_joint meets placing's need for service 'wrist/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-placing-wrist__digital_servo_command-wrist_joint
    :parameters ()
    :precondition (and
      (checking placing)
      (not (met placing wrist__digital_servo_command))
      (serves wrist_joint placing wrist__digital_servo_command)
    )
    :effect (and
      (met placing wrist__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_joint meets placing's need for service 'gripper/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-placing-gripper__digital_servo_command-gripper_joint
    :parameters ()
    :precondition (and
      (checking placing)
      (not (met placing gripper__digital_servo_command))
      (serves gripper_joint placing gripper__digital_servo_command)
    )
    :effect (and
      (met placing gripper__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; perception meets reasoner's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-reasoner-visual_perception-perception
    :parameters ()
    :precondition (and
      (checking reasoner)
      (not (met reasoner visual_perception))
      (serves perception reasoner visual_perception)
    )
    :effect (and
      (met reasoner visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_sensor meets reasoner's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-reasoner-gripper_feeling-gripper_sensor
    :parameters ()
    :precondition (and
      (checking reasoner)
      (not (met reasoner gripper_feeling))
      (serves gripper_sensor reasoner gripper_feeling)
    )
    :effect (and
      (met reasoner gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; base_joint meets reasoner's need for any one of service 'base/dc_servo_command' (robot_arm_msgs/DcServoCommand), service 'base/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-reasoner-base__dc_servo_command-or-base__digital_servo_command-base_joint
    :parameters ()
    :precondition (and
      (checking reasoner)
      (not (met reasoner base__dc_servo_command-or-base__digital_servo_command))
      (serves base_joint reasoner base__dc_servo_command-or-base__digital_servo_command)
    )
    :effect (and
      (met reasoner base__dc_servo_command-or-base__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; shoulder_joint meets reasoner's need for any one of service 'shoulder/dc_servo_command' (robot_arm_msgs/DcServoCommand), service 'shoulder/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-reasoner-shoulder__dc_servo_command-or-shoulder__digital_servo_command-shoulder_joint
    :parameters ()
    :precondition (and
      (checking reasoner)
      (not (met reasoner shoulder__dc_servo_command-or-shoulder__digital_servo_command))
      (serves shoulder_joint reasoner shoulder__dc_servo_command-or-shoulder__digital_servo_command)
    )
    :effect (and
      (met reasoner shoulder__dc_servo_command-or-shoulder__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; elbow_joint meets reasoner's need for any one of service 'elbow/dc_servo_command' (robot_arm_msgs/DcServoCommand), service 'elbow/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-reasoner-elbow__dc_servo_command-or-elbow__digital_servo_command-elbow_joint
    :parameters ()
    :precondition (and
      (checking reasoner)
      (not (met reasoner elbow__dc_servo_command-or-elbow__digital_servo_command))
      (serves elbow_joint reasoner elbow__dc_servo_command-or-elbow__digital_servo_command)
    )
    :effect (and
      (met reasoner elbow__dc_servo_command-or-elbow__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; wrist_joint meets reasoner's need for any one of service 'wrist/dc_servo_command' (robot_arm_msgs/DcServoCommand), service 'wrist/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-reasoner-wrist__dc_servo_command-or-wrist__digital_servo_command-wrist_joint
    :parameters ()
    :precondition (and
      (checking reasoner)
      (not (met reasoner wrist__dc_servo_command-or-wrist__digital_servo_command))
      (serves wrist_joint reasoner wrist__dc_servo_command-or-wrist__digital_servo_command)
    )
    :effect (and
      (met reasoner wrist__dc_servo_command-or-wrist__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; gripper_joint meets reasoner's need for any one of service 'gripper/dc_servo_command' (robot_arm_msgs/DcServoCommand), service 'gripper/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-reasoner-gripper__dc_servo_command-or-gripper__digital_servo_command-gripper_joint
    :parameters ()
    :precondition (and
      (checking reasoner)
      (not (met reasoner gripper__dc_servo_command-or-gripper__digital_servo_command))
      (serves gripper_joint reasoner gripper__dc_servo_command-or-gripper__digital_servo_command)
    )
    :effect (and
      (met reasoner gripper__dc_servo_command-or-gripper__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NDC1 has all it requires and needs
  (:action finish-base_joint-ndc1
    :parameters ()
    :precondition (and
      (checking base_joint)
      (uses base_joint ndc1)
    )
    :effect (and
      (not (checking base_joint))
      (checking shoulder_joint)
      (increase (total-cost) 0)
    )
  )

  ;; NSM1 has all it requires and needs
  (:action finish-base_joint-nsm1
    :parameters ()
    :precondition (and
      (checking base_joint)
      (uses base_joint nsm1)
    )
    :effect (and
      (not (checking base_joint))
      (checking shoulder_joint)
      (increase (total-cost) 0)
    )
  )

  ;; NDC2 has all it requires and needs
  (:action finish-shoulder_joint-ndc2
    :parameters ()
    :precondition (and
      (checking shoulder_joint)
      (uses shoulder_joint ndc2)
    )
    :effect (and
      (not (checking shoulder_joint))
      (checking elbow_joint)
      (increase (total-cost) 0)
    )
  )

  ;; NSM2 has all it requires and needs
  (:action finish-shoulder_joint-nsm2
    :parameters ()
    :precondition (and
      (checking shoulder_joint)
      (uses shoulder_joint nsm2)
    )
    :effect (and
      (not (checking shoulder_joint))
      (checking elbow_joint)
      (increase (total-cost) 0)
    )
  )

  ;; NDC3 has all it requires and needs
  (:action finish-elbow_joint-ndc3
    :parameters ()
    :precondition (and
      (checking elbow_joint)
      (uses elbow_joint ndc3)
    )
    :effect (and
      (not (checking elbow_joint))
      (checking wrist_joint)
      (increase (total-cost) 0)
    )
  )

  ;; NSM3 has all it requires and needs
  (:action finish-elbow_joint-nsm3
    :parameters ()
    :precondition (and
      (checking elbow_joint)
      (uses elbow_joint nsm3)
    )
    :effect (and
      (not (checking elbow_joint))
      (checking wrist_joint)
      (increase (total-cost) 0)
    )
  )

  ;; NDC4 has all it requires and needs
  (:action finish-wrist_joint-ndc4
    :parameters ()
    :precondition (and
      (checking wrist_joint)
      (uses wrist_joint ndc4)
    )
    :effect (and
      (not (checking wrist_joint))
      (checking gripper_joint)
      (increase (total-cost) 0)
    )
  )

  ;; NSM4 has all it requires and needs
  (:action finish-wrist_joint-nsm4
    :parameters ()
    :precondition (and
      (checking wrist_joint)
      (uses wrist_joint nsm4)
    )
    :effect (and
      (not (checking wrist_joint))
      (checking gripper_joint)
      (increase (total-cost) 0)
    )
  )

  ;; NDC5 has all it requires and needs
  (:action finish-gripper_joint-ndc5
    :parameters ()
    :precondition (and
      (checking gripper_joint)
      (uses gripper_joint ndc5)
    )
    :effect (and
      (not (checking gripper_joint))
      (checking camera)
      (increase (total-cost) 0)
    )
  )

  ;; NSM5 has all it requires and needs
  (:action finish-gripper_joint-nsm5
    :parameters ()
    :precondition (and
      (checking gripper_joint)
      (uses gripper_joint nsm5)
    )
    :effect (and
      (not (checking gripper_joint))
      (checking camera)
      (increase (total-cost) 0)
    )
  )

  ;; NCA1 has all it requires and needs
  (:action finish-camera-nca1
    :parameters ()
    :precondition (and
      (checking camera)
      (uses camera nca1)
    )
    :effect (and
      (not (checking camera))
      (checking gripper_sensor)
      (increase (total-cost) 0)
    )
  )

  ;; NCA2 has all it requires and needs
  (:action finish-camera-nca2
    :parameters ()
    :precondition (and
      (checking camera)
      (uses camera nca2)
    )
    :effect (and
      (not (checking camera))
      (checking gripper_sensor)
      (increase (total-cost) 0)
    )
  )

  ;; NCO1 has all it requires and needs
  (:action finish-gripper_sensor-nco1
    :parameters ()
    :precondition (and
      (checking gripper_sensor)
      (uses gripper_sensor nco1)
    )
    :effect (and
      (not (checking gripper_sensor))
      (checking perception)
      (increase (total-cost) 0)
    )
  )

  ;; NCO2 has all it requires and needs
  (:action finish-gripper_sensor-nco2
    :parameters ()
    :precondition (and
      (checking gripper_sensor)
      (uses gripper_sensor nco2)
    )
    :effect (and
      (not (checking gripper_sensor))
      (checking perception)
      (increase (total-cost) 0)
    )
  )

  ;; NVP1 has all it requires and needs
  (:action finish-perception-nvp1
    :parameters ()
    :precondition (and
      (checking perception)
      (uses perception nvp1)
      (met perception camera_image)
      (met perception gripper_feeling)
      (chosen nca1)
      (chosen nco1)
    )
    :effect (and
      (not (checking perception))
      (checking positioning)
      (increase (total-cost) 0)
    )
  )

  ;; NVP2 has all it requires and needs
  (:action finish-perception-nvp2
    :parameters ()
    :precondition (and
      (checking perception)
      (uses perception nvp2)
      (met perception camera_image)
      (met perception gripper_feeling)
      (chosen nca2)
      (chosen nco2)
    )
    :effect (and
      (not (checking perception))
      (checking positioning)
      (increase (total-cost) 0)
    )
  )

  ;; NFB11 has all it requires and needs
  (:action finish-positioning-nfb11
    :parameters ()
    :precondition (and
      (checking positioning)
      (uses positioning nfb11)
      (met positioning gripper_feeling)
      (met positioning visual_perception)
      (met positioning base__dc_servo_command)
      (met positioning shoulder__dc_servo_command)
      (met positioning elbow__dc_servo_command)
      (met positioning wrist__dc_servo_command)
      (met positioning gripper__dc_servo_command)
    )
    :effect (and
      (not (checking positioning))
      (checking grasping)
      (increase (total-cost) 0)
    )
  )

  ;; NFB21 has all it requires and needs
  (:action finish-positioning-nfb21
    :parameters ()
    :precondition (and
      (checking positioning)
      (uses positioning nfb21)
      (met positioning gripper_feeling)
      (met positioning visual_perception)
      (met positioning base__digital_servo_command)
      (met positioning shoulder__digital_servo_command)
      (met positioning elbow__digital_servo_command)
      (met positioning wrist__digital_servo_command)
      (met positioning gripper__digital_servo_command)
    )
    :effect (and
      (not (checking positioning))
      (checking grasping)
      (increase (total-cost) 0)
    )
  )

  ;; NFB12 has all it requires and needs
  (:action finish-grasping-nfb12
    :parameters ()
    :precondition (and
      (checking grasping)
      (uses grasping nfb12)
      (met grasping gripper_feeling)
      (met grasping visual_perception)
      (met grasping base__dc_servo_command)
      (met grasping shoulder__dc_servo_command)
      (met grasping elbow__dc_servo_command)
      (met grasping wrist__dc_servo_command)
      (met grasping gripper__dc_servo_command)
    )
    :effect (and
      (not (checking grasping))
      (checking carrying)
      (increase (total-cost) 0)
    )
  )

  ;; NFB22 has all it requires and needs
  (:action finish-grasping-nfb22
    :parameters ()
    :precondition (and
      (checking grasping)
      (uses grasping nfb22)
      (met grasping gripper_feeling)
      (met grasping visual_perception)
      (met grasping base__digital_servo_command)
      (met grasping shoulder__digital_servo_command)
      (met grasping elbow__digital_servo_command)
      (met grasping wrist__digital_servo_command)
      (met grasping gripper__digital_servo_command)
    )
    :effect (and
      (not (checking grasping))
      (checking carrying)
      (increase (total-cost) 0)
    )
  )

  ;; NFB13 has all it requires and needs
  (:action finish-carrying-nfb13
    :parameters ()
    :precondition (and
      (checking carrying)
      (uses carrying nfb13)
      (met carrying gripper_feeling)
      (met carrying visual_perception)
      (met carrying base__dc_servo_command)
      (met carrying shoulder__dc_servo_command)
      (met carrying elbow__dc_servo_command)
      (met carrying wrist__dc_servo_command)
      (met carrying gripper__dc_servo_command)
    )
    :effect (and
      (not (checking carrying))
      (checking placing)
      (increase (total-cost) 0)
    )
  )

  ;; NFB23 has all it requires and needs
  (:action finish-carrying-nfb23
    :parameters ()
    :precondition (and
      (checking carrying)
      (uses carrying nfb23)
      (met carrying gripper_feeling)
      (met carrying visual_perception)
      (met carrying base__digital_servo_command)
      (met carrying shoulder__digital_servo_command)
      (met carrying elbow__digital_servo_command)
      (met carrying wrist__digital_servo_command)
      (met carrying gripper__digital_servo_command)
    )
    :effect (and
      (not (checking carrying))
      (checking placing)
      (increase (total-cost) 0)
    )
  )

  ;; NFB14 has all it requires and needs
  (:action finish-placing-nfb14
    :parameters ()
    :precondition (and
      (checking placing)
      (uses placing nfb14)
      (met placing gripper_feeling)
      (met placing visual_perception)
      (met placing base__dc_servo_command)
      (met placing shoulder__dc_servo_command)
      (met placing elbow__dc_servo_command)
      (met placing wrist__dc_servo_command)
      (met placing gripper__dc_servo_command)
    )
    :effect (and
      (not (checking placing))
      (checking reasoner)
      (increase (total-cost) 0)
    )
  )

  ;; NFB24 has all it requires and needs
  (:action finish-placing-nfb24
    :parameters ()
    :precondition (and
      (checking placing)
      (uses placing nfb24)
      (met placing gripper_feeling)
      (met placing visual_perception)
      (met placing base__digital_servo_command)
      (met placing shoulder__digital_servo_command)
      (met placing elbow__digital_servo_command)
      (met placing wrist__digital_servo_command)
      (met placing gripper__digital_servo_command)
    )
    :effect (and
      (not (checking placing))
      (checking reasoner)
      (increase (total-cost) 0)
    )
  )

  ;; NREA has all it requires and needs
  (:action finish-reasoner-nrea
    :parameters ()
    :precondition (and
      (checking reasoner)
      (uses reasoner nrea)
      (met reasoner visual_perception)
      (met reasoner gripper_feeling)
      (met reasoner base__dc_servo_command-or-base__digital_servo_command)
      (met reasoner shoulder__dc_servo_command-or-shoulder__digital_servo_command)
      (met reasoner elbow__dc_servo_command-or-elbow__digital_servo_command)
      (met reasoner wrist__dc_servo_command-or-wrist__digital_servo_command)
      (met reasoner gripper__dc_servo_command-or-gripper__digital_servo_command)
    )
    :effect (and
      (not (checking reasoner))
      (finished)
      (increase (total-cost) 0)
    )
  )
)

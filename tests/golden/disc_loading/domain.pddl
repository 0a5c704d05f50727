;; rosreconf: Disc Loading (disc_loading), pre-grounded STRIPS with action costs.
;; choose-ROLE-COMPONENT fills a role; connect-ROLE-REQUIREMENT-PROVIDERROLE-PROVIDER meets a
;; requirement along an edge; finish-ROLE-COMPONENT checks requirements and couplings.
;; Generated from the templates in rosreconf; see docs/pddl.md.
(define (domain rosreconf-disc_loading)
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
    base__dc_servo_command-or-base__digital_servo_command
    base__digital_servo_command
    camera_image
    elbow__dc_servo_command-or-elbow__digital_servo_command
    elbow__digital_servo_command
    gripper__dc_servo_command-or-gripper__digital_servo_command
    gripper__digital_servo_command
    gripper_feeling
    shoulder__dc_servo_command-or-shoulder__digital_servo_command
    shoulder__digital_servo_command
    visual_perception
    wrist__dc_servo_command-or-wrist__digital_servo_command
    wrist__digital_servo_command
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

  ;; keep NSM1 as base_joint
  (:action choose-base_joint-nsm1
    :parameters ()
    :precondition (and
      (not (filled base_joint))
      (not (chosen nsm1))
    )
    :effect (and
      (filled base_joint)
      (uses base_joint nsm1)
      (chosen nsm1)
      (increase (total-cost) 0)
    )
  )

  ;; keep NSM2 as shoulder_joint
  (:action choose-shoulder_joint-nsm2
    :parameters ()
    :precondition (and
      (not (filled shoulder_joint))
      (not (chosen nsm2))
      (filled base_joint)
    )
    :effect (and
      (filled shoulder_joint)
      (uses shoulder_joint nsm2)
      (chosen nsm2)
      (increase (total-cost) 0)
    )
  )

  ;; keep NSM3 as elbow_joint
  (:action choose-elbow_joint-nsm3
    :parameters ()
    :precondition (and
      (not (filled elbow_joint))
      (not (chosen nsm3))
      (filled shoulder_joint)
    )
    :effect (and
      (filled elbow_joint)
      (uses elbow_joint nsm3)
      (chosen nsm3)
      (increase (total-cost) 0)
    )
  )

  ;; keep NSM4 as wrist_joint
  (:action choose-wrist_joint-nsm4
    :parameters ()
    :precondition (and
      (not (filled wrist_joint))
      (not (chosen nsm4))
      (filled elbow_joint)
    )
    :effect (and
      (filled wrist_joint)
      (uses wrist_joint nsm4)
      (chosen nsm4)
      (increase (total-cost) 0)
    )
  )

  ;; keep NSM5 as gripper_joint
  (:action choose-gripper_joint-nsm5
    :parameters ()
    :precondition (and
      (not (filled gripper_joint))
      (not (chosen nsm5))
      (filled wrist_joint)
    )
    :effect (and
      (filled gripper_joint)
      (uses gripper_joint nsm5)
      (chosen nsm5)
      (increase (total-cost) 0)
    )
  )

  ;; keep NCA1 as camera
  (:action choose-camera-nca1
    :parameters ()
    :precondition (and
      (not (filled camera))
      (not (chosen nca1))
      (filled gripper_joint)
    )
    :effect (and
      (filled camera)
      (uses camera nca1)
      (chosen nca1)
      (increase (total-cost) 0)
    )
  )

  ;; start NCA2 as camera
  (:action choose-camera-nca2
    :parameters ()
    :precondition (and
      (not (filled camera))
      (not (chosen nca2))
      (filled gripper_joint)
    )
    :effect (and
      (filled camera)
      (uses camera nca2)
      (chosen nca2)
      (increase (total-cost) 1)
    )
  )

  ;; keep NCO1 as gripper_sensor
  (:action choose-gripper_sensor-nco1
    :parameters ()
    :precondition (and
      (not (filled gripper_sensor))
      (not (chosen nco1))
      (filled camera)
    )
    :effect (and
      (filled gripper_sensor)
      (uses gripper_sensor nco1)
      (chosen nco1)
      (increase (total-cost) 0)
    )
  )

  ;; start NCO2 as gripper_sensor
  (:action choose-gripper_sensor-nco2
    :parameters ()
    :precondition (and
      (not (filled gripper_sensor))
      (not (chosen nco2))
      (filled camera)
    )
    :effect (and
      (filled gripper_sensor)
      (uses gripper_sensor nco2)
      (chosen nco2)
      (increase (total-cost) 1)
    )
  )

  ;; keep NVP1 as perception
  (:action choose-perception-nvp1
    :parameters ()
    :precondition (and
      (not (filled perception))
      (not (chosen nvp1))
      (filled gripper_sensor)
    )
    :effect (and
      (filled perception)
      (uses perception nvp1)
      (chosen nvp1)
      (increase (total-cost) 0)
    )
  )

  ;; start NVP2 as perception
  (:action choose-perception-nvp2
    :parameters ()
    :precondition (and
      (not (filled perception))
      (not (chosen nvp2))
      (filled gripper_sensor)
    )
    :effect (and
      (filled perception)
      (uses perception nvp2)
      (chosen nvp2)
      (increase (total-cost) 1)
    )
  )

  ;; keep NFB21 as positioning
  (:action choose-positioning-nfb21
    :parameters ()
    :precondition (and
      (not (filled positioning))
      (not (chosen nfb21))
      (filled perception)
    )
    :effect (and
      (filled positioning)
      (uses positioning nfb21)
      (chosen nfb21)
      (increase (total-cost) 0)
    )
  )

  ;; keep NFB22 as grasping
  (:action choose-grasping-nfb22
    :parameters ()
    :precondition (and
      (not (filled grasping))
      (not (chosen nfb22))
      (filled positioning)
    )
    :effect (and
      (filled grasping)
      (uses grasping nfb22)
      (chosen nfb22)
      (increase (total-cost) 0)
    )
  )

  ;; keep NFB23 as carrying
  (:action choose-carrying-nfb23
    :parameters ()
    :precondition (and
      (not (filled carrying))
      (not (chosen nfb23))
      (filled grasping)
    )
    :effect (and
      (filled carrying)
      (uses carrying nfb23)
      (chosen nfb23)
      (increase (total-cost) 0)
    )
  )

  ;; keep NFB24 as placing
  (:action choose-placing-nfb24
    :parameters ()
    :precondition (and
      (not (filled placing))
      (not (chosen nfb24))
      (filled carrying)
    )
    :effect (and
      (filled placing)
      (uses placing nfb24)
      (chosen nfb24)
      (increase (total-cost) 0)
    )
  )

  ;; keep NREA as reasoner
  (:action choose-reasoner-nrea
    :parameters ()
    :precondition (and
      (not (filled reasoner))
      (not (chosen nrea))
      (filled placing)
    )
    :effect (and
      (filled reasoner)
      (uses reasoner nrea)
      (chosen nrea)
      (increase (total-cost) 0)
    )
  )

  ;; NCA1 (camera) meets perception's need for service 'camera_image' (robot_arm_msgs/CameraImage)
  (:action connect-perception-camera_image-camera-nca1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done gripper_sensor)
      (not (met perception camera_image))
      (uses camera nca1)
    )
    :effect (and
      (met perception camera_image)
      (increase (total-cost) 0)
    )
  )

  ;; NCA2 (camera) meets perception's need for service 'camera_image' (robot_arm_msgs/CameraImage)
  (:action connect-perception-camera_image-camera-nca2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done gripper_sensor)
      (not (met perception camera_image))
      (uses camera nca2)
    )
    :effect (and
      (met perception camera_image)
      (increase (total-cost) 0)
    )
  )

  ;; NCO1 (gripper_sensor) meets perception's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-perception-gripper_feeling-gripper_sensor-nco1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done gripper_sensor)
      (not (met perception gripper_feeling))
      (uses gripper_sensor nco1)
    )
    :effect (and
      (met perception gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; NCO2 (gripper_sensor) meets perception's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-perception-gripper_feeling-gripper_sensor-nco2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done gripper_sensor)
      (not (met perception gripper_feeling))
      (uses gripper_sensor nco2)
    )
    :effect (and
      (met perception gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; NCO1 (gripper_sensor) meets positioning's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-positioning-gripper_feeling-gripper_sensor-nco1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done perception)
      (not (met positioning gripper_feeling))
      (uses gripper_sensor nco1)
    )
    :effect (and
      (met positioning gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; NCO2 (gripper_sensor) meets positioning's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-positioning-gripper_feeling-gripper_sensor-nco2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done perception)
      (not (met positioning gripper_feeling))
      (uses gripper_sensor nco2)
    )
    :effect (and
      (met positioning gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; NVP1 (perception) meets positioning's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-positioning-visual_perception-perception-nvp1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done perception)
      (not (met positioning visual_perception))
      (uses perception nvp1)
    )
    :effect (and
      (met positioning visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; NVP2 (perception) meets positioning's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-positioning-visual_perception-perception-nvp2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done perception)
      (not (met positioning visual_perception))
      (uses perception nvp2)
    )
    :effect (and
      (met positioning visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; NSM1 (base_joint) meets positioning's need for service 'base/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-positioning-base__digital_servo_command-base_joint-nsm1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done perception)
      (not (met positioning base__digital_servo_command))
      (uses base_joint nsm1)
    )
    :effect (and
      (met positioning base__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM2 (shoulder_joint) meets positioning's need for service 'shoulder/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-positioning-shoulder__digital_servo_command-shoulder_joint-nsm2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done perception)
      (not (met positioning shoulder__digital_servo_command))
      (uses shoulder_joint nsm2)
    )
    :effect (and
      (met positioning shoulder__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM3 (elbow_joint) meets positioning's need for service 'elbow/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-positioning-elbow__digital_servo_command-elbow_joint-nsm3
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done perception)
      (not (met positioning elbow__digital_servo_command))
      (uses elbow_joint nsm3)
    )
    :effect (and
      (met positioning elbow__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM4 (wrist_joint) meets positioning's need for service 'wrist/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-positioning-wrist__digital_servo_command-wrist_joint-nsm4
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done perception)
      (not (met positioning wrist__digital_servo_command))
      (uses wrist_joint nsm4)
    )
    :effect (and
      (met positioning wrist__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM5 (gripper_joint) meets positioning's need for service 'gripper/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-positioning-gripper__digital_servo_command-gripper_joint-nsm5
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done perception)
      (not (met positioning gripper__digital_servo_command))
      (uses gripper_joint nsm5)
    )
    :effect (and
      (met positioning gripper__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NCO1 (gripper_sensor) meets grasping's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-grasping-gripper_feeling-gripper_sensor-nco1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done positioning)
      (not (met grasping gripper_feeling))
      (uses gripper_sensor nco1)
    )
    :effect (and
      (met grasping gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; NCO2 (gripper_sensor) meets grasping's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-grasping-gripper_feeling-gripper_sensor-nco2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done positioning)
      (not (met grasping gripper_feeling))
      (uses gripper_sensor nco2)
    )
    :effect (and
      (met grasping gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; NVP1 (perception) meets grasping's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-grasping-visual_perception-perception-nvp1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done positioning)
      (not (met grasping visual_perception))
      (uses perception nvp1)
    )
    :effect (and
      (met grasping visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; NVP2 (perception) meets grasping's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-grasping-visual_perception-perception-nvp2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done positioning)
      (not (met grasping visual_perception))
      (uses perception nvp2)
    )
    :effect (and
      (met grasping visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; NSM1 (base_joint) meets grasping's need for service 'base/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-grasping-base__digital_servo_command-base_joint-nsm1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done positioning)
      (not (met grasping base__digital_servo_command))
      (uses base_joint nsm1)
    )
    :effect (and
      (met grasping base__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM2 (shoulder_joint) meets grasping's need for service 'shoulder/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-grasping-shoulder__digital_servo_command-shoulder_joint-nsm2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done positioning)
      (not (met grasping shoulder__digital_servo_command))
      (uses shoulder_joint nsm2)
    )
    :effect (and
      (met grasping shoulder__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM3 (elbow_joint) meets grasping's need for service 'elbow/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-grasping-elbow__digital_servo_command-elbow_joint-nsm3
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done positioning)
      (not (met grasping elbow__digital_servo_command))
      (uses elbow_joint nsm3)
    )
    :effect (and
      (met grasping elbow__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM4 (wrist_joint) meets grasping's need for service 'wrist/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-grasping-wrist__digital_servo_command-wrist_joint-nsm4
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done positioning)
      (not (met grasping wrist__digital_servo_command))
      (uses wrist_joint nsm4)
    )
    :effect (and
      (met grasping wrist__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM5 (gripper_joint) meets grasping's need for service 'gripper/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-grasping-gripper__digital_servo_command-gripper_joint-nsm5
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done positioning)
      (not (met grasping gripper__digital_servo_command))
      (uses gripper_joint nsm5)
    )
    :effect (and
      (met grasping gripper__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NCO1 (gripper_sensor) meets carrying's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-carrying-gripper_feeling-gripper_sensor-nco1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done grasping)
      (not (met carrying gripper_feeling))
      (uses gripper_sensor nco1)
    )
    :effect (and
      (met carrying gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; NCO2 (gripper_sensor) meets carrying's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-carrying-gripper_feeling-gripper_sensor-nco2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done grasping)
      (not (met carrying gripper_feeling))
      (uses gripper_sensor nco2)
    )
    :effect (and
      (met carrying gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; NVP1 (perception) meets carrying's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-carrying-visual_perception-perception-nvp1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done grasping)
      (not (met carrying visual_perception))
      (uses perception nvp1)
    )
    :effect (and
      (met carrying visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; NVP2 (perception) meets carrying's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-carrying-visual_perception-perception-nvp2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done grasping)
      (not (met carrying visual_perception))
      (uses perception nvp2)
    )
    :effect (and
      (met carrying visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; NSM1 (base_joint) meets carrying's need for service 'base/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-carrying-base__digital_servo_command-base_joint-nsm1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done grasping)
      (not (met carrying base__digital_servo_command))
      (uses base_joint nsm1)
    )
    :effect (and
      (met carrying base__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM2 (shoulder_joint) meets carrying's need for service 'shoulder/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-carrying-shoulder__digital_servo_command-shoulder_joint-nsm2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done grasping)
      (not (met carrying shoulder__digital_servo_command))
      (uses shoulder_joint nsm2)
    )
    :effect (and
      (met carrying shoulder__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM3 (elbow_joint) meets carrying's need for service 'elbow/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-carrying-elbow__digital_servo_command-elbow_joint-nsm3
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done grasping)
      (not (met carrying elbow__digital_servo_command))
      (uses elbow_joint nsm3)
    )
    :effect (and
      (met carrying elbow__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM4 (wrist_joint) meets carrying's need for service 'wrist/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-carrying-wrist__digital_servo_command-wrist_joint-nsm4
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done grasping)
      (not (met carrying wrist__digital_servo_command))
      (uses wrist_joint nsm4)
    )
    :effect (and
      (met carrying wrist__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM5 (gripper_joint) meets carrying's need for service 'gripper/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-carrying-gripper__digital_servo_command-gripper_joint-nsm5
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done grasping)
      (not (met carrying gripper__digital_servo_command))
      (uses gripper_joint nsm5)
    )
    :effect (and
      (met carrying gripper__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NCO1 (gripper_sensor) meets placing's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-placing-gripper_feeling-gripper_sensor-nco1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done carrying)
      (not (met placing gripper_feeling))
      (uses gripper_sensor nco1)
    )
    :effect (and
      (met placing gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; NCO2 (gripper_sensor) meets placing's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-placing-gripper_feeling-gripper_sensor-nco2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done carrying)
      (not (met placing gripper_feeling))
      (uses gripper_sensor nco2)
    )
    :effect (and
      (met placing gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; NVP1 (perception) meets placing's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-placing-visual_perception-perception-nvp1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done carrying)
      (not (met placing visual_perception))
      (uses perception nvp1)
    )
    :effect (and
      (met placing visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; NVP2 (perception) meets placing's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-placing-visual_perception-perception-nvp2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done carrying)
      (not (met placing visual_perception))
      (uses perception nvp2)
    )
    :effect (and
      (met placing visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; NSM1 (base_joint) meets placing's need for service 'base/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-placing-base__digital_servo_command-base_joint-nsm1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done carrying)
      (not (met placing base__digital_servo_command))
      (uses base_joint nsm1)
    )
    :effect (and
      (met placing base__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM2 (shoulder_joint) meets placing's need for service 'shoulder/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-placing-shoulder__digital_servo_command-shoulder_joint-nsm2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done carrying)
      (not (met placing shoulder__digital_servo_command))
      (uses shoulder_joint nsm2)
    )
    :effect (and
      (met placing shoulder__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM3 (elbow_joint) meets placing's need for service 'elbow/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-placing-elbow__digital_servo_command-elbow_joint-nsm3
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done carrying)
      (not (met placing elbow__digital_servo_command))
      (uses elbow_joint nsm3)
    )
    :effect (and
      (met placing elbow__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM4 (wrist_joint) meets placing's need for service 'wrist/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-placing-wrist__digital_servo_command-wrist_joint-nsm4
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done carrying)
      (not (met placing wrist__digital_servo_command))
      (uses wrist_joint nsm4)
    )
    :effect (and
      (met placing wrist__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM5 (gripper_joint) meets placing's need for service 'gripper/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-placing-gripper__digital_servo_command-gripper_joint-nsm5
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done carrying)
      (not (met placing gripper__digital_servo_command))
      (uses gripper_joint nsm5)
    )
    :effect (and
      (met placing gripper__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NVP1 (perception) meets reasoner's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-reasoner-visual_perception-perception-nvp1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done placing)
      (not (met reasoner visual_perception))
      (uses perception nvp1)
    )
    :effect (and
      (met reasoner visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; NVP2 (perception) meets reasoner's need for service 'visual_perception' (robot_arm_msgs/VisualPerception)
  (:action connect-reasoner-visual_perception-perception-nvp2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done placing)
      (not (met reasoner visual_perception))
      (uses perception nvp2)
    )
    :effect (and
      (met reasoner visual_perception)
      (increase (total-cost) 0)
    )
  )

  ;; NCO1 (gripper_sensor) meets reasoner's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-reasoner-gripper_feeling-gripper_sensor-nco1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done placing)
      (not (met reasoner gripper_feeling))
      (uses gripper_sensor nco1)
    )
    :effect (and
      (met reasoner gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; NCO2 (gripper_sensor) meets reasoner's need for service 'gripper_feeling' (robot_arm_msgs/GripperFeeling)
  (:action connect-reasoner-gripper_feeling-gripper_sensor-nco2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done placing)
      (not (met reasoner gripper_feeling))
      (uses gripper_sensor nco2)
    )
    :effect (and
      (met reasoner gripper_feeling)
      (increase (total-cost) 0)
    )
  )

  ;; NSM1 (base_joint) meets reasoner's need for any one of service 'base/dc_servo_command' (robot_arm_msgs/DcServoCommand), service 'base/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-reasoner-base__dc_servo_command-or-base__digital_servo_command-base_joint-nsm1
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done placing)
      (not (met reasoner base__dc_servo_command-or-base__digital_servo_command))
      (uses base_joint nsm1)
    )
    :effect (and
      (met reasoner base__dc_servo_command-or-base__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM2 (shoulder_joint) meets reasoner's need for any one of service 'shoulder/dc_servo_command' (robot_arm_msgs/DcServoCommand), service 'shoulder/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-reasoner-shoulder__dc_servo_command-or-shoulder__digital_servo_command-shoulder_joint-nsm2
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done placing)
      (not (met reasoner shoulder__dc_servo_command-or-shoulder__digital_servo_command))
      (uses shoulder_joint nsm2)
    )
    :effect (and
      (met reasoner shoulder__dc_servo_command-or-shoulder__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM3 (elbow_joint) meets reasoner's need for any one of service 'elbow/dc_servo_command' (robot_arm_msgs/DcServoCommand), service 'elbow/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-reasoner-elbow__dc_servo_command-or-elbow__digital_servo_command-elbow_joint-nsm3
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done placing)
      (not (met reasoner elbow__dc_servo_command-or-elbow__digital_servo_command))
      (uses elbow_joint nsm3)
    )
    :effect (and
      (met reasoner elbow__dc_servo_command-or-elbow__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM4 (wrist_joint) meets reasoner's need for any one of service 'wrist/dc_servo_command' (robot_arm_msgs/DcServoCommand), service 'wrist/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-reasoner-wrist__dc_servo_command-or-wrist__digital_servo_command-wrist_joint-nsm4
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done placing)
      (not (met reasoner wrist__dc_servo_command-or-wrist__digital_servo_command))
      (uses wrist_joint nsm4)
    )
    :effect (and
      (met reasoner wrist__dc_servo_command-or-wrist__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM5 (gripper_joint) meets reasoner's need for any one of service 'gripper/dc_servo_command' (robot_arm_msgs/DcServoCommand), service 'gripper/digital_servo_command' (robot_arm_msgs/DigitalServoCommand)
  (:action connect-reasoner-gripper__dc_servo_command-or-gripper__digital_servo_command-gripper_joint-nsm5
    :parameters ()
    :precondition (and
      (filled reasoner)
      (done placing)
      (not (met reasoner gripper__dc_servo_command-or-gripper__digital_servo_command))
      (uses gripper_joint nsm5)
    )
    :effect (and
      (met reasoner gripper__dc_servo_command-or-gripper__digital_servo_command)
      (increase (total-cost) 0)
    )
  )

  ;; NSM1 has all it requires and needs
  (:action finish-base_joint-nsm1
    :parameters ()
    :precondition (and
      (uses base_joint nsm1)
      (filled reasoner)
    )
    :effect (and
      (done base_joint)
      (increase (total-cost) 0)
    )
  )

  ;; NSM2 has all it requires and needs
  (:action finish-shoulder_joint-nsm2
    :parameters ()
    :precondition (and
      (uses shoulder_joint nsm2)
      (filled reasoner)
      (done base_joint)
    )
    :effect (and
      (done shoulder_joint)
      (increase (total-cost) 0)
    )
  )

  ;; NSM3 has all it requires and needs
  (:action finish-elbow_joint-nsm3
    :parameters ()
    :precondition (and
      (uses elbow_joint nsm3)
      (filled reasoner)
      (done shoulder_joint)
    )
    :effect (and
      (done elbow_joint)
      (increase (total-cost) 0)
    )
  )

  ;; NSM4 has all it requires and needs
  (:action finish-wrist_joint-nsm4
    :parameters ()
    :precondition (and
      (uses wrist_joint nsm4)
      (filled reasoner)
      (done elbow_joint)
    )
    :effect (and
      (done wrist_joint)
      (increase (total-cost) 0)
    )
  )

  ;; NSM5 has all it requires and needs
  (:action finish-gripper_joint-nsm5
    :parameters ()
    :precondition (and
      (uses gripper_joint nsm5)
      (filled reasoner)
      (done wrist_joint)
    )
    :effect (and
      (done gripper_joint)
      (increase (total-cost) 0)
    )
  )

  ;; NCA1 has all it requires and needs
  (:action finish-camera-nca1
    :parameters ()
    :precondition (and
      (uses camera nca1)
      (filled reasoner)
      (done gripper_joint)
    )
    :effect (and
      (done camera)
      (increase (total-cost) 0)
    )
  )

  ;; NCA2 has all it requires and needs
  (:action finish-camera-nca2
    :parameters ()
    :precondition (and
      (uses camera nca2)
      (filled reasoner)
      (done gripper_joint)
    )
    :effect (and
      (done camera)
      (increase (total-cost) 0)
    )
  )

  ;; NCO1 has all it requires and needs
  (:action finish-gripper_sensor-nco1
    :parameters ()
    :precondition (and
      (uses gripper_sensor nco1)
      (filled reasoner)
      (done camera)
    )
    :effect (and
      (done gripper_sensor)
      (increase (total-cost) 0)
    )
  )

  ;; NCO2 has all it requires and needs
  (:action finish-gripper_sensor-nco2
    :parameters ()
    :precondition (and
      (uses gripper_sensor nco2)
      (filled reasoner)
      (done camera)
    )
    :effect (and
      (done gripper_sensor)
      (increase (total-cost) 0)
    )
  )

  ;; NVP1 has all it requires and needs
  (:action finish-perception-nvp1
    :parameters ()
    :precondition (and
      (uses perception nvp1)
      (filled reasoner)
      (done gripper_sensor)
      (met perception camera_image)
      (met perception gripper_feeling)
      (chosen nca1)
      (chosen nco1)
    )
    :effect (and
      (done perception)
      (increase (total-cost) 0)
    )
  )

  ;; NVP2 has all it requires and needs
  (:action finish-perception-nvp2
    :parameters ()
    :precondition (and
      (uses perception nvp2)
      (filled reasoner)
      (done gripper_sensor)
      (met perception camera_image)
      (met perception gripper_feeling)
      (chosen nca2)
      (chosen nco2)
    )
    :effect (and
      (done perception)
      (increase (total-cost) 0)
    )
  )

  ;; NFB21 has all it requires and needs
  (:action finish-positioning-nfb21
    :parameters ()
    :precondition (and
      (uses positioning nfb21)
      (filled reasoner)
      (done perception)
      (met positioning gripper_feeling)
      (met positioning visual_perception)
      (met positioning base__digital_servo_command)
      (met positioning shoulder__digital_servo_command)
      (met positioning elbow__digital_servo_command)
      (met positioning wrist__digital_servo_command)
      (met positioning gripper__digital_servo_command)
    )
    :effect (and
      (done positioning)
      (increase (total-cost) 0)
    )
  )

  ;; NFB22 has all it requires and needs
  (:action finish-grasping-nfb22
    :parameters ()
    :precondition (and
      (uses grasping nfb22)
      (filled reasoner)
      (done positioning)
      (met grasping gripper_feeling)
      (met grasping visual_perception)
      (met grasping base__digital_servo_command)
      (met grasping shoulder__digital_servo_command)
      (met grasping elbow__digital_servo_command)
      (met grasping wrist__digital_servo_command)
      (met grasping gripper__digital_servo_command)
    )
    :effect (and
      (done grasping)
      (increase (total-cost) 0)
    )
  )

  ;; NFB23 has all it requires and needs
  (:action finish-carrying-nfb23
    :parameters ()
    :precondition (and
      (uses carrying nfb23)
      (filled reasoner)
      (done grasping)
      (met carrying gripper_feeling)
      (met carrying visual_perception)
      (met carrying base__digital_servo_command)
      (met carrying shoulder__digital_servo_command)
      (met carrying elbow__digital_servo_command)
      (met carrying wrist__digital_servo_command)
      (met carrying gripper__digital_servo_command)
    )
    :effect (and
      (done carrying)
      (increase (total-cost) 0)
    )
  )

  ;; NFB24 has all it requires and needs
  (:action finish-placing-nfb24
    :parameters ()
    :precondition (and
      (uses placing nfb24)
      (filled reasoner)
      (done carrying)
      (met placing gripper_feeling)
      (met placing visual_perception)
      (met placing base__digital_servo_command)
      (met placing shoulder__digital_servo_command)
      (met placing elbow__digital_servo_command)
      (met placing wrist__digital_servo_command)
      (met placing gripper__digital_servo_command)
    )
    :effect (and
      (done placing)
      (increase (total-cost) 0)
    )
  )

  ;; NREA has all it requires and needs
  (:action finish-reasoner-nrea
    :parameters ()
    :precondition (and
      (uses reasoner nrea)
      (filled reasoner)
      (done placing)
      (met reasoner visual_perception)
      (met reasoner gripper_feeling)
      (met reasoner base__dc_servo_command-or-base__digital_servo_command)
      (met reasoner shoulder__dc_servo_command-or-shoulder__digital_servo_command)
      (met reasoner elbow__dc_servo_command-or-elbow__digital_servo_command)
      (met reasoner wrist__dc_servo_command-or-wrist__digital_servo_command)
      (met reasoner gripper__dc_servo_command-or-gripper__digital_servo_command)
    )
    :effect (and
      (done reasoner)
      (increase (total-cost) 0)
    )
  )
)

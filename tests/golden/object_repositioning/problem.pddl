;; rosreconf: Object Repositioning (object_repositioning).
;; Skill: Pick an object up from where it lies and put it down at a target position: position the arm, grasp the object, carry it and place it, guided by camera images and gripper pressure.
;; running now: base_joint = NSM1
;; running now: shoulder_joint = NSM2
;; running now: elbow_joint = NSM3
;; running now: wrist_joint = NSM4
;; running now: gripper_joint = NSM5
;; running now: camera = NCA1
;; running now: gripper_sensor = NCO1
;; running now: perception = NVP1
;; running now: positioning = NFB21
;; running now: grasping = NFB22
;; running now: carrying = NFB23
;; running now: placing = NFB24
;; running now: reasoner = NREA
(define (problem rosreconf-object_repositioning-task)
  (:domain rosreconf-object_repositioning)
  (:init
    (choosing base_joint)
    (= (total-cost) 0)
  )
  (:goal (and
    (finished)
  ))
  (:metric minimize (total-cost))
)

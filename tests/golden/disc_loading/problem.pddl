;; rosreconf: Disc Loading (disc_loading).
;; Skill: Load a disc into a slot: position, grasp, carry and place it with the accuracy only position-feedback servos give.
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
(define (problem rosreconf-disc_loading-task)
  (:domain rosreconf-disc_loading)
  (:init
    (choosing base_joint)
    (= (total-cost) 0)
  )
  (:goal (and
    (finished)
  ))
  (:metric minimize (total-cost))
)

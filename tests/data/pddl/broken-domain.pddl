; A syntax error: the action's effect uses the predicate 'chosen', which is never declared.
(define (domain pick-components)
  (:requirements :strips :typing :action-costs)
  (:types role component service)
  (:predicates
    (open ?r - role)
    (filled ?r - role)
    (candidate ?r - role ?c - component)
    (needs ?c - component ?s - service)
    (offers ?c - component ?s - service)
    (available ?s - service)
    (uses ?r - role ?c - component))
  (:functions
    (total-cost) - number
    (price ?c - component) - number)
  (:action pick
    :parameters (?r - role ?c - component ?need - service ?offer - service)
    :precondition (and (open ?r) (candidate ?r ?c) (needs ?c ?need) (available ?need)
                       (offers ?c ?offer))
    :effect (and (not (open ?r)) (filled ?r) (chosen ?r ?c) (available ?offer)
                 (increase (total-cost) (price ?c)))))

"""Stage 5, planning: the PDDL encoding (Def. 11), real planners, the plan read back and explained.

``pddl_names`` maps model names to PDDL names and back; ``pddl`` renders the Jinja templates;
``planners`` runs Fast Downward or FF; ``replan`` joins them and checks every plan against
``rosreconf.model.validity``; ``narrative`` explains a re-plan to an operator.
"""

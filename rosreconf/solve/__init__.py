"""Stage 3, finding configurations: counting, the first, the optimum and enumeration.

``instance`` compiles one interoperability schema over a component library into static
tables; ``factors`` and ``counting`` count by variable elimination; ``optimum`` finds the
exact optimum by min-sum elimination; ``solver`` enumerates with clingo and owns the
``Objective``.
"""

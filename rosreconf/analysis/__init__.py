"""Stage 4, analysis: orthogonality (Def. 8), redundancy (Thm. 10), failures and what-if.

``library`` answers the Section 4 questions about a library and a schema; ``redundancy``
solves Theorem 10; ``whatif`` sweeps failure sets.
"""

"""Stage 1, reading and checking files: YAML with positions -> checked model.

``yamlsource`` parses YAML 1.2 keeping file:line:column; ``structure`` checks the JSON Schema
of each format; ``checks`` makes the semantic checks (Lemma 4, names, references); ``loader``
joins them into the one entry point, ``load_checked``. ``configfile`` reads configuration
files; ``generate`` writes synthetic libraries and schemas.
"""

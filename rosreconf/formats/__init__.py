"""Stage 1, reading and checking files: YAML with positions -> checked model.

``yamlsource`` reads YAML 1.2 into PyYAML's node tree (``nodes`` reads it: file:line:column,
text, value) and plain data; ``structure`` checks the JSON Schema of each format
(jsonschema-rs); ``values`` the values; ``build`` makes the model; ``checks`` makes the
semantic checks (Lemma 4, names, references); ``loader`` joins them, once per file, into the
entry points (``load_selection``, ``load_checked``). ``configfile`` reads configuration
files; ``generate`` writes synthetic libraries and schemas.
"""

"""Stage 1, reading and checking files: YAML -> checked model, positions when a problem needs them.

``yamlsource`` reads every file, YAML 1.2 composed by PyYAML over libyaml into a node tree
with its marks, and its plain data (``nodes`` reads it: file:line:column, text, value);
``structure`` checks the JSON Schema of each format (jsonschema-rs); ``values`` the values;
``build`` makes the model; ``checks`` makes the semantic checks (Lemma 4, names,
references); ``loader`` joins them, once per file, into the entry points
(``load_selection``, ``load_checked``). ``configfile`` reads configuration files.
"""

"""Stage 1, reading and checking files: YAML -> checked model, positions when a problem needs them.

``yamlsource`` reads every file, YAML 1.2 from libyaml's event stream, into its plain data
(``nodes``) and a compact table of where each value is written (``positions``:
file:line:column and the text as written, looked up only to report a problem);
``structure`` checks the JSON Schema of each format (jsonschema-rs); ``values`` the values;
``build`` makes the model; ``checks`` makes the semantic checks (Lemma 4, names,
references); ``loader`` joins them, once per file, into the entry points
(``load_selection``, ``load_checked``). ``configfile`` reads configuration files.
"""

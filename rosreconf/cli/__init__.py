"""Stage 8, the command line: each verb parses options, calls the library, hands on the result.

``app`` registers the verbs and maps errors to exit codes; ``console`` owns stdout and stderr.
"""

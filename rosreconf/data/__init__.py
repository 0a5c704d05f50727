"""Bundled JSON Schemas and other data files of rosreconf."""

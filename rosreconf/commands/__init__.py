"""One module per CLI verb (ros2cli style); each registers itself on the typer app."""

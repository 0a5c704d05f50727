"""Stage 7, output: pictures (DOT, SVG, PNG) and problem reports."""

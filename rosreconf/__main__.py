"""Let ``python -m rosreconf`` run the CLI."""

from rosreconf.cli import main

main()

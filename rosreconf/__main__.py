"""Let ``python -m rosreconf`` run the CLI."""

from rosreconf.cli.app import main

main()

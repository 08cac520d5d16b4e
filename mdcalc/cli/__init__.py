"""The command line: what a person types and sees; nothing here computes.

- ``launch.py``: the console script ``mdcalc``. A plain ``mdcalc PROBLEM CASE.toml
  [--json] [--debug]`` or ``mdcalc run PATH... [--jobs N] [--json] [--debug]`` goes
  straight to its command body; anything else through the typer app.
- ``app.py``: the typer app: one command per registry entry (``--json``, ``--plot``,
  ``--save``, ``--report``), check, run, sweep, study, new; shell completion.
- ``command.py``: the bodies of a problem command and of ``run``, and the one error
  handler (exit codes, messages), without typer: shared by launch.py and app.py.
- ``schema.py``: the bodies of ``schema`` (a problem's case-file JSON Schema, its keys
  as a table) and ``new`` (a starter case beside its schema).
- ``terminal.py``: printing a report (plain text on a pipe, rich on a terminal),
  progress bars, the run summary, sweep tables.
- ``startup.py``: what every command sets before it runs (warnings, pydantic's
  plugin loader).

Imports nothing eagerly: ``mdcalc.cli.launch`` pays only for what a command needs.
"""

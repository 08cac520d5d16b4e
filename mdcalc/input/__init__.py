"""Input: case files, from the bytes on disk to a validated pydantic case, and the
rules for the user's files (``files.py``) that every output written also follows.

- ``casefile.py``: TOML reading (tomli), strict pydantic validation, messages with
  the line, the field path, the value and what is allowed.
- ``model.py``: base case models (strict, no unknown keys), the ``[expect]`` entry,
  and ``with_values`` (a case with numpy arrays at key paths, for the kernels).
- ``files.py``: the user's files: regular case files of bounded size; atomic
  writes, exclusive without ``--force`` (``--save``, ``--plot``, ``--out``,
  ``--report`` all write through it).
- ``quantities.py``: quantity strings (``"52.5 N*m/deg"``) through pint.
- ``expr.py``: the restricted formula language of case files (no eval).
- ``schema.py``: a problem's case file as a JSON Schema (from its pydantic model), and
  its keys as rows of a table.
- ``starter.py``: the starter case of ``mdcalc new``: the template with every key of
  the schema beside it, commented out where optional.

Imports nothing eagerly.
"""

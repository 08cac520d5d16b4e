"""Output: what a computed case looks like to a person or a program.

- ``report.py``: the Report value (quantities, tables, Methods tables, notes) and
  its grids, the cells every text renderer lays out.
- ``text.py``: rich on a terminal; the same text without rich on a pipe.
- ``jsondoc.py``: ``--json`` (format 1) and the TOML table of ``--save``.
- ``document.py``: calculation documents, HTML and Markdown (``--report``).
- ``plot.py``: the chart data classes problems fill, drawn with matplotlib
  (``--plot``).

Imports nothing eagerly.
"""

"""Domain data and case sections several problems share, so that no problem
imports another. A layer of its own below ``problems`` (it imports none of them)
and above ``input``, whose case models its sections build on; no subcommand.

- ``tables.py``: coefficient tables with their sources: road adhesion (braking, and
  acceleration through vehicle.py), allowable accelerations by machine type and the
  brake safety factor (hoist).
- ``vehicle.py``: case sections braking and acceleration share (drag, road
  surfaces, speed in m/s or km/h).
"""

"""What several problems share, so that no problem imports another.

- ``tables.py``: coefficient tables with their sources: road adhesion (braking, and
  acceleration through vehicle.py), allowable accelerations by machine type and the
  brake safety factor (hoist).
- ``vehicle.py``: case sections braking and acceleration share (drag, road
  surfaces, speed in m/s or km/h).
"""

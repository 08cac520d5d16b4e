"""What several problems share, so that no problem imports another.

- ``tables.py``: coefficient tables with their sources (road adhesion, allowable
  accelerations by machine type): hoist, braking, acceleration.
- ``vehicle.py``: case sections braking and acceleration share (drag, road
  surfaces, speed in m/s or km/h).
"""

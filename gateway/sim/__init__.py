"""Simulated ArduCopter vehicles speaking MAVLink 2 (see docs/simulator.md)."""

from gateway.sim.fleet import SimFleet
from gateway.sim.timeline import Timeline
from gateway.sim.vehicle import SimVehicle

__all__ = ["SimFleet", "SimVehicle", "Timeline"]

"""Simulated ArduCopter vehicles speaking MAVLink 2 (see docs/simulator.md)."""

from gateway.sim.boot import Timeline
from gateway.sim.fleet import SimFleet
from gateway.sim.vehicle import SimVehicle

__all__ = ["SimFleet", "SimVehicle", "Timeline"]

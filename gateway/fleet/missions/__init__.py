"""Missions and flights: mission items, mission files (QGC .plan, .waypoints), the flight log and its
exports."""

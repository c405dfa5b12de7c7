"""The vehicles: the seam the flight logic reads and acts through (`protocols`), the MAVSDK-backed vehicle,
its registry, the telemetry readings and parameters."""

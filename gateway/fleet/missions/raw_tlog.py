"""A flight's raw MAVLink as the drone sent it: the telemetry log (``.tlog``) the field's tools read.

Each record is what QGroundControl and MAVProxy write: an 8-byte big-endian Unix time in microseconds
(when the gateway received the frame) and the frame as received, byte for byte (MAVLink 1 or 2,
signed or not). The frames come from the vehicle's relay (`gateway.link.relay`), already cut by its
framing; nothing here parses them. Cost per frame: one ``time.time()``, two writes into a 64 KiB file
buffer (written to disk when full and at every track flush), no copy of the frame beyond that buffer.

* One file per flight, ``<vehicle id>-flight-<flight id>.tlog`` in the folder ``flight_tlog_dir``
  names (default: ``<database file>-tlogs`` next to a SQLite database, ``fleet-gateway-tlogs`` in the
  working directory otherwise), on the node that flew it.
* The flight is opened by the recorder's 1 Hz tick after the autopilot reports armed; the frames of the
  last ``PREROLL_S`` seconds before (at most ``PREROLL_FRAMES``) are written first, so the log starts
  before the arming. It ends when the recorder closes the flight (disarmed, or recording stopped).
* At most ``flight_tlog_max_mib`` MiB per flight: the frames after that are not written, and the
  export says the log was cut (``X-Tlog-Cut``).
"""

from __future__ import annotations

import logging
import time
from collections import deque
from pathlib import Path
from typing import BinaryIO

from gateway.config import Settings

log = logging.getLogger("gateway.flightlog")

#: how far before the flight is opened its log starts, and how many frames that keeps at most
PREROLL_S = 3.0
PREROLL_FRAMES = 512
#: the longest MAVLink frame (v2, 255-byte payload, signed) with its time stamp
LONGEST_RECORD = 8 + 280
BUFFER_BYTES = 64 * 1024


def tlog_folder(settings: Settings, database_url: str) -> Path | None:
    """Where raw flight logs are written; None when they are not recorded."""
    given = settings.flight_tlog_dir.strip()
    if not settings.records_flight_frames:
        return None
    if given:
        return Path(given)
    if database_url.startswith("sqlite") and ":memory:" not in database_url:
        database = database_url.split(":///", 1)[-1]
        if database:
            return Path(f"{database}-tlogs")
    return Path("fleet-gateway-tlogs")


def tlog_file(folder: Path, vehicle_id: str, flight_id: int) -> Path:
    return folder / f"{vehicle_id}-flight-{flight_id}.tlog"


def was_cut(path: Path, settings: Settings) -> bool:
    """Whether the log at ``path`` reached its cap (frames after it were not written)."""
    return path.stat().st_size > settings.flight_tlog_max_mib * 1024 * 1024 - LONGEST_RECORD


class RawTlog:
    """Writes the frames a vehicle sends into the open flight's file; keeps a short pre-roll between."""

    def __init__(self, folder: Path, vehicle_id: str, max_bytes: int) -> None:
        self.folder = folder
        self.vehicle_id = vehicle_id
        self.max_bytes = max_bytes
        self.path: Path | None = None
        self._file: BinaryIO | None = None
        self._written = 0
        self._preroll: deque[tuple[float, bytes]] = deque(maxlen=PREROLL_FRAMES)

    def frame(self, data: bytes) -> None:
        """One frame from the vehicle, as received (called by the relay for every frame)."""
        now = time.time()
        file = self._file
        if file is None:
            self._preroll.append((now, data))
            return
        if self._written + LONGEST_RECORD > self.max_bytes:
            return
        try:
            file.write(int(now * 1e6).to_bytes(8, "big"))
            file.write(data)
        except OSError as exc:  # the disk is full or gone: the flight's log ends here, the relay goes on
            self._failed(exc)
            return
        self._written += 8 + len(data)

    def _failed(self, exc: OSError) -> None:
        log.error("%s: the raw MAVLink log %s cannot be written: %s", self.vehicle_id, self.path, exc)
        file, self._file = self._file, None
        if file is not None:
            try:
                file.close()
            except OSError:
                pass

    def open(self, flight_id: int) -> None:
        """Start the flight's file (replacing one of that name) with the pre-roll's recent frames."""
        self.close()
        self.folder.mkdir(parents=True, exist_ok=True)
        path = tlog_file(self.folder, self.vehicle_id, flight_id)
        file = path.open("wb", buffering=BUFFER_BYTES)
        self.path, self._file, self._written = path, file, 0
        since = time.time() - PREROLL_S
        preroll, self._preroll = self._preroll, deque(maxlen=PREROLL_FRAMES)
        for at, data in preroll:
            if at >= since:
                file.write(int(at * 1e6).to_bytes(8, "big"))
                file.write(data)
                self._written += 8 + len(data)
        log.info("%s: raw MAVLink of flight %d written to %s", self.vehicle_id, flight_id, path)

    def flush(self) -> None:
        if self._file is not None:
            try:
                self._file.flush()
            except OSError as exc:
                self._failed(exc)

    def close(self) -> None:
        file, self._file = self._file, None
        if file is not None:
            try:
                file.close()
            except OSError as exc:
                self._file = file
                self._failed(exc)
                return
            if self._written + LONGEST_RECORD > self.max_bytes:
                log.warning(
                    "%s: the raw MAVLink log %s reached its cap of %d bytes; later frames were not written",
                    self.vehicle_id,
                    self.path,
                    self.max_bytes,
                )

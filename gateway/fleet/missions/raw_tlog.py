"""A flight's raw MAVLink as the drone sent it: the telemetry log (``.tlog``) the field's tools read.

Each record is what QGroundControl and MAVProxy write: an 8-byte big-endian Unix time in microseconds
(when the gateway received the frame) and the frame as received, byte for byte (MAVLink 1 or 2,
signed or not). The relay (`gateway.link.relay`) hands over the vehicle's bytes as it read them (one
or more frames, or part of one), with no per-frame work of its own; they are cut into frames here
(`gateway.link.mavlink_frames`, checked by CRC) only while a flight's file is open. At rest a read
costs one ``time.time()`` and a place in the pre-roll; in flight, each frame two writes into a 64 KiB
file buffer (written to disk when full and at every track flush).

* One file per flight, ``<vehicle id>-flight-<flight id>.tlog`` in the folder ``flight_tlog_dir``
  names (default: ``<database file>-tlogs`` next to a SQLite database, ``fleet-gateway-tlogs`` in the
  working directory otherwise), on the node that flew it.
* The flight is opened by the recorder's 1 Hz tick after the autopilot reports armed; the frames of the
  last ``PREROLL_S`` seconds before (at most ``PREROLL_BYTES`` of reads) are written first, so the log
  starts before the arming. It ends when the recorder closes the flight (disarmed, or recording stopped).
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

#: how far before the flight is opened its log starts, and how many bytes of reads that keeps at most
PREROLL_S = 3.0
PREROLL_BYTES = 64 * 1024
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
        # the framing (pymavlink's CRC) is imported with the first drone's log, not at every start
        from gateway.link.mavlink_frames import FrameSplitter

        self._new_splitter = FrameSplitter
        self.folder = folder
        self.vehicle_id = vehicle_id
        self.max_bytes = max_bytes
        self.path: Path | None = None
        self._file: BinaryIO | None = None
        self._written = 0
        self._splitter = self._new_splitter()
        #: the reads of the last PREROLL_S seconds (at most PREROLL_BYTES), oldest first, with their time
        self._preroll: deque[tuple[float, bytes]] = deque()
        self._preroll_bytes = 0

    def received(self, data: bytes) -> None:
        """A read from the vehicle as it came (called by the relay for every read)."""
        now = time.time()
        if self._file is None:
            preroll = self._preroll
            preroll.append((now, data))
            self._preroll_bytes += len(data)
            since = now - PREROLL_S
            while preroll[0][0] < since or self._preroll_bytes > PREROLL_BYTES:
                self._preroll_bytes -= len(preroll.popleft()[1])
            return
        self._write(now, data)

    def _write(self, at: float, data: bytes) -> None:
        stamp = int(at * 1e6).to_bytes(8, "big")
        for frame in self._splitter.feed(data):
            file = self._file
            if file is None or self._written + LONGEST_RECORD > self.max_bytes:
                return
            try:
                file.write(stamp)
                file.write(frame.data)
            except OSError as exc:  # the disk is full or gone: the flight's log ends here, the relay goes on
                self._failed(exc)
                return
            self._written += 8 + len(frame.data)

    def open(self, flight_id: int) -> None:
        """Start the flight's file (replacing one of that name) with the pre-roll's recent frames."""
        self.close()
        self.folder.mkdir(parents=True, exist_ok=True)
        path = tlog_file(self.folder, self.vehicle_id, flight_id)
        file = path.open("wb", buffering=BUFFER_BYTES)
        self.path, self._file, self._written = path, file, 0
        since = time.time() - PREROLL_S
        preroll, self._preroll, self._preroll_bytes = self._preroll, deque(), 0
        self._splitter = self._new_splitter()
        for at, data in preroll:
            if at >= since:
                self._write(at, data)
        log.info("%s: raw MAVLink of flight %d written to %s", self.vehicle_id, flight_id, path)

    def flush(self) -> None:
        if self._file is not None:
            try:
                self._file.flush()
            except OSError as exc:
                self._failed(exc)

    def close(self) -> None:
        file, self._file = self._file, None
        self._splitter = self._new_splitter()
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

    def _failed(self, exc: OSError) -> None:
        log.error("%s: the raw MAVLink log %s cannot be written: %s", self.vehicle_id, self.path, exc)
        file, self._file = self._file, None
        if file is not None:
            try:
                file.close()
            except OSError:
                pass

"""Which process holds which socket, read from /proc: the rows of /proc/net/{tcp,udp}[6], the inodes
of the sockets listening on a port and their addresses, and the socket inodes a process holds."""

from __future__ import annotations

import ipaddress
import os
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import NamedTuple

TCP_LISTEN = "0A"  # the state column of a listening socket in /proc/net/tcp


class ProcNetRow(NamedTuple):
    """One socket of /proc/net/{tcp,udp}{,6}: its local address (hex), port, state and inode."""

    address: str
    port: int
    state: str
    inode: int


def proc_net_rows(protocol: str) -> Iterator[ProcNetRow]:
    """The sockets of ``protocol`` ("tcp" or "udp"), IPv4 and IPv6, from /proc/net."""
    for table in (f"/proc/net/{protocol}", f"/proc/net/{protocol}6"):
        try:
            lines = Path(table).read_text().splitlines()[1:]
        except OSError:
            continue
        for line in lines:
            cols = line.split()
            if len(cols) < 10:
                continue
            address, _, hex_port = cols[1].rpartition(":")
            yield ProcNetRow(address, int(hex_port, 16), cols[3], int(cols[9]))


def listening_inodes(port: int) -> set[int]:
    """Socket inodes of TCP listeners (IPv4 and IPv6) on ``port``, from /proc/net."""
    return {row.inode for row in proc_net_rows("tcp") if row.state == TCP_LISTEN and row.port == port}


def _proc_net_address(hex_address: str) -> str:
    """A /proc/net/tcp{,6} local address (hex, 32-bit words in host byte order) as text."""
    raw = bytes.fromhex(hex_address)
    order = sys.byteorder
    words = b"".join(int.from_bytes(raw[i : i + 4], "big").to_bytes(4, order) for i in range(0, len(raw), 4))
    address = ipaddress.ip_address(words)
    if isinstance(address, ipaddress.IPv6Address) and address.ipv4_mapped is not None:
        return str(address.ipv4_mapped)
    return str(address)


def listening_addresses(port: int, inodes: set[int]) -> set[str]:
    """The local addresses of the TCP listeners on ``port`` whose socket inode is in ``inodes``."""
    return {
        _proc_net_address(row.address)
        for row in proc_net_rows("tcp")
        if row.state == TCP_LISTEN and row.port == port and row.inode in inodes
    }


def socket_inodes(pid: int) -> set[int]:
    """Socket inodes held open by ``pid``."""
    inodes: set[int] = set()
    fd_dir = Path(f"/proc/{pid}/fd")
    try:
        entries = list(fd_dir.iterdir())
    except OSError:
        return inodes
    for entry in entries:
        try:
            target = os.readlink(entry)
        except OSError:
            continue
        if target.startswith("socket:["):
            inodes.add(int(target[8:-1]))
    return inodes


class UnixRow(NamedTuple):
    """One socket of /proc/net/unix: its state (01 unconnected or listening, 03 connected), inode and
    the path it is bound to ("" for none; an accepted connection shows its listener's path)."""

    state: str
    inode: int
    path: str


def unix_rows() -> Iterator[UnixRow]:
    """The unix sockets of this network namespace, from /proc/net/unix."""
    try:
        lines = Path("/proc/net/unix").read_text().splitlines()[1:]
    except OSError:
        return
    for line in lines:
        cols = line.split(maxsplit=7)
        if len(cols) < 7:
            continue
        yield UnixRow(cols[5], int(cols[6]), cols[7] if len(cols) > 7 else "")

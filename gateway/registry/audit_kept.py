"""The audit trail's kept writes as the spool keeps them (JSON, read again after a restart): each is written
with ``model_dump(mode="json")`` and read back with ``model_validate``, so its writer gets it typed."""

from __future__ import annotations

import uuid
from dataclasses import dataclass
from datetime import datetime

from pydantic import BaseModel, Field

from gateway.registry.records import AuditEntry, SessionKind


def _fresh_call_id() -> str:
    return uuid.uuid4().hex


@dataclass(frozen=True)
class SessionSeen:
    """A session seen by one audited call: written with the call's audit row (`Store.queue_audit`)."""

    key: str
    kind: SessionKind
    principal: str | None = None
    client_name: str | None = None
    client_version: str | None = None


class KeptAudit(BaseModel):
    """One audit row written at once (`AuditTrail.add_audit`), its values bounded."""

    values: AuditEntry
    #: written once, however often the write is tried (a write kept by an older version has none: a fresh one)
    call_id: str = Field(default_factory=_fresh_call_id)


class KeptCallRow(BaseModel):
    """One row of a batch: the call, the session it came in, and its call's id (its row is written once,
    however often the write is tried; a write kept by an older version names no call: a fresh id)."""

    entry: AuditEntry
    seen: SessionSeen | None = None
    call_id: str = Field(default_factory=_fresh_call_id)


class KeptAuditBatch(BaseModel):
    """Audit rows written in one transaction, with the touches of their sessions."""

    rows: list[KeptCallRow]


class CallRowChanges(BaseModel):
    """What a call's later write changes of the row `AuditCall` wrote before its command was sent: the
    fields it sets (``model_dump(exclude_unset=True)``), no others."""

    outcome: str | None = None
    error: str | None = None
    duration_ms: float | None = None
    operation_id: str | None = None


class KeptCallEnd(BaseModel):
    """A call row's later write (written with ``exclude_unset=True``: a change names only what it sets)."""

    call_id: str
    changes: CallRowChanges


class KeptOperationEnd(BaseModel):
    """The end of an operation this store does not keep (a fleet operation)."""

    operation_id: str
    status: str
    message: str | None = None
    #: a kept write of an older version has none (then now is the nearest)
    ended_at: datetime | None = None

"""What of the MCP SDK the MCP door imports. The request-state cryptography is deferred
(gateway/mcp/sdk_crypto.py): nothing of ``cryptography`` is loaded by importing the door and building its
server; the first seal loads it and the SDK's own AES-GCM codec then seals, opens and refuses a changed
token as it does without the deferral. The SDK's package ``__init__`` and httpx2 run when first used
(gateway/mcp/sdk_package.py). Each check runs in a fresh interpreter, since what is in ``sys.modules`` is
the point."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from tests.helpers.timing import scaled

ROOT = Path(__file__).resolve().parents[2]

CHILD = r"""
import sys

import gateway.mcp  # the door: the SDK's request-state module is imported with cryptography deferred
from gateway.config import Settings
from gateway.mcp.sdk_crypto import DeferredCodec, deferred_request_state_security
from mcp.server.mcpserver import MCPServer
import mcp.server.request_state as request_state

assert not [m for m in sys.modules if m.split(".")[0] == "cryptography"], "loaded at import"
server = MCPServer("fleet-gateway", request_state_security=deferred_request_state_security())
assert "cryptography" not in sys.modules, "loaded by MCPServer.__init__"

codec = DeferredCodec()
token = codec.seal(b"state")
assert "cryptography.hazmat.primitives.ciphers.aead" in sys.modules, "the first seal loads it"
from cryptography.exceptions import InvalidTag
from cryptography.hazmat.primitives.ciphers.aead import AESGCM
assert request_state.AESGCM is AESGCM and request_state.InvalidTag is InvalidTag, "the SDK has the real names"
assert codec.unseal(token) == b"state"
assert DeferredCodec().seal(b"state") != token  # a key of its own

changed = token[:-2] + ("A" if token[-2] != "A" else "B") + token[-1]
try:
    codec.unseal(changed)
except request_state.InvalidRequestState as refused:
    assert str(refused) == "seal", refused  # the SDK's except clause caught the real InvalidTag
else:
    raise AssertionError("a changed token was opened")

# the SDK's own policy with shared keys works as it does without the deferral
keyed = request_state.RequestStateSecurity(keys=["k" * 32])
assert keyed.codec.unseal(keyed.codec.seal(b"x")) == b"x"
print("ok")
"""

LATE = r"""
import sys
import cryptography.exceptions  # loaded before the door: nothing is deferred, nothing replaced
import gateway.mcp
import mcp.server.request_state as request_state
from cryptography.exceptions import InvalidTag
assert request_state.InvalidTag is InvalidTag
print("ok")
"""


PACKAGE = r"""
import sys
import gateway.mcp
import mcp.server.mcpserver.resources.types as resource_types

assert not [m for m in sys.modules if m.startswith("mcp.client") or m.split(".")[0] == "httpx2"], "loaded"
from mcp import ClientSession, types  # a name of the package's __init__: the __init__ runs
import mcp
from mcp.client.session import ClientSession as Session
assert ClientSession is Session and mcp.Client is not None and types.Tool is mcp.types.Tool
assert "mcp.client.streamable_http" in sys.modules  # what the __init__ imports, and httpx2 with it
import httpx2
assert resource_types.httpx2.AsyncClient is httpx2.AsyncClient  # the SDK's stand-in answers from httpx2
assert sys.modules["httpx2"] is httpx2 and httpx2.__file__
try:
    mcp.no_such_name
except AttributeError as missing:
    assert "no_such_name" in str(missing)
else:
    raise AssertionError("a name the package does not have")
print("ok")
"""

FIRST_USE = r"""
import sys
import gateway.mcp
import mcp.server.mcpserver.resources.types as resource_types
assert "httpx2" not in sys.modules
assert resource_types.httpx2.Timeout(3.0).read == 3.0  # the first use imports httpx2
assert "httpx2" in sys.modules and sys.modules["httpx2"] is not resource_types.httpx2
print("ok")
"""


def run_child(code: str) -> str:
    done = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=scaled(120)
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout.strip()


def test_cryptography_is_loaded_by_the_first_seal_and_the_sdk_codec_works() -> None:
    assert run_child(CHILD) == "ok"


def test_cryptography_imported_before_the_door_is_left_as_it_is() -> None:
    assert run_child(LATE) == "ok"


def test_the_sdk_package_init_runs_when_a_name_of_it_is_first_asked() -> None:
    assert run_child(PACKAGE) == "ok"


def test_httpx2_is_imported_by_its_first_use_in_the_sdk() -> None:
    assert run_child(FIRST_USE) == "ok"

"""The MCP door. Before any MCP SDK module is imported, the SDK is set up to import only what a server
uses: its package without its ``__init__`` (which imports the client) and httpx2 when first used
(gateway/mcp/sdk_package.py), and its request-state module with cryptography deferred to the first
sealed request state (gateway/mcp/sdk_crypto.py). uvicorn's command line is kept out of the SDK's
sse_starlette (gateway/util/lean_uvicorn.py). The SDK's wire types are imported first, their validators
built when first used (gateway/util/deferred_models.py)."""

import gateway.util.lean_uvicorn  # noqa: F401
from gateway.mcp.sdk_crypto import defer_sdk_cryptography
from gateway.mcp.sdk_package import httpx2_when_used, install_bare_package
from gateway.util.deferred_models import import_with_models_deferred

import_with_models_deferred("mcp_types", "mcp_types.methods")
install_bare_package()
with httpx2_when_used():
    defer_sdk_cryptography()  # imports mcp.server and what it imports

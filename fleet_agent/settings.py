"""Environment fallbacks of ``fleet-gateway agent`` (prefix GATEWAY_AGENT_; command-line options win)."""

from __future__ import annotations

import os

from pydantic import Field
from pydantic_settings import BaseSettings, SettingsConfigDict


class AgentSettings(BaseSettings):
    """Defaults for the agent host, read from the environment."""

    model_config = SettingsConfigDict(env_prefix="GATEWAY_AGENT_", env_file=".env", extra="ignore")

    mcp_url: str = Field("http://127.0.0.1:8765/mcp", description="The gateway's MCP endpoint.")
    token: str | None = Field(None, description="Bearer token for the gateway's /mcp (an agent token).")
    endpoint: str = Field(
        "http://127.0.0.1:11434/v1",
        description="OpenAI-compatible base URL (Ollama default shown; LM Studio: http://127.0.0.1:1234/v1).",
    )
    model: str | None = Field(None, description="Model name at the endpoint.")
    api_key: str | None = Field(None, description="API key of the endpoint; falls back to OPENAI_API_KEY.")
    decoding: str = Field(
        "json_schema",
        pattern="^(json_schema|ollama|guided|none)$",
        description="How the plan is decoded under its JSON schema: json_schema (response_format: llama.cpp, "
        "LM Studio, OpenAI), ollama (format), guided (vLLM guided_json) or none (validated only).",
    )
    nearest: int = Field(0, ge=0, le=8, description="Pool examples nearest a request, after the fixed ones.")
    places_url: str | None = Field(None, description="An MCP server (Streamable HTTP) of named places.")
    places_tool: str = Field("find_place", description="Its tool that gives a place's lat_deg, lon_deg.")

    def resolved_api_key(self) -> str:
        """The key to send: GATEWAY_AGENT_API_KEY, else OPENAI_API_KEY, else a placeholder that local
        servers (Ollama, LM Studio, llama.cpp) accept."""
        return self.api_key or os.environ.get("OPENAI_API_KEY") or "not-needed"

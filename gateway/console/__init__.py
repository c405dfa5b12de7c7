"""The operator console: a page at /console on the gateway's own port, for the people watching agents fly.

The page and its assets (``static/``: the page's own modules and the vendored libraries, see
``static/vendor/VENDORED.md``) are public: they hold no data. Everything the page shows comes from the
REST API with the operator's or viewer's bearer token (kept in the tab's sessionStorage, sent as an
Authorization header, never in a URL): ``GET /api/v1/console`` (settings and who you are),
``GET /api/v1/events`` (the live stream), and the REST routes operators already use for actions, so the
console's buttons go through the same command path, checks and audit as ``curl``.
"""

from __future__ import annotations

from pathlib import Path
from urllib.parse import urlsplit

from fastapi import APIRouter, FastAPI, Request
from fastapi.responses import FileResponse, RedirectResponse
from fastapi.staticfiles import StaticFiles
from pydantic import BaseModel, Field

from gateway.api.deps import GatewayDep, PrincipalDep

STATIC_DIR = Path(__file__).resolve().parent / "static"
PAGE = "/console"
ASSETS = "/console/static"


def content_security_policy(tiles_url: str | None) -> str:
    """Only this server's scripts and connections; images also from the tile server when one is set.

    Inline styles stay allowed: Leaflet positions its layers and icons with them."""
    images = "'self' data:"
    if tiles_url and tiles_url.startswith(("http://", "https://")):
        parts = urlsplit(tiles_url)
        host = parts.netloc.replace("{s}", "*")  # Leaflet's subdomains: a.tile..., b.tile...
        images += f" {parts.scheme}://{host}"
    return (
        "default-src 'self'; script-src 'self'; connect-src 'self'; "
        f"img-src {images}; style-src 'self' 'unsafe-inline'; "
        "frame-ancestors 'none'; base-uri 'none'; form-action 'none'"
    )


def install_console(app: FastAPI) -> None:
    """Serve /console and its assets from the package (no CDN: it works offline)."""
    settings = app.state.gateway.settings
    headers = {
        "Content-Security-Policy": content_security_policy(settings.console_tiles_url),
        "Cache-Control": "no-cache",
        "Referrer-Policy": "no-referrer",
        "X-Content-Type-Options": "nosniff",
    }
    app.mount(ASSETS, StaticFiles(directory=STATIC_DIR), name="console-assets")

    @app.get(PAGE, include_in_schema=False)
    async def console_page() -> FileResponse:
        return FileResponse(STATIC_DIR / "index.html", media_type="text/html", headers=headers)

    @app.get(PAGE + "/", include_in_schema=False)
    async def console_slash() -> RedirectResponse:
        return RedirectResponse(PAGE)


class ConsoleConfig(BaseModel):
    principal: str = Field(description="Who the token names (operator-xxxxxxxx, viewer-..., anonymous).")
    role: str = Field(description="operator (may act) or viewer (reads only).")
    tiles_url: str | None = Field(description="Tile URL template of the map; None: drawn without tiles.")
    tiles_attribution: str
    version: str


router = APIRouter(tags=["console"])


@router.get(
    "/console", response_model=ConsoleConfig, summary="The operator console's settings, and who you are"
)
async def console_config(request: Request, gateway: GatewayDep, who: PrincipalDep) -> ConsoleConfig:
    settings = gateway.settings
    return ConsoleConfig(
        principal=who.name,
        role=who.role,
        tiles_url=settings.console_tiles_url,
        tiles_attribution=settings.console_tiles_attribution,
        version=request.app.version,
    )

"""`make swarm-test`: deploy/docker-compose.yml run for real with podman, flown from outside.

    .venv/bin/python scripts/swarm_test.py [--base-only]

1. Environment: podman, buildah, runc, netavark, aardvark-dns, iptables and debootstrap from Debian when
   missing (as root), podman-compose >= 1.1 from PyPI; podman runs with a containers.conf of this
   script's (ulimits within the host's hard limits, runc, netavark).
2. Base image: the Dockerfile's FROM (python:3.11-slim) when it is present or can be pulled; otherwise a
   local one built once from Debian packages with debootstrap (Debian's python3.11 in a venv at /usr/local,
   the host's CA bundle) and kept as localhost/fleet-gateway-base:bookworm, the only thing left behind.
3. A probe container runs; if none can, the script says why and exits 0 having skipped (CI stays green on
   machines that cannot run containers).
4. Leftovers of an earlier run that was killed are removed (by their labels). The image is built from
   deploy/Dockerfile, the compose project comes up (a gateway and five simulated
   drones, each in its own container at its own address; the registrars wait for the gateway themselves),
   and a real MCP client on the host flies fleet_takeoff, formation_goto (wedge) and fleet_land, then
   checks each drone's final position.
5. Teardown: compose down, then every container, volume, network and image the run made is removed and
   checked gone. The last line states what was flown and the figures.

With ``--hand-image-over`` a run that passed leaves its gateway image for scripts/cluster_test.py, which
runs the same image and removes it (it builds its own when none was handed over, or one built from other
sources): CI builds the gateway image once for both tests. The image carries the digest of what it was
built from (the Dockerfile's COPY sources and the base image) as a label; a handed-over image whose digest
is not the tree's is a leftover, removed by either script.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import fcntl
import hashlib
import json
import os
import resource
import secrets
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import AsyncIterator, Callable, Iterator
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tests.swarm.topology import DRONES, LOCK_PATH, drone_home, drone_id  # noqa: E402

COMPOSE_FILE = ROOT / "deploy" / "docker-compose.yml"
DOCKERFILE = ROOT / "deploy" / "Dockerfile"
UPSTREAM_BASE = "python:3.11-slim"
LOCAL_BASE = "localhost/fleet-gateway-base:bookworm"
PROJECT = "fleet-gateway-swarm-test"
IMAGE = "fleet-gateway:latest"  # the compose file's
TEST_LABEL = "io.fleet-gateway.test"  # on the images a test run builds: its project's name
SOURCES_LABEL = "io.fleet-gateway.sources"  # on every image a run builds: build_digest() of its sources
PREPARED = "fleet-gateway-prepared"  # TEST_LABEL of the images scripts/compose_images.py builds ahead
COMPOSE_PROJECT_LABEL = "io.podman.compose.project"
# the compose test projects on this machine: each run's leftover check leaves the other's objects alone,
# so that the two can run at once (scripts/compose_images.py, CI)
CLUSTER_PROJECT = "fleet-gateway-cluster-test"  # scripts/cluster_test.py's
TEST_PROJECTS = (PROJECT, CLUSTER_PROJECT)
PREPARED_HELP = (
    "run the images `scripts/compose_images.py prepare` built ahead from these sources and leave them to "
    "`scripts/compose_images.py remove` (CI builds them while the test suite runs)"
)
# podman's networks: netavark with aardvark-dns (service names resolve) and iptables (published ports).
# podman-compose comes from PyPI (the dev extra): Debian's 1.0.3 ignores ipam subnets and fixed addresses.
DEBIAN_PACKAGES = ("podman", "buildah", "runc", "netavark", "aardvark-dns", "iptables", "debootstrap")
COMPOSE_MIN = (1, 1)
DEBIAN_MIRROR = "http://deb.debian.org/debian"
SKIPPED = 0  # exit status when the machine cannot run containers: a skip, said in the last line
WAIT_S = 240.0
CONTAINER_ULIMIT = 20000  # open files and processes per container (measured: runc refused 96365 processes)


class Skip(Exception):
    """The machine cannot run the swarm test (no podman, no containers); the message says why."""


class Failed(Exception):
    """The swarm test ran and something did not work."""


LOG_PREFIX = ["swarm-test"]  # scripts/cluster_test.py says cluster-test


def log(message: str) -> None:
    print(f"{LOG_PREFIX[0]}: {message}", flush=True)


def run(argv: list[str], *, check: bool = True, timeout: float | None = None, **kw: Any) -> str:
    """Run a command, return its stdout; on failure raise Failed with the command and its output tail.
    The command runs in its own session: a signal meant for this script (a CI time limit's SIGINT to the
    whole process group) reaches it only through this script, which stops it or lets its teardown finish."""
    try:
        done = subprocess.run(
            argv, capture_output=True, text=True, timeout=timeout, check=False, start_new_session=True, **kw
        )
    except subprocess.TimeoutExpired as exc:
        raise Failed(f"{' '.join(argv[:4])} ... did not finish within {timeout:.0f} s") from exc
    if check and done.returncode != 0:
        tail = "\n".join((done.stdout + done.stderr).strip().splitlines()[-25:])
        raise Failed(f"{' '.join(argv)} exited {done.returncode}:\n{tail}")
    return done.stdout


# --- 1. environment --------------------------------------------------------------------------------------


def install_missing() -> None:
    if shutil.which("dpkg-query") is None:
        if shutil.which("podman"):
            return  # not Debian: use what is there
        raise Skip("podman is missing and this is not a Debian system")
    listed = subprocess.run(
        ["dpkg-query", "-W", "-f", "${Package} ${db:Status-Status}\\n", *DEBIAN_PACKAGES],
        capture_output=True, text=True, check=False,
    ).stdout  # fmt: skip
    installed = {line.split()[0] for line in listed.splitlines() if line.endswith(" installed")}
    missing = [pkg for pkg in DEBIAN_PACKAGES if pkg not in installed]
    if not missing:
        return
    if os.geteuid() != 0 or shutil.which("apt-get") is None:
        raise Skip(f"missing {', '.join(missing)} and cannot install them (needs root and apt-get)")
    log(f"installing from Debian: {' '.join(missing)}")
    env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
    try:
        run(["apt-get", "update", "-qq"], env=env, timeout=300)
        run(["apt-get", "install", "-y", "-qq", "--no-install-recommends", *missing], env=env, timeout=600)
    except Failed as exc:
        raise Skip(f"could not install {', '.join(missing)}: {exc}") from None


def podman_compose() -> str:
    """podman-compose of this Python environment (>= 1.1), installed into it from PyPI when missing."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        found = tuple(int(p) for p in version("podman-compose").split(".")[:2])
    except (PackageNotFoundError, ValueError):
        found = (0, 0)
    if found < COMPOSE_MIN:
        log("installing podman-compose from PyPI into this environment")
        try:
            run([sys.executable, "-m", "pip", "install", "-q", "podman-compose>=1.1"], timeout=300)
        except Failed as exc:
            raise Skip(f"podman-compose >= 1.1 is missing and could not be installed: {exc}") from None
    return str(Path(sys.executable).parent / "podman-compose")


def containers_conf(workdir: Path) -> dict[str, str]:
    """A containers.conf of this run's own (podman reads it instead of /etc's through CONTAINERS_CONF):
    container ulimits within this host's hard limits (podman's defaults exceed a sandbox's), and runc
    (crun refuses cgroups in hybrid mode)."""
    limits = []
    for name, which in (("nofile", resource.RLIMIT_NOFILE), ("nproc", resource.RLIMIT_NPROC)):
        hard = resource.getrlimit(which)[1]
        value = CONTAINER_ULIMIT if hard == resource.RLIM_INFINITY else min(hard, CONTAINER_ULIMIT)
        limits.append(f'"{name}={value}:{value}"')
    lines = ["[containers]", f"default_ulimits = [{', '.join(limits)}]", "[engine]"]
    if shutil.which("runc"):
        lines.append('runtime = "runc"')
    if Path("/usr/lib/podman/netavark").is_file():
        lines += ["[network]", 'network_backend = "netavark"']
    path = workdir / "containers.conf"
    path.write_text("\n".join(lines) + "\n")
    return {**os.environ, "CONTAINERS_CONF": str(path)}


# --- 2. base image ---------------------------------------------------------------------------------------


def image_exists(name: str, env: dict[str, str]) -> bool:
    return subprocess.run(["podman", "image", "exists", name], env=env, check=False).returncode == 0


def base_image(env: dict[str, str]) -> str:
    if image_exists(UPSTREAM_BASE, env):
        return UPSTREAM_BASE
    if image_exists(LOCAL_BASE, env):
        log(f"base image: {LOCAL_BASE} (cached)")
        return LOCAL_BASE
    pulled = subprocess.run(
        ["podman", "pull", "-q", f"docker.io/library/{UPSTREAM_BASE}"],
        env=env, capture_output=True, text=True, timeout=300, check=False,
    )  # fmt: skip
    if pulled.returncode == 0:
        log(f"base image: {UPSTREAM_BASE} (pulled)")
        return UPSTREAM_BASE
    reason = (pulled.stderr.strip().splitlines() or ["no answer"])[-1]
    log(f"no image registry ({reason[:120]}); building {LOCAL_BASE} from Debian packages (once)")
    build_local_base(env)
    return LOCAL_BASE


def build_local_base(env: dict[str, str]) -> None:
    """Debian bookworm (minbase) with python3.11 in a venv at /usr/local, as the official image has it."""
    started = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="fgw-base-") as tmp:
        rootfs = Path(tmp) / "rootfs"
        try:
            run(
                ["debootstrap", "--variant=minbase", "--include=python3,python3-venv,ca-certificates",
                 "bookworm", str(rootfs), DEBIAN_MIRROR],
                timeout=900,
            )  # fmt: skip
        except Failed as exc:
            raise Skip(f"cannot build a base image (no registry, and debootstrap failed): {exc}") from None
        # package downloads may pass a TLS-inspecting proxy: the image trusts what this host trusts
        host_ca = Path("/etc/ssl/certs/ca-certificates.crt")
        if host_ca.is_file():
            shutil.copyfile(host_ca, rootfs / "etc/ssl/certs/ca-certificates.crt")
        run(["chroot", str(rootfs), "python3", "-m", "venv", "/usr/local"], timeout=300)
        for junk in (
            "var/cache/apt",
            "var/lib/apt/lists",
            "usr/share/doc",
            "usr/share/man",
            "usr/share/info",
        ):
            shutil.rmtree(rootfs / junk, ignore_errors=True)
            (rootfs / junk).mkdir(parents=True, exist_ok=True)
        changes = [
            "ENV PATH=/usr/local/bin:/usr/local/sbin:/usr/bin:/usr/sbin:/bin:/sbin",
            "ENV LANG=C.UTF-8",
            "ENV PIP_CERT=/etc/ssl/certs/ca-certificates.crt",
            "ENV SSL_CERT_FILE=/etc/ssl/certs/ca-certificates.crt",
            'CMD ["python3"]',
        ]
        tar = subprocess.Popen(["tar", "-C", str(rootfs), "-c", "."], stdout=subprocess.PIPE)
        imported = subprocess.run(
            ["podman", "import", *(a for c in changes for a in ("--change", c)), "-", LOCAL_BASE],
            stdin=tar.stdout, env=env, capture_output=True, text=True, check=False,
        )  # fmt: skip
        assert tar.stdout is not None
        tar.stdout.close()
        tar.wait()
        if imported.returncode != 0:
            raise Skip(f"podman import of the base image failed: {imported.stderr.strip()[-300:]}")
    log(f"built {LOCAL_BASE} in {time.monotonic() - started:.0f} s")


# --- 3. probe --------------------------------------------------------------------------------------------


def probe(base: str, env: dict[str, str]) -> None:
    """A container runs on podman's default bridge network (netavark, iptables), or the test is skipped."""
    done = subprocess.run(
        ["podman", "run", "--rm", base, "python3", "-c", "print('ok')"],
        env=env, capture_output=True, text=True, timeout=180, check=False,
    )  # fmt: skip
    if done.returncode != 0 or "ok" not in done.stdout:
        raise Skip(f"podman cannot run a container here: {done.stderr.strip()[-300:]}")


# --- 4. build, bring up, fly --------------------------------------------------------------------------------


def snapshot(env: dict[str, str], project: str = PROJECT) -> dict[str, set[str]]:
    """What podman holds now: container ids, volume names, network names, image ids; without what the
    other compose test project (``TEST_PROJECTS``) holds, which may be running beside this one."""
    others = [p for p in TEST_PROJECTS if p != project]

    def listed(*argv: str, label: str = COMPOSE_PROJECT_LABEL) -> set[str]:
        found = set(run(["podman", *argv], env=env, timeout=120).split())
        for other in others:
            found -= set(
                run(["podman", *argv, "--filter", f"label={label}={other}"], env=env, timeout=120).split()
            )
        return found

    return {
        "containers": listed("ps", "-a", "-q", "--no-trunc"),
        "volumes": listed("volume", "ls", "-q"),
        "networks": listed("network", "ls", "-q"),
        "images": listed("images", "-a", "-q", "--no-trunc", label=TEST_LABEL),
    }


@contextlib.contextmanager
def swarm_lock() -> Iterator[None]:
    """The compose network's addresses are the namespace swarm test's (tests/swarm/topology.py): hold
    its lock so the two never build that subnet at once on one machine."""
    fd = os.open(LOCK_PATH, os.O_RDWR | os.O_CREAT, 0o600)
    deadline = time.monotonic() + 900
    try:
        while True:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                if time.monotonic() > deadline:
                    raise Failed(f"another swarm run held {LOCK_PATH} for 900 s") from None
                time.sleep(1)
        yield
    finally:
        os.close(fd)


def sigterm_interrupts() -> None:
    """SIGTERM stops the run as Ctrl-C does (KeyboardInterrupt), so its teardown still runs."""

    def interrupt(_signum: int, _frame: object) -> None:
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, interrupt)


@contextlib.contextmanager
def signals_deferred() -> Iterator[None]:
    """SIGINT and SIGTERM noted but not acted on inside; raised as KeyboardInterrupt once out."""
    caught: list[int] = []
    handlers = {
        sig: signal.signal(sig, lambda n, _f: caught.append(n)) for sig in (signal.SIGINT, signal.SIGTERM)
    }
    try:
        yield
    finally:
        for sig, handler in handlers.items():
            signal.signal(sig, handler)
    if caught:
        log(f"teardown finished; now stopping for signal {caught[0]}")
        raise KeyboardInterrupt


def build_digest(base: str, containerfile: Path = DOCKERFILE) -> str:
    """SHA-256 over the base image's name, the Containerfile and every file its COPY lines take from the
    repository (compiled bytecode left out): equal digests, equal builds."""
    digest = hashlib.sha256(f"{base}\n".encode())
    digest.update(containerfile.read_bytes())
    sources: list[Path] = []
    for line in containerfile.read_text().splitlines():
        words = line.split()
        if words[:1] == ["COPY"]:
            sources += [ROOT / word for word in words[1:-1] if not word.startswith("--")]
    files = sorted(
        path
        for source in sources
        for path in ([source] if source.is_file() else source.rglob("*"))
        if path.is_file() and "__pycache__" not in path.parts
    )
    for path in files:
        digest.update(f"{path.relative_to(ROOT)}\n".encode())
        digest.update(hashlib.sha256(path.read_bytes()).digest())
    return digest.hexdigest()


def image_label(image: str, label: str, env: dict[str, str]) -> str:
    """The value of ``label`` on ``image`` ("" when the image or the label is missing)."""
    done = subprocess.run(
        ["podman", "image", "inspect", image, "--format", f'{{{{index .Labels "{label}"}}}}'],
        env=env, capture_output=True, text=True, check=False, timeout=60,
    )  # fmt: skip
    value = done.stdout.strip() if done.returncode == 0 else ""
    return "" if value == "<no value>" else value


def build_image(image: str, containerfile: Path, base: str, owner: str, env: dict[str, str]) -> None:
    """``podman build`` of ``containerfile`` on ``base`` as ``image``, labelled with its owner (a test
    project, or ``PREPARED``) and the digest of its sources."""
    sources = build_digest(base, containerfile)
    run(
        ["podman", "build", "--layers=false", "--build-arg", f"BASE_IMAGE={base}",
         "--label", f"{TEST_LABEL}={owner}", "--label", f"{SOURCES_LABEL}={sources}",
         "-f", str(containerfile), "-t", image, str(ROOT)],
        env=env, timeout=1200,
    )  # fmt: skip


def image_mb(image: str, env: dict[str, str]) -> int:
    return round(
        int(run(["podman", "image", "inspect", image, "--format", "{{.Size}}"], env=env).strip()) / 1e6
    )


class Swarm:
    """The compose project: built, brought up, torn down; figures collected on the way."""

    compose_file = COMPOSE_FILE
    project = PROJECT

    def __init__(self, env: dict[str, str], base: str, prepared: bool = False) -> None:
        from gateway.util.ports import free_tcp_port

        self.operator = secrets.token_hex(16)
        self.agent = secrets.token_hex(16)
        self.port = free_tcp_port()
        self.base = base
        self.env = {
            **env,
            "GATEWAY_OPERATOR_TOKENS": self.operator,
            "GATEWAY_AGENT_TOKENS": self.agent,
            "GATEWAY_PUBLISH_PORT": str(self.port),
        }
        self.url = f"http://127.0.0.1:{self.port}"
        self.figures: dict[str, Any] = {}
        self.compose_bin = podman_compose()
        self.images: list[str] = []  # built (or taken over) by this run, removed at the end
        self.handed_over: list[str] = []  # left for the next run (--hand-image-over), not removed
        self.prepared = prepared  # run the images scripts/compose_images.py built ahead (and leave them)

    def compose(self, *argv: str, timeout: float = 600) -> str:
        return run(
            [self.compose_bin, "-p", self.project, "-f", str(self.compose_file), *argv],
            env=self.env, timeout=timeout, cwd=ROOT,
        )  # fmt: skip

    def build(self, image: str = IMAGE, containerfile: Path = DOCKERFILE, figure: str = "") -> None:
        """Build ``image`` on the base image (its size and build time are figures ``figure``image_mb...);
        with ``prepared``, run the one built ahead from these sources instead, and leave it."""
        if self.prepared and image_label(image, TEST_LABEL, self.env) == PREPARED:
            if image_label(image, SOURCES_LABEL, self.env) != build_digest(self.base, containerfile):
                raise Failed(
                    f"{image} was built ahead from other sources; run scripts/compose_images.py again"
                )
            self.figures[f"{figure}image_mb"] = image_mb(image, self.env)
            self.figures[f"{figure}build_s"] = 0.0
            log(f"{image} ({self.figures[f'{figure}image_mb']} MB): built ahead from these sources")
            return
        if image_exists(image, self.env):
            raise Failed(f"an image {image} exists already; remove it (podman rmi {image}) and run again")
        started = time.monotonic()
        self.images.append(image)
        build_image(image, containerfile, self.base, self.project, self.env)
        self.figures[f"{figure}build_s"] = round(time.monotonic() - started, 1)
        self.figures[f"{figure}image_mb"] = image_mb(image, self.env)
        log(f"built {image} ({self.figures[f'{figure}image_mb']} MB) in {self.figures[f'{figure}build_s']} s")

    def up(self) -> None:
        started = time.monotonic()
        self.compose("up", "-d")
        asyncio.run(self._wait_ready())
        self.figures["up_s"] = round(time.monotonic() - started, 1)
        log(f"gateway and {DRONES} drones ready in {self.figures['up_s']} s")

    def containers(self) -> list[dict[str, Any]]:
        label = f"label=io.podman.compose.project={self.project}"
        out = run(["podman", "ps", "-a", "--filter", label, "--format", "json"], env=self.env)
        return list(json.loads(out or "[]"))

    def logs(self, name: str, lines: int = 20) -> str:
        done = subprocess.run(
            ["podman", "logs", "--tail", str(lines), name],
            env=self.env, capture_output=True, text=True, check=False, timeout=60,
        )  # fmt: skip
        return (done.stdout + done.stderr).strip()

    def explain(self) -> str:
        parts = []
        for c in self.containers():
            name = c["Names"][0]
            parts.append(f"--- {name} ({c['State']}, exit {c.get('ExitCode')})\n{self.logs(name, 8)}")
        return "\n".join(parts)

    async def _wait_ready(self) -> None:
        import httpx

        want = [drone_id(i) for i in range(DRONES)]
        headers = {"authorization": f"Bearer {self.operator}"}
        deadline = time.monotonic() + WAIT_S
        ready: list[str] = []
        async with httpx.AsyncClient(base_url=self.url, timeout=10, headers=headers) as http:
            while time.monotonic() < deadline:
                with contextlib.suppress(httpx.HTTPError, KeyError, ValueError):
                    items = (await http.get("/api/v1/vehicles")).json()["items"]
                    ready = sorted(v["id"] for v in items if v.get("state") == "ready")
                    if ready == want:
                        break
                await asyncio.sleep(1)
            else:
                raise Failed(f"drones ready after {WAIT_S:.0f} s: {ready}, not {want}\n{self.explain()}")
        registrars = [c for c in self.containers() if "register-drone" in c["Names"][0]]
        failed = [c["Names"][0] for c in registrars if c["State"] != "exited" or c.get("ExitCode") != 0]
        if len(registrars) != DRONES or failed:
            raise Failed(f"registrars did not all succeed: {failed or registrars}\n{self.explain()}")

    def fly(self) -> None:
        try:
            asyncio.run(self._fly())
        except BaseExceptionGroup as group:  # the MCP client's task groups wrap what went wrong
            failed = group.subgroup(lambda e: isinstance(e, Failed))
            while failed is not None and isinstance(failed.exceptions[0], BaseExceptionGroup):
                failed = failed.exceptions[0]
            if failed is not None:
                raise failed.exceptions[0] from None
            raise

    @contextlib.asynccontextmanager
    async def _client(self) -> AsyncIterator[Any]:
        from mcp import Client
        from mcp.client.streamable_http import streamable_http_client
        from mcp.shared._httpx_utils import create_mcp_http_client
        from mcp.types import Implementation

        http = create_mcp_http_client(headers={"authorization": f"Bearer {self.agent}"})
        async with (
            http,
            Client(
                streamable_http_client(f"{self.url}/mcp", http_client=http),
                client_info=Implementation(name="swarm-test", version="1.0"),
            ) as client,
        ):
            yield client

    async def _fly(self) -> None:
        from gateway.fleet import geo

        ids = [drone_id(i) for i in range(DRONES)]

        def ok(result: Any) -> dict[str, Any]:
            if result.is_error:
                raise Failed(result.content[0].text)
            return dict(result.structured_content)

        async with self._client() as c:

            async def operation(tool: str, args: dict[str, Any]) -> dict[str, Any]:
                started = time.monotonic()
                r = ok(await c.call_tool(tool, args))
                while r["status"] == "running":
                    if time.monotonic() - started > WAIT_S:
                        raise Failed(f"{tool} still running after {WAIT_S:.0f} s: {json.dumps(r)[:1500]}")
                    r = ok(await c.call_tool("monitor_fleet", {"operation_id": r["operation_id"]}))
                if r["status"] != "succeeded":
                    raise Failed(f"{tool} ended {r['status']}: {json.dumps(r)[:1500]}")
                self.figures[f"{tool}_s"] = round(time.monotonic() - started, 1)
                log(f"{tool}: {r['status']} in {self.figures[f'{tool}_s']} s")
                return r

            async def positions() -> dict[str, dict[str, Any]]:
                return {row["drone_id"]: row for row in ok(await c.call_tool("list_drones", {}))["drones"]}

            # each drone climbs to its own altitude (10 m and up, staggered so neighbours never share one)
            r = await operation("fleet_takeoff", {"drone_ids": ids, "alt_m": 10})
            told = {m["drone_id"]: m["target_alt_m"] for m in r["drones"]}
            now = await positions()
            for i, d in enumerate(ids):
                lat, lon = (float(x) for x in drone_home(i).split(",")[:2])
                off = geo.horizontal_distance_m(now[d]["lat_deg"], now[d]["lon_deg"], lat, lon)
                if not (now[d]["in_air"] and abs(now[d]["alt_m"] - told[d]) <= 1.5 and off <= 3.0):
                    raise Failed(f"after fleet_takeoff {d} is not {told[d]} m above its home: {now[d]}")
            self.figures["takeoff_alts_m"] = "/".join(f"{told[d]:g}" for d in ids)

            home_lat, home_lon = (float(x) for x in drone_home(DRONES // 2).split(",")[:2])
            centre = geo.offset_position(home_lat, home_lon, 60.0, 0.0)
            r = await operation(
                "formation_goto",
                {"drone_ids": ids, "formation": "wedge", "center_lat_deg": centre[0],
                 "center_lon_deg": centre[1], "alt_m": 15, "spacing_m": 12},
            )  # fmt: skip
            slots = {s["drone_id"]: s for s in r["drones"]}
            now = await positions()
            worst = 0.0
            for d in ids:
                slot, pos = slots[d], now[d]
                off = geo.horizontal_distance_m(
                    pos["lat_deg"], pos["lon_deg"], slot["target_lat_deg"], slot["target_lon_deg"]
                )
                worst = max(worst, off)
                if off > 2.5 or abs(pos["alt_m"] - slot["target_alt_m"]) > 1.5:
                    raise Failed(f"after formation_goto {d} is {off:.1f} m off its slot: {slot} / {pos}")
            self.figures["wedge_worst_off_m"] = round(worst, 2)

            await operation("fleet_land", {"drone_ids": ids})
            now = await positions()
            worst = 0.0
            for d in ids:
                slot, pos = slots[d], now[d]
                off = geo.horizontal_distance_m(
                    pos["lat_deg"], pos["lon_deg"], slot["target_lat_deg"], slot["target_lon_deg"]
                )
                worst = max(worst, off)
                if pos["armed"] or pos["in_air"] or abs(pos["alt_m"]) > 1.0 or off > 3.0:
                    raise Failed(f"after fleet_land {d} is not on the ground below its slot: {pos}")
            self.figures["landed_worst_off_m"] = round(worst, 2)

    def clear_leftovers(self) -> None:
        """Remove what an earlier run of this test left when it was killed: its compose project's
        containers, volumes and networks, and the images it labelled as its own."""
        label = f"label=io.podman.compose.project={self.project}"
        found = run(["podman", "ps", "-a", "-q", "--filter", label], env=self.env, check=False).split()
        for kind in ("volume", "network"):
            found += run(["podman", kind, "ls", "-q", "--filter", label], env=self.env, check=False).split()
        ours = f"label={TEST_LABEL}={self.project}"
        images = run(["podman", "images", "-q", "--filter", ours], env=self.env, check=False).split()
        if found or images:
            log(
                f"removing what an earlier run left: {len(found)} containers, volumes or networks, "
                f"{len(images)} images"
            )
            self.remove_project()
            if images:
                run(["podman", "rmi", "-f", *images], env=self.env, check=False)

    def remove_project(self) -> None:
        label = f"label=io.podman.compose.project={self.project}"
        leftovers = run(["podman", "ps", "-a", "-q", "--filter", label], env=self.env, check=False).split()
        if leftovers:
            run(["podman", "rm", "-f", "-v", *leftovers], env=self.env, check=False)
        for kind in ("volume", "network"):
            names = run(["podman", kind, "ls", "-q", "--filter", label], env=self.env, check=False).split()
            if names:
                run(["podman", kind, "rm", "-f", *names], env=self.env, check=False)

    def down(self, before: dict[str, set[str]]) -> None:
        """Remove everything this run made, then check that podman holds nothing more than before.
        SIGINT and SIGTERM (a CI time limit, Ctrl-C) wait until this is done."""
        with signals_deferred():
            self._down(before)

    def _down(self, before: dict[str, set[str]]) -> None:
        started = time.monotonic()
        problems = []
        try:
            self.compose("down", "-v", "-t", "10", timeout=300)
        except Failed as exc:
            problems.append(str(exc))
        self.remove_project()
        removed = [image for image in self.images if image not in self.handed_over]
        if removed:  # ours: none existed before
            run(["podman", "rmi", "-f", *removed], env=self.env, check=False)
        after = snapshot(self.env, self.project)
        cache: set[str] = set()  # kept on purpose: the base image, and the image handed over
        for kept in (LOCAL_BASE, *self.handed_over):
            listed = run(["podman", "images", "-q", "--no-trunc", kept], env=self.env, check=False)
            cache |= set(listed.split())
        for kind, names in after.items():
            extra = names - before[kind] - (cache if kind == "images" else set())
            if extra:
                problems.append(f"left behind: {kind} {sorted(extra)}")
        self.figures["down_s"] = round(time.monotonic() - started, 1)
        if problems:
            raise Failed("; ".join(problems))
        kept = f" but {', '.join(self.handed_over)}, handed over" if self.handed_over else ""
        log(f"torn down in {self.figures['down_s']} s; no container, volume, network or image left{kept}")


def swarm_test(env: dict[str, str], base: str, hand_image_over: bool = False, prepared: bool = False) -> str:
    started = time.monotonic()
    with swarm_lock():
        swarm = Swarm(env, base, prepared)
        swarm.clear_leftovers()
        before = snapshot(env)
        error: BaseException | None = None
        try:
            swarm.build()
            swarm.up()
            swarm.fly()
            if hand_image_over and IMAGE in swarm.images:  # passed: the cluster test runs it (and removes it)
                swarm.handed_over.append(IMAGE)
        except BaseException as exc:
            error = exc
        try:
            swarm.down(before)
        except Failed as exc:
            if error is None:
                raise
            log(f"teardown also failed: {exc}")
        if error is not None:
            raise error
    f = swarm.figures
    total = round(time.monotonic() - started, 1)
    return (
        f"swarm-test: PASSED: {DRONES} drones, each in its own container, flown by an MCP client outside: "
        f"fleet_takeoff to {f['takeoff_alts_m']} m {f['fleet_takeoff_s']} s, formation_goto wedge 60 m north "
        f"{f['formation_goto_s']} s (worst {f['wedge_worst_off_m']} m off its slot), fleet_land "
        f"{f['fleet_land_s']} s (worst {f['landed_worst_off_m']} m from below its slot); image "
        f"{f['image_mb']} MB built in {f['build_s']} s, up {f['up_s']} s, down {f['down_s']} s, "
        f"total {total} s; nothing left behind"
        + (f" but the image {IMAGE}, handed over to the cluster test" if swarm.handed_over else "")
    )


def run_on_podman(
    name: str,
    work: Callable[[dict[str, str], str], str],
    *,
    needs_base: bool = True,
    interrupted: str = "after tearing down what it made",
) -> int:
    """A compose script's frame: podman set up (Debian packages, this run's containers.conf, and with
    ``needs_base`` the base image and a probe container), then ``work(env, base)``, whose line is printed.
    Exit status 0; SKIPPED where containers cannot run here, 1 on Failed, 130 on SIGINT or SIGTERM (after
    the work's own teardown), each said in a last line."""
    LOG_PREFIX[0] = name
    sigterm_interrupts()
    try:
        if needs_base:
            install_missing()
        with tempfile.TemporaryDirectory(prefix=f"fgw-{name}-") as tmp:
            env = containers_conf(Path(tmp))
            base = base_image(env) if needs_base else ""
            if needs_base:
                probe(base, env)
            print(work(env, base), flush=True)
            return 0
    except Skip as exc:
        print(f"{name}: SKIPPED: {exc}", flush=True)
        return SKIPPED
    except Failed as exc:
        print(f"{name}: FAILED: {exc}", flush=True)
        return 1
    except KeyboardInterrupt:
        print(f"{name}: INTERRUPTED (SIGINT/SIGTERM) {interrupted}", flush=True)
        return 130


def main() -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--base-only", action="store_true", help="prepare the base image and stop")
    parser.add_argument(
        "--hand-image-over",
        action="store_true",
        help=f"after a pass, leave {IMAGE} for scripts/cluster_test.py (which runs it and removes it)",
    )
    parser.add_argument("--prepared", action="store_true", help=PREPARED_HELP)
    args = parser.parse_args()

    def work(env: dict[str, str], base: str) -> str:
        if args.base_only:
            return f"swarm-test: base image {base} ready; podman runs containers here"
        return swarm_test(env, base, args.hand_image_over, args.prepared)

    return run_on_podman("swarm-test", work)


if __name__ == "__main__":
    sys.exit(main())

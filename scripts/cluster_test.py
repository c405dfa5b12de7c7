"""`make cluster-test`: deploy/docker-compose.cluster.yml run for real with podman; a node killed.

    .venv/bin/python scripts/cluster_test.py

The same environment, base image and probe as scripts/swarm_test.py. Builds the gateway image and, on the
same base, NATS and PostgreSQL from Debian packages (deploy/debian/), brings up NATS, PostgreSQL, the nine
simulated drones and two gateway nodes (node-a, node-b; the file's node-c is left down), waits until the
drones are spread over both nodes, kills node-b's container (SIGKILL: no goodbye, its leases just stop
being renewed), waits until node-a holds every drone, then through node-a's /mcp takes off and lands one
of node-b's former drones. Removes everything it made; its last line states the figures.

The gateway image a passing `scripts/swarm_test.py --hand-image-over` left (built from these same
sources and base image: its digest label says so) is run as it is and removed at the end instead of being
built again; one built from other sources is removed and the image built here.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import sys
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

import swarm_test as s

COMPOSE_FILE = s.ROOT / "deploy" / "docker-compose.cluster.yml"
PROJECT = s.CLUSTER_PROJECT
NATS_IMAGE = "localhost/fleet-gateway-nats:cluster-test"
POSTGRES_IMAGE = "localhost/fleet-gateway-postgres:cluster-test"
DRONES = 9  # the file's simulator service serves nine
NODES = ("node-a", "node-b")


class Cluster(s.Swarm):
    compose_file = COMPOSE_FILE
    project = PROJECT

    def __init__(self, env: dict[str, str], base: str, prepared: bool = False) -> None:
        from gateway.util.ports import free_tcp_port

        super().__init__(env, base, prepared)
        self.ports = {node: free_tcp_port() for node in NODES}
        self.env.update(
            POSTGRES_PASSWORD=s.secrets.token_hex(12),
            NATS_IMAGE=NATS_IMAGE,
            POSTGRES_IMAGE=POSTGRES_IMAGE,
            NODE_A_PORT=str(self.ports["node-a"]),
            NODE_B_PORT=str(self.ports["node-b"]),
            NODE_C_PORT=str(free_tcp_port()),
        )
        self.urls = {node: f"http://127.0.0.1:{port}" for node, port in self.ports.items()}
        self.url = self.urls["node-a"]

    def build_all(self) -> None:
        if not self.take_over_gateway_image():
            self.build()
        debian = s.ROOT / "deploy" / "debian"
        self.build(NATS_IMAGE, debian / "nats.Containerfile", "nats_")
        self.build(POSTGRES_IMAGE, debian / "postgres.Containerfile", "postgres_")

    def take_over_gateway_image(self) -> bool:
        """Whether the swarm test handed its gateway image over, built from these sources on this base
        (then it is this run's, removed at its end); a handed-over one from other sources is removed."""
        if s.image_label(s.IMAGE, s.TEST_LABEL, self.env) != s.PROJECT:
            return False
        if s.image_label(s.IMAGE, s.SOURCES_LABEL, self.env) != s.build_digest(self.base):
            s.log(f"removing {s.IMAGE}: the swarm test left it, built from other sources")
            s.run(["podman", "rmi", "-f", s.IMAGE], env=self.env, timeout=120)
            return False
        self.images.append(s.IMAGE)
        size = int(s.run(["podman", "image", "inspect", s.IMAGE, "--format", "{{.Size}}"], env=self.env))
        self.figures["image_mb"] = round(size / 1e6)
        self.figures["handed_over"] = True
        s.log(f"{s.IMAGE} ({self.figures['image_mb']} MB): the swarm test's, built from these sources")
        return True

    def container(self, service: str) -> str:
        for c in self.containers():
            if c.get("Labels", {}).get("com.docker.compose.service") == service:
                return str(c["Names"][0])
        raise s.Failed(f"no container for {service}\n{self.explain()}")

    def up_cluster(self) -> None:
        started = time.monotonic()
        self.compose("up", "-d", "postgres", "nats", "drones")
        # the nodes open the database on start: wait for it here (podman-compose ignores service_healthy)
        pg = self.container("postgres")
        deadline = time.monotonic() + s.WAIT_S
        while s.run(["podman", "exec", pg, "pg_isready", "-U", "fleet", "-d", "fleet"], env=self.env,
                    check=False, timeout=60).find("accepting connections") < 0:  # fmt: skip
            if time.monotonic() > deadline:
                raise s.Failed(f"PostgreSQL not ready within {s.WAIT_S:.0f} s\n{self.explain()}")
            time.sleep(1)
        self.compose("up", "-d", "--no-deps", *NODES, "register-drones")
        held = asyncio.run(self._wait_cluster(set(NODES), "drones spread over both nodes"))
        self.figures["up_s"] = round(time.monotonic() - started, 1)
        self.figures["spread"] = {n: len(v) for n, v in held.items()}
        self.before_kill = held
        s.log(f"cluster up in {self.figures['up_s']} s; drones held: {self.figures['spread']}")
        registrar = [c for c in self.containers() if "register-drones" in c["Names"][0]]
        failed = [c["Names"][0] for c in registrar if c["State"] != "exited" or c.get("ExitCode") != 0]
        if not registrar or failed:
            raise s.Failed(f"the registrar did not succeed: {failed}\n{self.explain()}")

    async def _wait_cluster(self, nodes: set[str], what: str) -> dict[str, list[str]]:
        """Until node-a sees exactly ``nodes`` alive, each holding some drones, all nine held and ready."""
        import httpx

        headers = {"authorization": f"Bearer {self.operator}"}
        deadline = time.monotonic() + s.WAIT_S
        seen: Any = None
        async with httpx.AsyncClient(base_url=self.url, timeout=10, headers=headers) as http:
            while time.monotonic() < deadline:
                with contextlib.suppress(httpx.HTTPError, KeyError, ValueError):
                    view = (await http.get("/api/v1/cluster")).json()
                    held = {n["node_id"]: n["vehicles"] for n in view["nodes"] if n["alive"]}
                    items = (await http.get("/api/v1/vehicles")).json()["items"]
                    ready = sorted(v["id"] for v in items if v.get("state") == "ready")
                    seen = {"held": held, "ready": ready}
                    if (
                        set(held) == nodes
                        and all(held.values())
                        and sum(len(v) for v in held.values()) == DRONES
                        and len(ready) == DRONES
                    ):
                        return held
                await asyncio.sleep(1)
        raise s.Failed(f"{what}: not within {s.WAIT_S:.0f} s; last seen {seen}\n{self.explain()}")

    def kill_node_b(self) -> None:
        node_b = self.container("node-b")
        s.run(["podman", "kill", "--signal", "KILL", node_b], env=self.env, timeout=60)
        started = time.monotonic()
        s.run(["podman", "stop", "-t", "0", node_b], env=self.env, check=False, timeout=60)  # no restart
        held = asyncio.run(self._wait_cluster({"node-a"}, "node-a holding every drone after node-b died"))
        self.figures["takeover_s"] = round(time.monotonic() - started, 1)
        s.log(
            f"node-b killed; node-a holds all {len(held['node-a'])} drones "
            f"after {self.figures['takeover_s']} s"
        )

    def fly_taken_over(self) -> None:
        try:
            asyncio.run(self._fly_one())
        except BaseExceptionGroup as group:
            failed = group.subgroup(lambda e: isinstance(e, s.Failed))
            while failed is not None and isinstance(failed.exceptions[0], BaseExceptionGroup):
                failed = failed.exceptions[0]
            if failed is not None:
                raise failed.exceptions[0] from None
            raise

    async def _fly_one(self) -> None:
        drone = sorted(self.before_kill["node-b"])[0]
        self.figures["flown"] = drone

        def ok(result: Any) -> dict[str, Any]:
            if result.is_error:
                raise s.Failed(result.content[0].text)
            return dict(result.structured_content)

        async with self._client() as c:

            async def row() -> dict[str, Any]:
                rows = ok(await c.call_tool("list_drones", {}))["drones"]
                return next(r for r in rows if r["drone_id"] == drone)

            async def operation(tool: str, args: dict[str, Any]) -> dict[str, Any]:
                started = time.monotonic()
                r = ok(await c.call_tool(tool, args))
                while r["status"] == "running":
                    if time.monotonic() - started > s.WAIT_S:
                        raise s.Failed(f"{tool} of {drone} still running after {s.WAIT_S:.0f} s: {r}")
                    r = ok(await c.call_tool("monitor_flight", {"drone_id": drone}))
                return r

            started = time.monotonic()
            r = await operation("takeoff", {"drone_id": drone, "alt_m": 8})
            now = await row()
            if r.get("status") != "succeeded" or not now["in_air"] or abs(now["alt_m"] - 8) > 1.5:
                raise s.Failed(f"takeoff of {drone} through node-a: {r} / {now}")
            r = await operation("land", {"drone_id": drone})
            now = await row()
            if r.get("status") != "succeeded" or now["armed"] or now["in_air"] or abs(now["alt_m"]) > 1.0:
                raise s.Failed(f"land of {drone} through node-a: {r} / {now}")
            self.figures["fly_s"] = round(time.monotonic() - started, 1)
            s.log(
                f"{drone} (node-b's) took off to 8 m and landed through node-a in {self.figures['fly_s']} s"
            )


def cluster_test(env: dict[str, str], base: str, prepared: bool = False) -> str:
    started = time.monotonic()
    cluster = Cluster(env, base, prepared)
    cluster.clear_leftovers()
    before = s.snapshot(env, PROJECT)
    error: BaseException | None = None
    try:
        cluster.build_all()
        cluster.up_cluster()
        cluster.kill_node_b()
        cluster.fly_taken_over()
    except BaseException as exc:
        error = exc
    try:
        cluster.down(before)
    except s.Failed as exc:
        if error is None:
            raise
        s.log(f"teardown also failed: {exc}")
    if error is not None:
        raise error
    f = cluster.figures
    handed = " (the swarm test's)" if f.get("handed_over") else " (built ahead)" if cluster.prepared else ""
    return (
        f"cluster-test: PASSED: NATS and PostgreSQL from Debian packages, two gateway nodes, {DRONES} drones "
        f"spread {f['spread']}; node-b killed, node-a held all {DRONES} after {f['takeover_s']} s and flew "
        f"{f['flown']} (node-b's) up 8 m and down in {f['fly_s']} s; images gateway {f['image_mb']} MB"
        f"{handed}, nats {f['nats_image_mb']} MB, postgres {f['postgres_image_mb']} MB; up {f['up_s']} s, "
        f"down {f['down_s']} s, total {round(time.monotonic() - started, 1)} s; nothing left behind"
    )


def main() -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--prepared", action="store_true", help=s.PREPARED_HELP)
    args = parser.parse_args()
    return s.run_on_podman("cluster-test", lambda env, base: cluster_test(env, base, args.prepared))


if __name__ == "__main__":
    sys.exit(main())

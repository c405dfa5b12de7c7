# Two entry points for a fresh clone: `make demo` and `make test`.
# Both create .venv (Python >= 3.11) and install the project with its dev extras when needed, with uv
# (pip installs it first): on a fresh machine 17 s against pip's 73 s for the same versions (2026-12-01).
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
# Most tests wait on simulated flights: two workers halve the suite's time on two cores.
# Files stay whole on one worker (--dist loadfile), so a module's shared sim + gateway is built once.
# Three workers on a shared 2-core machine (load 3 at the start, up to 19; 2026-11-30): 9 of 1,839
# tests failed on timing (commands timing out, a link lost, a simulated battery drained; the deadlines
# scale by the load at the start only) in 2,561 s: two stay.
TEST_WORKERS ?= 2

.PHONY: install demo test lint docs bench bench-nl swarm-test cluster-test clean

$(STAMP): pyproject.toml
	@echo "Installing fleet-gateway and its dependencies into $(VENV) (about 20 s on a fresh machine)..."
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip uv
	$(BIN)/python -m uv pip install --python $(BIN)/python -e '.[dev]'
	@$(BIN)/python -c "import gateway, mcp, mavsdk_grpc" || { echo "make install: the installation failed (see the pip output above)"; exit 1; }
	@touch $(STAMP)
	@echo "Installed into $(VENV)."

install: $(STAMP)

demo: $(STAMP)
	$(BIN)/fleet-gateway demo

# mypy runs beside the suite (about 40 s of one core on a fresh machine, while the suite mostly waits on
# simulated flights); its report follows the suite's, and either failing fails the target.
test: $(STAMP)
	$(BIN)/ruff check .
	@$(BIN)/mypy > .mypy-report.txt 2>&1 & typing=$$!; \
	echo "$(BIN)/mypy (beside the tests; its report follows theirs)"; \
	echo "$(BIN)/python -m pytest -q -n $(TEST_WORKERS) --dist loadfile --no-loadscope-reorder $(PYTEST_ARGS)"; \
	$(BIN)/python -m pytest -q -n $(TEST_WORKERS) --dist loadfile --no-loadscope-reorder $(PYTEST_ARGS); \
	tests=$$?; wait $$typing; typed=$$?; echo "$(BIN)/mypy:"; cat .mypy-report.txt; rm -f .mypy-report.txt; \
	if [ $$tests -ne 0 ]; then exit $$tests; fi; exit $$typed

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/mypy

# the generated docs: docs/tools.md from the tools the server lists (the verbs' declarations and the
# hand-written reads), the README's settings table and deploy/.env.example from Settings; tests check both
docs: $(STAMP)
	$(BIN)/python scripts/gen_tools_doc.py
	$(BIN)/python scripts/gen_config_doc.py

bench: $(STAMP)
	@for b in bench/*.py; do [ "$$b" = bench/common.py ] && continue; echo "== $$b"; $(BIN)/python $$b || exit 1; done

# Natural-language missions flown by a real model. With ENDPOINT=URL MODEL=NAME it uses that endpoint;
# without, it starts ../shared/llm/serve-local-model (LLM=1.5b or 0.5b) and stops it afterwards.
# BENCH_NL_ARGS passes more options, e.g. BENCH_NL_ARGS="--runs 1 --missions takeoff-land --write".
LLM ?= 1.5b
PROFILE ?= small
bench-nl: $(STAMP)
	$(BIN)/python bench/nl_missions.py \
	  $(if $(ENDPOINT),--endpoint $(ENDPOINT) --model $(MODEL),--serve-local $(LLM)) $(BENCH_NL_ARGS)

# deploy/docker-compose.yml run for real with podman (installed from Debian when missing; as root): the
# image built, a gateway and five simulated drones in their own containers, flown from an MCP client
# outside, everything removed afterwards. Skips, saying why, where containers cannot run.
# SWARM_TEST_ARGS=--hand-image-over leaves the gateway image of a passing run for cluster-test (CI).
swarm-test: $(STAMP)
	$(BIN)/python scripts/swarm_test.py $(SWARM_TEST_ARGS)

# deploy/docker-compose.cluster.yml the same way: NATS and PostgreSQL built from Debian packages, two
# gateway nodes, nine drones; one node's container killed, the other takes its drones over. It runs
# the gateway image swarm-test handed over when that was built from these sources, else builds its own.
cluster-test: $(STAMP)
	$(BIN)/python scripts/cluster_test.py $(CLUSTER_TEST_ARGS)

clean:
	rm -rf $(VENV) .pytest_cache *.db *.db-wal *.db-shm

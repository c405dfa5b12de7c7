"""docs/tools.md is generated from the server's tools/list and must not drift from it."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_tools_doc_is_current() -> None:
    result = subprocess.run(
        [sys.executable, "scripts/gen_tools_doc.py", "--check"], cwd=ROOT, capture_output=True, text=True
    )
    assert result.returncode == 0, result.stdout + result.stderr


def test_tools_doc_lists_every_tool_of_table_b2() -> None:
    text = (ROOT / "docs" / "tools.md").read_text()
    for name in [*B2_TOOLS, "get_telemetry"]:
        assert f"### `{name}`" in text, name


B2_TOOLS = [
    "arm_drone", "disarm_drone", "takeoff", "land", "hold_position", "return_to_launch", "kill_motors",
    "get_battery", "get_position", "get_home_position", "go_to_location", "move_to_relative", "set_max_speed",
    "set_yaw", "reposition", "check_arrival", "monitor_flight", "initiate_mission", "upload_mission",
    "download_mission", "print_mission_progress", "pause_mission", "hold_mission_position", "resume_mission",
    "clear_mission", "set_current_waypoint", "is_mission_finished", "get_flight_mode", "get_health",
    "get_health_all_ok", "get_speed", "get_attitude", "get_gps_info", "get_in_air", "get_armed",
    "get_landed_state", "get_rc_status", "get_heading", "get_imu", "get_odometry", "print_status_text",
    "get_parameter", "set_parameter", "list_parameters", "set_flight_mode",
]  # fmt: skip
assert len(B2_TOOLS) == 45

"""/api/v1/vehicles/{id}/mission: a ground station's mission file in (QGC .plan or QGC WPL 110) and out
(the operator's start, pause and resume of the stored mission are routes their verbs declare,
`gateway.api.declared`).

Each is one Commander call with the operator's caller (``via="rest"``): the upload goes through the same
policy checks as ``upload_mission``, item by item, and a refusal names the item's number (the file's
sequence number) and the rule. How the file's items are read:
`gateway.fleet.missions.mission_files`.
"""

from __future__ import annotations

from typing import Annotated, Literal

from fastapi import APIRouter, Query, Request, Response

from gateway.api.audit import AuditedRoute, note_unchecked
from gateway.api.control import CommandOut, operator
from gateway.api.deps import CommanderDep, CommandVehicleId, PrincipalDep
from gateway.errors import InvalidArgument
from gateway.fleet.missions.mission import MAX_ITEMS

router = APIRouter(tags=["operator control"], route_class=AuditedRoute)

FileFormat = Literal["plan", "waypoints"]
MEDIA = {"plan": "application/json", "waypoints": "text/plain"}
SUFFIX = {"plan": "plan", "waypoints": "waypoints"}
_NUMBER_OR_NULL = {"type": ["number", "null"]}
_SIMPLE_ITEM = {
    "type": "object",
    "required": ["type", "command", "frame", "params"],
    "properties": {
        "type": {"const": "SimpleItem"},
        "command": {"type": "integer", "minimum": 0, "maximum": 65535, "description": "A MAV_CMD."},
        "frame": {"type": "integer", "minimum": 0, "maximum": 255, "description": "A MAV_FRAME."},
        "params": {"type": "array", "items": _NUMBER_OR_NULL, "minItems": 7, "maxItems": 7},
        "autoContinue": {"type": "boolean"},
    },
}
#: what `gateway.fleet.missions.mission_files.parse_plan` reads, as far as a schema says it (the items'
#: meaning is the policy's: a refusal there names the item)
PLAN_SCHEMA = {
    "type": "object",
    "description": "A QGroundControl .plan file (simple items; complex items are refused by name).",
    "required": ["fileType", "mission"],
    "properties": {
        "fileType": {"const": "Plan"},
        "mission": {
            "type": "object",
            "required": ["items"],
            "properties": {
                "items": {"type": "array", "items": _SIMPLE_ITEM, "minItems": 1, "maxItems": MAX_ITEMS},
                "plannedHomePosition": {
                    "type": "array",
                    "items": {"type": "number"},
                    "minItems": 3,
                    "maxItems": 3,
                },
            },
        },
        "geoFence": {"type": "object"},
        "rallyPoints": {"type": "object"},
    },
}
_FILE_BODY = {
    "required": True,
    "content": {
        "application/json": {"schema": PLAN_SCHEMA},
        "text/plain": {
            "schema": {
                "type": "string",
                "description": "A QGC WPL 110 waypoint file: line 0 home, then one item a line.",
                "pattern": r"^\s*QGC WPL 110\s*\n",
            }
        },
    },
}


@router.put(
    "/vehicles/{vehicle_id}/mission",
    response_model=CommandOut,
    summary="Store a mission file on the vehicle (QGC .plan or QGC WPL 110), checked like any mission",
    openapi_extra={"requestBody": _FILE_BODY},
)
async def put_mission_file(
    vehicle_id: CommandVehicleId,
    request: Request,
    commander: CommanderDep,
    who: PrincipalDep,
    file_format: Annotated[
        FileFormat | None,
        Query(alias="format", description="plan or waypoints; default: told from the file."),
    ] = None,
) -> CommandOut:
    """A .plan's geofence becomes the drone's zones (replacing its own, through the geofences' own
    path: all valid or nothing changes) and its rally points are kept beside the mission and written back
    by GET; the mission items are checked against the new zones, and if they are refused the zones are
    put back as they were (the verb `upload_plan`)."""
    try:
        content = (await request.body()).decode("utf-8-sig")
    except UnicodeDecodeError:
        raise InvalidArgument("the mission file is not UTF-8 text") from None
    result = await commander.upload_plan(operator(who), vehicle_id, content, file_format)
    plan = result.facts.get("plan")
    if plan:
        note = getattr(request.state, "audit_note", None) or {}
        request.state.audit_note = {**note, "plan": str(plan)}
    note_unchecked(request, result.facts.get("unchecked"))
    return CommandOut(
        vehicle_id=vehicle_id, action="upload_mission_file", outcome="sent", message=result.message
    )


@router.get(
    "/vehicles/{vehicle_id}/mission",
    summary="The vehicle's mission as a QGC .plan or a QGC WPL 110 file",
    response_class=Response,
    responses={200: {"content": {"application/json": {}, "text/plain": {}}}},
)
async def get_mission_file(
    vehicle_id: CommandVehicleId,
    commander: CommanderDep,
    who: PrincipalDep,
    file_format: Annotated[FileFormat, Query(alias="format", description="plan or waypoints.")] = "plan",
) -> Response:
    """A .plan carries the drone's geofence zones and the rally points kept from its last .plan."""
    view = await commander.export_plan(operator(who), vehicle_id, file_format)
    name = f"{vehicle_id}.{SUFFIX[file_format]}"
    return Response(
        view.content,
        media_type=MEDIA[file_format],
        headers={"Content-Disposition": f'attachment; filename="{name}"'},
    )

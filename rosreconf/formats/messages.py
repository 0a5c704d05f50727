"""The fields of the message types a context variable is most often read from.

rosreconf reads no ROS message definitions (it runs without ROS installed), so a context
declaration's ``field`` is checked only against the types listed here: the scalar wrappers
of ``std_msgs`` and the single-reading messages of ``sensor_msgs``, plus a few with nested
fields. A type not listed is taken on trust (``docs/context.md`` says so); its field is
checked when ``watch`` reads it live. Each field maps to the kind of value it holds, so a
bound on a string or an ``equals: true`` on a number is refused too.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import Literal

FieldKind = Literal["number", "boolean", "string"]
"""What a field holds, as a condition compares it."""

_STD_NUMBERS = ("Float32", "Float64", "Int8", "Int16", "Int32", "Int64", "UInt8", "UInt16")
_STD_NUMBERS_MORE = ("UInt32", "UInt64", "Byte", "Char")
_HEADER: dict[str, FieldKind] = {"header.stamp.sec": "number", "header.frame_id": "string"}
_VECTOR: dict[str, FieldKind] = {"x": "number", "y": "number", "z": "number"}


def _prefixed(prefix: str, fields: Mapping[str, FieldKind]) -> dict[str, FieldKind]:
    return {f"{prefix}.{k}": v for k, v in fields.items()}


_TABLE: dict[str, dict[str, FieldKind]] = {
    **{f"std_msgs/{t}": {"data": "number"} for t in (*_STD_NUMBERS, *_STD_NUMBERS_MORE)},
    "std_msgs/Bool": {"data": "boolean"},
    "std_msgs/String": {"data": "string"},
    "sensor_msgs/BatteryState": {
        **_HEADER,
        **{
            f: "number"
            for f in (
                "voltage",
                "temperature",
                "current",
                "charge",
                "capacity",
                "design_capacity",
                "percentage",
                "power_supply_status",
                "power_supply_health",
                "power_supply_technology",
            )
        },
        "present": "boolean",
        "location": "string",
        "serial_number": "string",
    },
    "sensor_msgs/Range": {
        **_HEADER,
        **{f: "number" for f in ("radiation_type", "field_of_view", "min_range", "max_range")},
        "range": "number",
    },
    "sensor_msgs/Temperature": {**_HEADER, "temperature": "number", "variance": "number"},
    "sensor_msgs/FluidPressure": {**_HEADER, "fluid_pressure": "number", "variance": "number"},
    "sensor_msgs/Illuminance": {**_HEADER, "illuminance": "number", "variance": "number"},
    "sensor_msgs/RelativeHumidity": {
        **_HEADER,
        "relative_humidity": "number",
        "variance": "number",
    },
    "sensor_msgs/NavSatFix": {
        **_HEADER,
        "status.status": "number",
        "status.service": "number",
        **{f: "number" for f in ("latitude", "longitude", "altitude", "position_covariance_type")},
    },
    "geometry_msgs/Vector3": {**_VECTOR},
    "geometry_msgs/Vector3Stamped": {**_HEADER, **_prefixed("vector", _VECTOR)},
    "geometry_msgs/Twist": {**_prefixed("linear", _VECTOR), **_prefixed("angular", _VECTOR)},
}

KNOWN_FIELDS: Mapping[str, Mapping[str, FieldKind]] = MappingProxyType(
    {k: MappingProxyType(v) for k, v in _TABLE.items()}
)
"""Message type (canonical key, ``std_msgs/Float64``) -> field path -> what it holds."""

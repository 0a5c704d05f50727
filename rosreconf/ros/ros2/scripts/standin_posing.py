"""Pose as a ROS 2 type that is not installed: the stand-in's type support copies.

A sibling of ``standin_node.py`` (imported from this folder; it runs under a Python with
rclpy, never imported by rosreconf). The example library's types (``robot_arm_msgs/msg/
DcServoCommand``) exist nowhere: each is posed as a subclass of an installed type
(``std_msgs/msg/String``; services ``std_srvs/srv/Trigger``; actions ``test_msgs`` or
``example_interfaces`` Fibonacci) whose type support handle is a copy of that type's Fast DDS
one (``rosidl_typesupport_fastrtps_c``) with the declared namespace and name, so rmw_fastrtps
announces ``robot_arm_msgs::msg::dds_::DcServoCommand_`` and rclpy's graph API says
``robot_arm_msgs/msg/DcServoCommand``. The copies are of rosidl's C structs, laid out here
with ctypes: their sizes are the Iron+ layouts (the constants below say which fields). The
wire format and type hash are the base type's: two stand-ins posing as one type talk to each
other; a real node with the real type would not match.
"""

from __future__ import annotations

import ctypes
import functools
import importlib
from typing import Any

import std_msgs.msg
import std_srvs.srv
from rclpy.type_support import check_for_type_support

POSING: set[str] = set()
"""The type names posed so far (the ready line lists them)."""
_KEEP: list[Any] = []
"""Every buffer and callback a posed type support points to: alive as long as the process."""
_FAST = b"rosidl_typesupport_fastrtps_c"
_DYNAMIC = b"rosidl_dynamic_typesupport_c"
_P = ctypes.c_void_p
_HANDLE_FN = ctypes.CFUNCTYPE(_P, _P, ctypes.c_char_p)
_API = ctypes.pythonapi
_API.PyCapsule_GetPointer.restype = _P
_API.PyCapsule_GetPointer.argtypes = [ctypes.py_object, ctypes.c_char_p]
_API.PyCapsule_New.restype = ctypes.py_object
_API.PyCapsule_New.argtypes = [_P, ctypes.c_char_p, _P]
_MSG_HANDLE_BYTES = 6 * 8
"""``rosidl_message_type_support_t`` (Iron and later): the typesupport identifier, its data,
the handle function, and three hooks (type hash, type description, description sources)."""
_SRV_HANDLE_BYTES = 11 * 8
"""``rosidl_service_type_support_t``: the identifier, data and handle function, the three
message type supports (request, response, event), and five hooks (event message creation and
destruction, type hash, type description, description sources)."""
_MSG_CALLBACKS_BYTES = 16 * 8
"""More than ``message_type_support_callbacks_t`` holds, so a copy takes all of it; two of its
fields are rewritten in the copy (the namespace and the name)."""
_ACTION_HANDLE_BYTES = 8 * 8
"""``rosidl_action_type_support_t`` (Iron and later): five type supports (goal, result and
cancel services, feedback and status messages) and three hooks."""
POSE_ACTIONS_AS = ("test_msgs", "example_interfaces")
"""Packages whose ``action/Fibonacci`` poses as an action type that is not installed."""
_SRV_CALLBACKS_BYTES = 4 * 8
"""``service_type_support_callbacks_t``: the namespace, the name, and the request and
response message type supports."""


class _Handle(ctypes.Structure):
    _fields_ = [("identifier", ctypes.c_char_p), ("data", _P), ("func", _P)]


def _lookup(handle: int, identifier: bytes) -> int:
    """Return the type support ``identifier`` of ``handle`` (rosidl's dispatch)."""
    h = _Handle.from_address(handle)
    if h.identifier == identifier:
        return handle
    return int(_HANDLE_FN(h.func)(handle, identifier) or 0)


def _copy(address: int, size: int) -> Any:
    buf = ctypes.create_string_buffer(size)
    ctypes.memmove(buf, address, size)
    _KEEP.append(buf)
    return buf


def _text(value: str) -> int:
    s = ctypes.c_char_p(value.encode())
    _KEEP.append(s)
    return int(ctypes.cast(s, _P).value or 0)


def _posed_handle(original: int, size: int, names: tuple[str, str], extra: Any = None) -> int:
    """Copy the Fast DDS type support of ``original`` with another namespace and name."""
    fast = _lookup(original, _FAST)
    if not fast:
        raise RuntimeError("no Fast DDS type support (rmw_fastrtps_cpp is the RMW posed)")
    callbacks_size = _MSG_CALLBACKS_BYTES if extra is None else _SRV_CALLBACKS_BYTES
    callbacks = _copy(_Handle.from_address(fast).data, callbacks_size)
    fields = (_P * 4).from_buffer(callbacks)
    fields[0], fields[1] = _text(names[0]), _text(names[1])
    if extra is not None:
        extra(fields)
    handle = _copy(fast, size)

    def dispatch(_me: int, identifier: bytes) -> int:  # no dynamic one (Kilted asks): the
        if identifier == _DYNAMIC:  # base's dispatch would fail and leave an rcutils error set
            return 0
        return ctypes.addressof(handle) if identifier == _FAST else _lookup(original, identifier)

    func = _HANDLE_FN(dispatch)
    _KEEP.append(func)
    view = _Handle.from_buffer(handle)
    view.data = ctypes.addressof(callbacks)
    view.func = ctypes.cast(func, _P).value
    return ctypes.addressof(handle)


def _posed_class(base: Any, name: str, handle: int, attrs: dict[str, Any]) -> Any:
    meta = type(base)
    capsule = _API.PyCapsule_New(handle, None, None)
    posed_meta = type(
        f"Metaclass_{name}",
        (meta,),
        {"_TYPE_SUPPORT": capsule, "__import_type_support__": classmethod(lambda cls: None)},
    )
    return posed_meta(name, (base,), attrs)


def _installed(pkg: str, folder: str, short: str) -> Any:
    """Return the installed class ``pkg.<folder>.<short>``, or None when no package has it."""
    try:
        return getattr(importlib.import_module(f"{pkg}.{folder}"), short)
    except (ImportError, AttributeError):
        return None


def _posing_base(name: str, base: Any) -> tuple[Any, Any]:
    """Note that ``name`` is posed; return ``base`` and its type support's raw pointer."""
    POSING.add(name)
    check_for_type_support(base)
    return base, _API.PyCapsule_GetPointer(type(base)._TYPE_SUPPORT, None)


def message_class(name: str) -> Any:
    """Return the installed class of ``pkg/msg/Name``, or a String posing as it."""
    pkg, _, short = name.split("/")
    installed = _installed(pkg, "msg", short)
    if installed is not None:
        return installed
    base, original = _posing_base(name, std_msgs.msg.String)
    handle = _posed_handle(original, _MSG_HANDLE_BYTES, (f"{pkg}::msg", short))
    return _posed_class(base, short, handle, {"__slots__": ()})


def _posed_service(original: int, ns: str, short: str) -> int:
    """Copy a service's Fast DDS type support, and its two messages', with other names."""

    def messages(fields: Any) -> None:  # request_members_, response_members_
        fields[2] = _posed_handle(fields[2], _MSG_HANDLE_BYTES, (ns, f"{short}_Request"))
        fields[3] = _posed_handle(fields[3], _MSG_HANDLE_BYTES, (ns, f"{short}_Response"))

    return _posed_handle(original, _SRV_HANDLE_BYTES, (ns, short), messages)


def service_class(name: str) -> Any:
    """Return the installed class of ``pkg/srv/Name``, or a Trigger posing as it."""
    pkg, _, short = name.split("/")
    installed = _installed(pkg, "srv", short)
    if installed is not None:
        return installed
    base, original = _posing_base(name, std_srvs.srv.Trigger)
    return _posed_class(base, short, _posed_service(original, f"{pkg}::srv", short), {})


class CannotPose(Exception):
    """An action type is not installed and no installed action type can pose as it."""


@functools.cache
def action_class(name: str) -> Any:
    """Return the installed class of ``pkg/action/Name``, or a Fibonacci posing as it.

    rcl_action builds an action from five parts of ``rosidl_action_type_support_t``: the
    send_goal and get_result services, the feedback message (these three carry the action's
    name, so they are posed: ``pkg::action::dds_::Name_SendGoal_Request_`` ...), and
    action_msgs' cancel service and status message (the same for every action; kept).
    """
    pkg, _, short = name.split("/")
    installed = _installed(pkg, "action", short)
    if installed is not None:
        return installed
    base = next(filter(None, (_installed(p, "action", "Fibonacci") for p in POSE_ACTIONS_AS)), None)
    if base is None:
        raise CannotPose(
            f"action type {name} is not installed, and no action type to pose as is "
            f"({' or '.join(f'{p}/action/Fibonacci' for p in POSE_ACTIONS_AS)}: install "
            "ros-<distro>-test-msgs or ros-<distro>-example-interfaces beside rclpy)"
        )
    base, original = _posing_base(name, base)
    ns = f"{pkg}::action"
    parts = _copy(original, _ACTION_HANDLE_BYTES)
    fields: Any = (_P * 8).from_buffer(parts)
    fields[0] = _posed_service(fields[0], ns, f"{short}_SendGoal")
    fields[1] = _posed_service(fields[1], ns, f"{short}_GetResult")
    fields[3] = _posed_handle(fields[3], _MSG_HANDLE_BYTES, (ns, f"{short}_FeedbackMessage"))
    return _posed_class(base, short, ctypes.addressof(parts), {})


def load_bases() -> None:
    """Load the type supports posed types are copied from (``standin_zygote.py`` forks after)."""
    for base in (
        std_msgs.msg.String,
        std_srvs.srv.Trigger,
        _installed(POSE_ACTIONS_AS[0], "action", "Fibonacci"),
    ):
        if base is not None:
            check_for_type_support(base)

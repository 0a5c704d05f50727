"""A ROS 2 Python or helper that hangs or talks garbage is named within seconds (issue 32, N8).

Provoked faults: the "interpreters" here are shell scripts that imitate a broken ROS 2
Python, since a real one cannot be made to hang or talk garbage on cue. One hangs on every
run; one answers rosreconf's rclpy check and then, run as a helper (the stand-in zygote),
hangs; one answers the check and then prints lines that are not the helpers' JSON protocol.
Before, the first was reported after 60 s as "cannot import rclpy", the second cost 60 s
with no event, and the third left 13 stand-ins "failed" with the zygote never named. The
reference is what watch writes on stderr, and when.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
import ros2_harness

FAKES = {
    "hangs": "exec sleep 600\n",
    "helper-hangs": 'case "$1" in -c) exit 0;; esac\nexec sleep 600\n',
    "helper-garbage": 'case "$1" in -c) exit 0;; esac\n'
    'while true; do echo "this is not json"; sleep 1; done\n',
}
NAMED = {
    "hangs": "did not answer within 10 s when asked to find rclpy (it hangs)",
    "helper-hangs": "standin_zygote.py) did not answer within 10 s",
    "helper-garbage": "standin_zygote.py) said 'this is not json', not a line of its JSON",
}


@pytest.mark.parametrize("fault", sorted(FAKES))
def test_a_bad_ros2_python_is_named_within_seconds(fault: str, tmp_path: Path) -> None:
    fake = tmp_path / f"fake-python-{fault}"
    fake.write_text("#!/bin/sh\n# provoked fault (tests/test_ros2_bad_python.py)\n" + FAKES[fault])
    fake.chmod(0o755)
    domain = ros2_harness.free_domain()
    env = {**ros2_harness.dds_env(), "ROSRECONF_ROS2_PYTHON": str(fake), "HOME": str(tmp_path)}
    env.pop("CYCLONEDDS_URI", None)
    argv = [sys.executable, "-m", "rosreconf", "watch", "--ros2", "--domain", str(domain),
            "--only", "object_repositioning", "--apply", "--stand-ins", "--once"]  # fmt: skip
    start = time.monotonic()
    watch = subprocess.Popen(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                             text=True, start_new_session=True)  # fmt: skip
    lines: list[tuple[float, str]] = []
    said = threading.Event()

    def read() -> None:
        assert watch.stderr is not None
        for line in watch.stderr:
            lines.append((time.monotonic() - start, line))
            if NAMED[fault] in line:
                said.set()

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    try:
        said.wait(60.0)
    finally:
        if watch.poll() is None:
            os.killpg(watch.pid, signal.SIGINT)
        watch.wait(30)
        reader.join(10)
    named = [(t, line) for t, line in lines if NAMED[fault] in line]
    assert named, "".join(line for _, line in lines)[-3000:]
    seconds, line = named[0]
    assert str(fake) in line  # the interpreter is named
    assert seconds < 25.0, f"named after {seconds:.1f} s"  # before: 60 s or never
    assert not any("Traceback" in text for _, text in lines)

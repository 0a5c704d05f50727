"""A ROS 2 Python or helper that hangs or talks garbage is named within seconds (issue 32, N8).

Provoked faults: the "interpreters" here are shell scripts that imitate a broken ROS 2
Python, since a real one cannot be made to hang or talk garbage on cue. One hangs on every
run; the others are the real Jazzy Python except when run as the stand-in zygote, where one
hangs and one prints lines that are not the helpers' JSON protocol (never taken for an answer:
they go to the helper's log, and the helper that never says ready is named as one that does
not answer). Before, the first was
reported after 60 s as "cannot import rclpy", the second cost 60 s with no event, and the
third left 13 stand-ins "failed" with the zygote never named; then a zygote that failed to
start kept the first stand-ins from starting at all. The zygote only saves CPU: the reference
is what watch writes on stderr, and when, and that ``watch --once`` still ends conformant
(exit 0: every stand-in came up, each started on its own).
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

ROOT = Path(__file__).resolve().parent.parent
JAZZY = ROOT / ".venv-ros2-jazzy" / "bin" / "python"
ZYGOTE = "standin_zygote.py"
FAKES: dict[str, tuple[str, str | None]] = {  # fault -> (what it runs, for which script)
    "hangs": ("exec sleep 600", None),
    "helper-hangs": ("exec sleep 600", ZYGOTE),
    "helper-garbage": ('while true; do echo "this is not json"; sleep 1; done', ZYGOTE),
}
NAMED = {
    "hangs": "did not answer within 10 s when asked to find rclpy (it hangs)",
    "helper-hangs": "standin_zygote.py) did not answer within 10 s",
    "helper-garbage": "standin_zygote.py) did not answer within 10 s",  # never ready
}


@pytest.mark.parametrize("fault", sorted(FAKES))
def test_a_bad_ros2_python_is_named_within_seconds(
    fault: str, domain_id: int, tmp_path: Path
) -> None:
    if not JAZZY.exists():  # make test builds it: missing is a failure, never a skip
        pytest.fail("the Jazzy venv is missing: run `make ros2-venvs`", pytrace=False)
    fake = ros2_harness.fake_python(tmp_path / f"fake-python-{fault}", JAZZY, *FAKES[fault])
    env = {**ros2_harness.dds_env(), "ROSRECONF_ROS2_PYTHON": str(fake), "HOME": str(tmp_path)}
    env.update(ROS_LOG_DIR=str(tmp_path))
    env.pop("CYCLONEDDS_URI", None)
    argv = [sys.executable, "-m", "rosreconf", "watch", "--ros2", "--domain", str(domain_id),
            "--only", "object_repositioning", "--apply", "--stand-ins", "--once",
            "--settle", "150"]  # fmt: skip  # 13 rclpy imports at once, no zygote: slow when busy
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
    helper = fault.startswith("helper")
    try:
        said.wait(60.0)
        if helper:  # the stand-ins start on their own: --once ends by itself
            watch.wait(180)
    finally:
        if watch.poll() is None:
            os.killpg(watch.pid, signal.SIGINT)
        watch.wait(30)
        reader.join(10)
    shown = "".join(line for _, line in lines)[-3000:]
    named = [(t, line) for t, line in lines if NAMED[fault] in line]
    assert named, shown
    seconds, line = named[0]
    assert str(fake) in line  # the interpreter is named
    # before: 60 s or never; after: the 10 s bound and the first read, slower when busy
    assert seconds < 45.0, f"named after {seconds:.1f} s"
    assert not any("Traceback" in text for _, text in lines)
    if fault == "helper-garbage":  # the stray lines are in the log the message names
        log = Path(line.split("; see ", 1)[1].split(")", 1)[0])
        assert "not a protocol line, passed over: this is not json" in log.read_text(), line
    if helper:
        assert len(named) == 1, shown  # said once
        assert watch.returncode == 0, shown  # before: the first stand-ins never started
        assert any("started stand-ins of" in text for _, text in lines), shown

"""One supervisor per ROS domain: the claim, and what a hostile local user cannot do to it.

The claim is an abstract Unix socket (``rosreconf.ros.ros2.domainclaim``); the reference for
an owner's pid is ``Popen.pid``. Each test keeps its claims apart with a scope of its own, so
parallel runs of the suite never meet. The planted cases are what another local user could
put where rosreconf's lock file once lay (a world-writable folder): none may disable the
claim, hang it, or change a file of the user's.
"""

from __future__ import annotations

import os
import socket
import stat
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from rosreconf.ros.ros2.domainclaim import Claim, Owner, claim_domain, claim_name


def test_a_second_claim_on_a_domain_names_the_owner(tmp_path: Path) -> None:
    scope = tmp_path.name  # the claims of this test only
    first = claim_domain(7, scope=scope)
    assert isinstance(first, Claim)
    second = claim_domain(7, scope=scope)
    assert isinstance(second, Owner) and second.pid == os.getpid()
    assert second.message == f"ROS domain 7 is supervised by process {os.getpid()} already"
    assert isinstance(claim_domain(8, scope=scope), Claim)
    first.release()
    with claim_domain(7, scope=scope) as third:
        assert isinstance(third, Claim) and third.held
    assert not third.held


def test_a_claim_is_released_when_its_owner_dies(tmp_path: Path) -> None:
    script = (
        "import sys, time\n"
        "from rosreconf.ros.ros2.domainclaim import claim_domain\n"
        "claim = claim_domain(9, scope=sys.argv[1])\n"
        "print(type(claim).__name__, flush=True)\n"
        "time.sleep(60)\n"
    )
    with subprocess.Popen(
        [sys.executable, "-c", script, tmp_path.name], stdout=subprocess.PIPE
    ) as owner:
        assert owner.stdout is not None
        assert owner.stdout.readline().strip() == b"Claim"
        held = claim_domain(9, scope=tmp_path.name)
        assert isinstance(held, Owner) and held.pid == owner.pid  # the kernel's word
        owner.kill()
        owner.wait(5)
    assert isinstance(claim_domain(9, scope=tmp_path.name), Claim)


def test_a_squatter_that_does_not_listen_is_named_as_nobody_s_pid(tmp_path: Path) -> None:
    squatter = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    with squatter:
        squatter.bind(claim_name(11, tmp_path.name))  # bound, never listening
        owner = claim_domain(11, scope=tmp_path.name)
        assert isinstance(owner, Owner) and owner.pid is None
        assert owner.message == "ROS domain 11 is supervised by another process already"
    assert isinstance(claim_domain(11, scope=tmp_path.name), Claim)


OLD_LOCK_DIR = Path("/run/lock") if os.access("/run/lock", os.W_OK) else Path(tempfile.gettempdir())
"""Where the claim was once a world-writable lock file (what a hostile user would plant)."""


@pytest.mark.parametrize("planted", ["fifo", "directory", "symlink", "hardlink", "huge", "digits"])
def test_nothing_planted_where_a_lock_file_was_disables_the_claim_or_is_touched(
    tmp_path: Path, planted: str
) -> None:
    domain = 9_000_000 + os.getpid() % 100_000  # no DDS domain: only this test plants here
    path = OLD_LOCK_DIR / f"rosreconf-ros2-domain-{domain}.lock"
    mine = tmp_path / "mine.txt"  # a file of the user's that a hard link would point at
    mine.write_text("keep me\n")
    mine.chmod(0o600)
    try:
        if planted == "fifo":
            os.mkfifo(path)
        elif planted == "directory":
            path.mkdir()
        elif planted == "symlink":
            path.symlink_to(tmp_path / "elsewhere")
        elif planted == "hardlink":
            os.link(mine, path)
        elif planted == "huge":
            with path.open("wb") as f:
                f.truncate(2 << 30)  # sparse: 2 GiB read whole would cost 4 GB
        else:
            path.write_text("9" * 5000)
        script = (
            "import sys\n"
            "from rosreconf.ros.ros2.domainclaim import claim_domain\n"
            "claim = claim_domain(int(sys.argv[1]))\n"
            "print(type(claim).__name__, flush=True)\n"
            "sys.stdin.read()\n"
        )
        argv = [sys.executable, "-c", script, str(domain)]
        with subprocess.Popen(argv, stdin=subprocess.PIPE, stdout=subprocess.PIPE) as first:
            assert first.stdout is not None
            assert first.stdout.readline().strip() == b"Claim"  # taken, not hung, not skipped
            second = subprocess.run(
                argv,
                input=b"",
                capture_output=True,
                timeout=60,
                check=True,
            )
            assert second.stdout.strip() == b"Owner"  # the two exclude each other
            assert first.stdin is not None
            first.stdin.close()
        assert mine.read_text() == "keep me\n" and stat.S_IMODE(mine.stat().st_mode) == 0o600
        assert not (tmp_path / "elsewhere").exists()  # nothing made through the link
    finally:
        if path.is_dir() and not path.is_symlink():
            path.rmdir()
        else:
            path.unlink(missing_ok=True)

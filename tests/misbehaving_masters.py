"""Fake ROS masters that misbehave on the wire, on 127.0.0.1, for the hang and swell tests.

These are FAKES that provoke faults a real rosmaster cannot show: ``DripMaster`` answers every
XML-RPC call correctly but sends its answer one byte every ``interval`` seconds (each read
arrives well within a per-read timeout, the whole answer takes minutes); ``EndlessMaster``
answers with an XML-RPC array that never ends. Each serves one connection at a time in a
daemon thread, stops writing as soon as the client hangs up, and stops by itself after
``lifetime`` seconds, so no test can leave one running.

Run as a script to serve one until Ctrl-C (used to measure ``rosreconf inspect`` by hand)::

    python tests/misbehaving_masters.py drip|endless [PORT]
"""

from __future__ import annotations

import contextlib
import socket
import sys
import threading
import time
from types import TracebackType

ANSWER = (
    b"<?xml version='1.0'?>\n<methodResponse><params><param><value><array><data>"
    b"<value><int>1</int></value><value><string>ok</string></value>"
    b"<value><array><data><value><array><data></data></array></value>"
    b"<value><array><data></data></array></value><value><array><data></data></array></value>"
    b"</data></array></value></data></array></value></param></params></methodResponse>\n"
)
"""A well-formed ``[1, "ok", [[], [], []]]``: what a master with nothing registered answers."""

HEAD = b"HTTP/1.0 200 OK\r\nContent-Type: text/xml\r\n"


class _FakeMaster:
    """Accept connections on a free loopback port and answer each with ``_answer``."""

    def __init__(self, *, port: int = 0, lifetime: float = 60.0) -> None:
        self.listener = socket.create_server(("127.0.0.1", port))
        self.listener.settimeout(0.1)
        self.uri = f"http://127.0.0.1:{self.listener.getsockname()[1]}/"
        self.stop = threading.Event()
        self.lifetime = lifetime
        self.sent = 0
        self.thread = threading.Thread(target=self._serve, daemon=True)

    def __enter__(self) -> _FakeMaster:
        self.thread.start()
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.stop.set()
        self.thread.join(10)
        self.listener.close()

    def _serve(self) -> None:
        end = time.monotonic() + self.lifetime
        while not self.stop.is_set() and time.monotonic() < end:
            try:
                conn, _ = self.listener.accept()
            except TimeoutError:
                continue
            with conn:
                conn.settimeout(2.0)
                try:
                    self._read_request(conn)
                    self._answer(conn, end)
                except OSError:
                    pass  # the client hung up: what the tests want

    @staticmethod
    def _read_request(conn: socket.socket) -> None:
        """Read the request's headers and its Content-Length body."""
        data = b""
        while b"\r\n\r\n" not in data:
            chunk = conn.recv(4096)
            if not chunk:
                raise ConnectionResetError
            data += chunk
        head, body = data.split(b"\r\n\r\n", 1)
        length = next(
            (int(v) for k, v in (h.split(b":", 1) for h in head.split(b"\r\n")[1:] if b":" in h)
             if k.strip().lower() == b"content-length"),
            0,
        )  # fmt: skip
        while len(body) < length:
            chunk = conn.recv(4096)
            if not chunk:
                raise ConnectionResetError
            body += chunk

    def _answer(self, conn: socket.socket, end: float) -> None:
        raise NotImplementedError

    def _live(self, end: float) -> bool:
        return not self.stop.is_set() and time.monotonic() < end


class DripMaster(_FakeMaster):
    """FAKE: answer correctly, one byte every ``interval`` seconds (headers included)."""

    def __init__(self, *, interval: float = 0.5, port: int = 0, lifetime: float = 60.0) -> None:
        super().__init__(port=port, lifetime=lifetime)
        self.interval = interval

    def _answer(self, conn: socket.socket, end: float) -> None:
        whole = HEAD + b"Content-Length: %d\r\n\r\n" % len(ANSWER) + ANSWER
        for i in range(len(whole)):
            if not self._live(end):
                return
            conn.sendall(whole[i : i + 1])
            self.sent += 1
            self.stop.wait(self.interval)


class EndlessMaster(_FakeMaster):
    """FAKE: answer with an XML-RPC array of strings that never ends, as fast as it is read."""

    def _answer(self, conn: socket.socket, end: float) -> None:
        conn.sendall(HEAD + b"\r\n" + ANSWER[: ANSWER.index(b"<value><int>")])
        item = b"<value><string>" + b"x" * 1000 + b"</string></value>"
        block = item * 64
        while self._live(end):
            conn.sendall(block)
            self.sent += len(block)


def main(argv: list[str]) -> int:
    """Serve one fake master until Ctrl-C (for measuring by hand)."""
    kinds = {"drip": DripMaster, "endless": EndlessMaster}
    if len(argv) not in (2, 3) or argv[1] not in kinds:
        print(f"usage: {argv[0]} drip|endless [PORT]", file=sys.stderr)
        return 2
    port = int(argv[2]) if len(argv) == 3 else 0
    with kinds[argv[1]](port=port, lifetime=3600.0) as fake:
        print(fake.uri, flush=True)
        with contextlib.suppress(KeyboardInterrupt):
            fake.thread.join()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

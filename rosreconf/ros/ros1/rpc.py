"""Call an XML-RPC endpoint (a ROS 1 master or node API) with one deadline and a byte cap.

The standard library's ``xmlrpc.client`` gives each socket read its own timeout, so a peer
that sends one byte at a time can keep a call going for as long as it likes, and it reads
any answer whole, however large. Here each call has one total deadline (connecting, sending,
the whole answer) and a cap on the bytes received; compressed answers are refused. Every
failure becomes ``ExternalToolError`` naming the endpoint, and anything quoted from the wire
goes through ``printable`` first: a status text can carry terminal escape sequences.
"""

from __future__ import annotations

import http.client
import socket
import time
import xmlrpc.client
from typing import Any
from urllib.parse import urlsplit
from xml.parsers.expat import ExpatError

from rosreconf.errors import ExternalToolError, UsageError
from rosreconf.printable import printable

DEFAULT_TIMEOUT = 3.0
"""Seconds one XML-RPC call may take in all: connecting, sending, and the whole answer."""

DEFAULT_MAX_BYTES = 32 << 20
"""How many bytes one answer may have (headers included); a large real master sends a few MiB."""


class _Late(TimeoutError):
    """The call's total deadline passed while connecting, sending or reading."""


class _TooLarge(OSError):
    """The answer grew past the byte cap."""


class _BoundedSocket(socket.socket):
    """A socket that gives each operation only what is left of one total deadline.

    ``http.client`` reads through a buffered file that loops over ``recv_into`` until it
    has what it asked for, so a per-read timeout lets a peer that sends one byte at a time
    keep a call going for as long as it likes. Here every ``recv_into``/``recv``/``sendall``
    first sets the timeout to the time left, and counts the bytes received against the cap.
    """

    deadline: float = 0.0
    max_bytes: int = DEFAULT_MAX_BYTES
    received: int = 0

    def _arm(self) -> None:
        left = self.deadline - time.monotonic()
        if left <= 0:
            raise _Late
        self.settimeout(left)

    def _count(self, n: int) -> int:
        self.received += n
        if self.received > self.max_bytes:
            raise _TooLarge
        return n

    def recv_into(self, buffer: Any, nbytes: int = 0, flags: int = 0) -> int:
        self._arm()
        return self._count(super().recv_into(buffer, nbytes, flags))

    def recv(self, bufsize: int, flags: int = 0) -> bytes:
        self._arm()
        data = super().recv(bufsize, flags)
        self._count(len(data))
        return data

    def sendall(self, data: Any, flags: int = 0) -> None:
        self._arm()
        super().sendall(data, flags)


class _BoundedConnection(http.client.HTTPConnection):
    """An HTTP connection over a ``_BoundedSocket`` with the transport's deadline and cap."""

    def __init__(self, host: str, deadline: float, max_bytes: int) -> None:
        super().__init__(host)
        self._deadline = deadline
        self._max_bytes = max_bytes

    def connect(self) -> None:
        left = self._deadline - time.monotonic()
        if left <= 0:
            raise _Late
        plain = socket.create_connection((self.host, self.port), timeout=left)
        sock = _BoundedSocket(plain.family, plain.type, plain.proto, fileno=plain.detach())
        sock.deadline, sock.max_bytes = self._deadline, self._max_bytes
        self.sock = sock


class _BoundedTransport(xmlrpc.client.Transport):
    """An XML-RPC transport with a total deadline and a byte cap for each call.

    The deadline starts when the request starts and covers connecting, sending and reading
    the whole answer; the cap counts every byte received. Compressed answers are neither
    asked for nor accepted: a small gzip body can unpack to any size.
    """

    accept_gzip_encoding = False

    def __init__(self, timeout: float, max_bytes: int) -> None:
        super().__init__()
        self._timeout = timeout
        self._max_bytes = max_bytes
        self._deadline = 0.0

    def request(self, host: Any, handler: str, request_body: Any, verbose: bool = False) -> Any:
        self._deadline = time.monotonic() + self._timeout
        return super().request(host, handler, request_body, verbose)

    def make_connection(self, host: Any) -> http.client.HTTPConnection:
        if self._connection[1] is not None and host == self._connection[0]:
            return self._connection[1]
        chost, self._extra_headers, _ = self.get_host_info(host)
        conn = _BoundedConnection(chost, self._deadline, self._max_bytes)
        self._connection = host, conn
        return conn

    def parse_response(self, response: http.client.HTTPResponse) -> Any:
        encoding = response.getheader("Content-Encoding", "") or "identity"
        if encoding.lower() != "identity":
            raise xmlrpc.client.ResponseError(
                f"answered with Content-Encoding {printable(encoding, 40)}, which was not asked for"
            )
        parser, unmarshaller = self.getparser()
        while chunk := response.read(1 << 16):
            parser.feed(chunk)
        parser.close()
        return unmarshaller.close()


def check_uri(uri: str, what: str) -> None:
    """Refuse a URI that cannot be an XML-RPC endpoint, before any connection is tried."""
    parts = urlsplit(uri)
    try:
        port = parts.port
    except ValueError:
        port = None
    if parts.scheme != "http" or not parts.hostname or port is None:
        raise UsageError(f"{what} URI {uri!r} is not of the form http://HOST:PORT/")


def ask(uri: str, who: str, timeout: float, max_bytes: int, method: str, *args: object) -> Any:
    """Call ``method`` at ``uri`` within ``timeout`` and ``max_bytes``; return the raw answer."""
    proxy = xmlrpc.client.ServerProxy(uri, transport=_BoundedTransport(timeout, max_bytes))
    try:
        return getattr(proxy, method)(*args)
    except TimeoutError:
        msg = (
            f"{who} at {uri} did not answer {method} within {timeout:g} s "
            "(the whole answer must arrive in that time; a slow master needs a longer timeout)"
        )
        raise ExternalToolError(msg) from None
    except _TooLarge:
        msg = (
            f"{who} at {uri} answered {method} with more than {_mib(max_bytes)} "
            "(a runaway answer: it was cut off; a really that large system needs a larger cap)"
        )
        raise ExternalToolError(msg) from None
    except ConnectionRefusedError:
        msg = f"{who} at {uri} refused the connection (is it running on that port?)"
        raise ExternalToolError(msg) from None
    except xmlrpc.client.ProtocolError as e:
        reason = printable(str(e.errmsg), 80)
        msg = f"{who} at {uri}: {method} failed: HTTP status {e.errcode} {reason}"
        raise ExternalToolError(msg) from None
    except xmlrpc.client.Fault as e:
        msg = f"{who} at {uri}: {method} failed: XML-RPC fault {printable(str(e.faultString))}"
        raise ExternalToolError(msg) from None
    except (OSError, xmlrpc.client.Error, http.client.HTTPException, ExpatError) as e:
        why = printable(str(e)) or type(e).__name__
        msg = f"{who} at {uri}: {method} failed: {type(e).__name__}: {why}"
        raise ExternalToolError(msg) from None
    finally:
        proxy("close")()


def _mib(n: int) -> str:
    """Say a byte count in MiB (or bytes below one MiB)."""
    return f"{n / (1 << 20):g} MiB" if n >= 1 << 20 else f"{n} bytes"


def call(
    uri: str,
    who: str,
    timeout: float,
    method: str,
    *args: object,
    max_bytes: int = DEFAULT_MAX_BYTES,
) -> Any:
    """Call ``method`` at ``uri`` and return the value of a code-1 answer, or raise."""
    answer = ask(uri, who, timeout, max_bytes, method, *args)
    if not (isinstance(answer, list) and len(answer) == 3 and isinstance(answer[0], int)):
        msg = f"{who} at {uri}: {method} gave {answer!r:.200}, not [code, status, value]"
        raise ExternalToolError(printable(msg, 400))
    if answer[0] != 1:
        raise ExternalToolError(f"{who} at {uri}: {method} failed: {printable(str(answer[1]))}")
    return answer[2]

"""A Dask scheduler named by its address, probed before Dask's client connects to it.

A server at ``tcp://HOST:PORT`` that is not a Dask scheduler (silent, or sending something other
than a scheduler's handshake), one that refuses connections past the timeout, or a malformed
address is refused in one line before Dask's client would wait or fail with its own traceback.
"""

from __future__ import annotations

import time

from perturb._defaults import SWEEP_CONNECT_RETRY, SWEEP_HANDSHAKE_BYTES
from perturb.errors import InvalidParameterError

__all__ = ["probe", "refused"]


def refused(address: str, timeout: float, reason: str) -> InvalidParameterError:
    """The one-line refusal of ``address``: no Dask scheduler answered within ``timeout`` s."""
    return InvalidParameterError(
        f"--scheduler (scheduler=) {address!r}: no Dask scheduler answered within {timeout:g} s "
        f"({reason}); start one with `dask scheduler` and check the address (tcp://HOST:PORT)"
    )


def probe(address: str, timeout: float) -> None:
    """Check, within ``timeout`` seconds, that a Dask scheduler listens at the TCP ``address``:
    it sends its handshake as soon as a connection opens (an 8-byte frame length, then the
    frames), while a server of another kind is silent or sends something else. Other schemes
    (``tls://``...) are left to the client."""
    import socket
    import struct
    from urllib.parse import urlsplit

    scheme, _, rest = address.partition("://")
    if not rest:
        scheme, rest = "tcp", address
    if scheme != "tcp":
        return
    try:
        parts = urlsplit(f"//{rest}")
        host, port = parts.hostname, parts.port
    except ValueError as exc:
        raise refused(address, timeout, f"the address is malformed: {exc}") from None
    if not host or port is None:
        raise refused(address, timeout, "give the host and the port, tcp://HOST:PORT")
    deadline = time.monotonic() + timeout
    while True:  # a scheduler starting up refuses connections for a moment: retried
        try:
            data = _first_bytes(host, port, deadline)
            break
        except ConnectionRefusedError as exc:
            if time.monotonic() + SWEEP_CONNECT_RETRY > deadline:
                raise refused(address, timeout, " ".join(str(exc).split())) from None
            time.sleep(SWEEP_CONNECT_RETRY)
        except (OSError, TimeoutError, ConnectionError) as exc:
            reason = " ".join(str(exc).split()) or type(exc).__name__
            if isinstance(exc, socket.timeout | TimeoutError) and "not Dask" not in reason:
                reason = "it accepts connections but says nothing: not a Dask scheduler"
            raise refused(address, timeout, reason) from None
    (length,) = struct.unpack("<Q", data)
    if not 0 < length <= SWEEP_HANDSHAKE_BYTES:
        raise refused(address, timeout, "it answers, but it is not a Dask scheduler")


def _first_bytes(host: str, port: int, deadline: float) -> bytes:
    """The first 8 bytes a server at ``host:port`` sends when a connection opens (by
    ``deadline``, a time of :func:`time.monotonic`)."""
    import socket

    left = max(deadline - time.monotonic(), 0.01)
    with socket.create_connection((host, port), timeout=left) as sock:
        data = b""
        while len(data) < 8:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError("it accepts connections but says nothing: not Dask")
            sock.settimeout(left)
            chunk = sock.recv(8 - len(data))
            if not chunk:
                raise ConnectionError("it closed the connection: not a Dask scheduler")
            data += chunk
    return data

"""Where the explorer listens: the address checked before anything loads, a free port,
the origins whose pages may open its websocket.  Sockets only, so the command line
refuses an address it cannot listen at without loading the server
(:mod:`tennis_stroke.live.server`)."""

from __future__ import annotations

import errno
import socket

LOCALHOST = "127.0.0.1"


def free_port(host: str) -> int:
    """A port no one listens on at ``host`` now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind((host, 0))
        return int(s.getsockname()[1])


#: The addresses that mean every interface of the machine.
EVERY_INTERFACE = ("0.0.0.0", "")


def check_address(host: str, port: int | None) -> None:
    """Fail in one line (ValueError) before anything loads when the explorer cannot listen
    at ``host`` (a name or an address of this machine) and ``port`` (None: any free one):
    a host that resolves to nothing or to no address of this machine, a port in use."""
    try:
        socket.getaddrinfo(host, None, socket.AF_INET, socket.SOCK_STREAM)
    except (socket.gaierror, UnicodeError) as exc:
        reason = getattr(exc, "strerror", None) or str(exc)
        raise ValueError(f"--host {host}: not a name or an address ({reason})") from None
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # as the server's socket
        try:
            s.bind((host, port or 0))
        except OSError as exc:
            if port and exc.errno == errno.EADDRINUSE:
                raise ValueError(
                    f"--port {port}: in use on {host} (another server listens there; "
                    "give another --port, or none for a free one)"
                ) from None
            raise ValueError(f"--host {host}: cannot listen there ({exc.strerror})") from None


def origins(host: str, port: int) -> list[str]:
    """The origins whose pages may open the explorer's websocket: the served address
    (and ``localhost`` for 127.0.0.1); on every interface (0.0.0.0), this machine's
    name and addresses as a browser elsewhere reaches it, and the loopback ones."""
    names = [host, "localhost"] if host == LOCALHOST else [host]
    if host in EVERY_INTERFACE:
        names = [socket.gethostname(), *_addresses(), LOCALHOST, "localhost"]
    return [f"{name}:{port}" for name in dict.fromkeys(n for n in names if n)]


def _addresses() -> list[str]:
    """This machine's IPv4 addresses by its name (none if the name does not resolve)."""
    try:
        return socket.gethostbyname_ex(socket.gethostname())[2]
    except OSError:
        return []

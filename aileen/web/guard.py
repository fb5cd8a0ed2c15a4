"""Which requests the console answers: only its own page's, on this machine's names for it.

Why a module of its own, without the web stack: these rules are the console's defence against
other web pages, so they are pure functions over a request's method and headers, tested alone.

- **Host.** Every request must name the server by a host it is bound to: `127.0.0.1`,
  `localhost`, `::1`, or the `--host` given. A DNS-rebinding page reaches the server under its
  own domain name (`Host: evil.example:8765`) and is refused, for reads too (the memory is
  the user's). When bound to every interface (`0.0.0.0`, `::`), an IP address is accepted as
  well: rebinding needs a name, and an address cannot be rebound.
- **Origin.** A request that changes anything (not GET, HEAD or OPTIONS) may carry an
  `Origin` only if it is the server's own (`http://` + the `Host` it was sent to): a page of
  another origin, even on this machine, cannot teach, edit or save. Browsers send `Origin` on
  every cross-origin POST; the page's own fetches carry its own origin, so no token is needed.
- **Method.** Only GET, HEAD, OPTIONS and POST: any other is `405`, before its body is looked at.
  OPTIONS is answered `204` with `Allow` (the path's methods) and no CORS header: it grants
  no other page anything.
- **Content type.** A request that changes anything must say `Content-Type:
  application/json`. An HTML form can only send `text/plain`, `multipart/form-data` or
  `application/x-www-form-urlencoded` without a CORS preflight, which the server never grants.
"""

from __future__ import annotations

import ipaddress
from collections.abc import Iterable

LOCAL_HOSTS = ("127.0.0.1", "localhost", "::1")
WILDCARDS = ("0.0.0.0", "::", "")
SAFE_METHODS = frozenset({"GET", "HEAD", "OPTIONS"})
METHODS = SAFE_METHODS | {"POST"}  # all the console takes: DELETE /api/scene was told to send JSON (415)
JSON = "application/json"


def said(methods: Iterable[str]) -> str:
    """Methods in a sentence, in one order: "GET, HEAD, OPTIONS and POST" (the 405 said "only GET
    and POST" where the docs and `METHODS` have four)."""
    names = sorted(methods)
    return names[0] if len(names) == 1 else f"{', '.join(names[:-1])} and {names[-1]}"


def allowed_hosts(bound: str) -> frozenset[str]:
    """The host names a request may use: this machine's, and the address the server is bound to."""
    return frozenset(LOCAL_HOSTS) | {bound.strip("[]").lower()}


def host_name(header: str) -> str | None:
    """The host of a `Host` header (`name`, `name:port`, `[v6]` or `[v6]:port`), lowercase;
    None when it is not one."""
    h = header.strip().lower()
    if h.startswith("["):
        end = h.find("]")
        if end < 0 or (h[end + 1:] and not _port(h[end + 1:])):
            return None
        return h[1:end] or None
    name, colon, port = h.partition(":")
    if colon and not _port(colon + port):
        return None
    return name or None


def _port(text: str) -> bool:
    """`:8765`: a colon and a port number."""
    digits = text[1:]
    return text[:1] == ":" and 0 < len(digits) <= 5 and digits.isascii() and digits.isdigit()


def _is_address(name: str) -> bool:
    try:
        ipaddress.ip_address(name)
    except ValueError:
        return False
    return True


def refusal(method: str, headers: Iterable[tuple[str, str]], hosts: frozenset[str]) -> tuple[int, str] | None:
    """(status, reason) when the console must refuse the request; None when it may answer.
    `headers`: (name, value) pairs as received (names in any case)."""
    seen: dict[str, list[str]] = {}
    for k, v in headers:
        seen.setdefault(k.lower(), []).append(v)
    for name in ("host", "origin", "content-type"):
        if len(seen.get(name, ())) > 1:
            return 400, f"the request has {name} twice"
    host_header = seen.get("host", [""])[0]
    host = host_name(host_header)
    wildcard = bool(hosts & set(WILDCARDS))
    if host is None or not (host in hosts or (wildcard and _is_address(host))):
        shown = host_header[:60] or "nothing"
        return 403, (f"this console answers only at {', '.join(sorted(h for h in hosts if h))} "
                     f"(the request was addressed to {shown!r}); a web page on another site cannot use it")
    if method.upper() not in METHODS:
        return 405, f"the console takes only {said(METHODS)} requests, not {method.upper()[:20]}"
    if method.upper() in SAFE_METHODS:
        return None
    origin = seen.get("origin", [None])[0]
    if origin is not None and origin.strip().lower() != f"http://{host_header.strip().lower()}":
        return 403, (f"the request came from another web page ({origin[:60]!r}); only the console's own "
                     "page can teach, edit or save")
    kind = seen.get("content-type", [""])[0].split(";", 1)[0].strip().lower()
    if kind != JSON:
        return 415, (f"send the body as {JSON} (Content-Type was {kind or 'not given'!r}); "
                     "e.g. curl -H 'Content-Type: application/json' -d '{}'")
    return None

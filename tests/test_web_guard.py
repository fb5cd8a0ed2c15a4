"""Which requests the console answers (aileen/web/guard.py), without a server."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from aileen.web import guard

LOCAL = guard.allowed_hosts("127.0.0.1")
PORT = st.integers(1, 65535)


@given(st.sampled_from(["127.0.0.1", "localhost", "LocalHost"]), PORT)
def test_this_machine_is_answered_with_or_without_a_port(name, port) -> None:
    for host in (name, f"{name}:{port}"):
        assert guard.refusal("GET", [("Host", host)], LOCAL) is None
        assert guard.refusal("POST", [("host", host), ("origin", f"http://{host}"),
                                      ("content-type", "application/json")], LOCAL) is None
    assert guard.refusal("GET", [("Host", f"[::1]:{port}")], LOCAL) is None


@given(st.text(max_size=40))
def test_any_other_host_is_refused(host) -> None:
    name = guard.host_name(host)
    answer = guard.refusal("GET", [("Host", host)], LOCAL)
    assert (answer is None) == (name in LOCAL)
    if answer is not None:
        assert answer[0] == 403 and "\n" not in answer[1]


@given(st.sampled_from(["127.0.0.1:8765", "localhost:8765"]),
       st.text(max_size=40).filter(lambda o: o.strip().lower() not in ("http://127.0.0.1:8765", "http://localhost:8765")))
def test_a_change_from_any_other_origin_is_refused(host, origin) -> None:
    if origin.strip().lower() == f"http://{host}":
        return
    status, _ = guard.refusal("POST", [("Host", host), ("Origin", origin), ("Content-Type", "application/json")],
                              LOCAL)
    assert status == 403
    # reading needs no origin check: a page cannot read another origin's answers anyway
    assert guard.refusal("GET", [("Host", host), ("Origin", origin)], LOCAL) is None


@given(st.text(max_size=30).filter(lambda t: t.split(";", 1)[0].strip().lower() != "application/json"))
def test_a_change_must_be_json(kind) -> None:
    status, message = guard.refusal("POST", [("Host", "127.0.0.1:8765"), ("Content-Type", kind)], LOCAL)
    assert status == 415 and "application/json" in message


def test_headers_given_twice_are_refused() -> None:
    two = [("Host", "127.0.0.1"), ("Host", "evil.example"), ("Content-Type", "application/json")]
    assert guard.refusal("POST", two, LOCAL)[0] == 400


def test_a_bound_address_and_a_wildcard() -> None:
    lan = guard.allowed_hosts("192.168.1.5")
    assert guard.refusal("GET", [("Host", "192.168.1.5:8765")], lan) is None
    assert guard.refusal("GET", [("Host", "rebound.example:8765")], lan)[0] == 403
    every = guard.allowed_hosts("0.0.0.0")
    assert guard.refusal("GET", [("Host", "10.0.0.9:8765")], every) is None
    assert guard.refusal("GET", [("Host", "[fe80::1]:8765")], every) is None
    assert guard.refusal("GET", [("Host", "rebound.example:8765")], every)[0] == 403
    v6 = guard.allowed_hosts("::1")
    assert guard.refusal("GET", [("Host", "[::1]:8765")], v6) is None


@given(st.sampled_from(["example.org", "127.0.0.1", "::1", "a-b.c"]), st.one_of(st.none(), PORT))
def test_host_names_parse(name, port) -> None:
    shown = f"[{name}]" if ":" in name else name
    header = shown if port is None else f"{shown}:{port}"
    assert guard.host_name(header) == name


def test_a_method_the_console_does_not_take_is_405_after_the_host_check() -> None:
    hosts = guard.allowed_hosts("127.0.0.1")
    assert guard.refusal("DELETE", [("Host", "127.0.0.1:8765")], hosts)[0] == 405
    assert guard.refusal("DELETE", [("Host", "evil.example")], hosts)[0] == 403
    assert guard.refusal("POST", [("Host", "127.0.0.1:8765"), ("Content-Type", "application/json")], hosts) is None

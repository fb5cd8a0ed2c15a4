"""`aileen serve` stopped while a client holds a request half-sent (a real process: signals)."""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")

ROOT = Path(__file__).resolve().parents[1]


@contextlib.contextmanager
def _reaped(proc: subprocess.Popen):  # noqa: ANN202
    """The server is killed on the way out if the test's steps left it running."""
    try:
        yield
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _post(port: int, path: str, body: dict) -> bytes:
    with socket.create_connection(("127.0.0.1", port), timeout=120) as s:
        data = json.dumps(body).encode()
        s.sendall(f"POST {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: application/json\r\n"
                  f"Content-Length: {len(data)}\r\nConnection: close\r\n\r\n".encode() + data)
        chunks = []
        while chunk := s.recv(65536):
            chunks.append(chunk)
    return b"".join(chunks)


def _started(memory: Path, head: tuple[str, ...] = ("-m", "aileen")) -> tuple[subprocess.Popen, int, Path]:
    """`aileen serve --memory MEMORY` (or `python HEAD... serve ...`) on a free port, answering."""
    port = _free_port()
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])))
    err = memory.with_name("serve.err")
    proc = subprocess.Popen([sys.executable, *head, "serve", "--memory", str(memory), "--port", str(port)],
                            env=env, stdout=subprocess.PIPE, stderr=open(err, "w"), text=True)
    assert "open http://" in proc.stdout.readline(), err.read_text()
    for _ in range(600):
        try:
            socket.create_connection(("127.0.0.1", port), timeout=5).close()
            break
        except OSError:
            time.sleep(0.05)
    return proc, port, err


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_a_second_stop_signal_ends_a_server_held_by_a_half_sent_request_and_saves(tmp_path, sig) -> None:
    # the request in flight waited for its body for ever: SIGTERM, twice, did nothing, nothing was
    # saved; SIGINT twice printed asyncio.CancelledError tracebacks
    memory = tmp_path / "m.json"
    proc, port, err = _started(memory)
    with _reaped(proc):
        assert b" 200 " in _post(port, "/api/scene", {"op": "add", "object": "red box"})
        assert b" 200 " in _post(port, "/api/lesson", {"signal": "inform", "content": "red box"})
        stalled = socket.create_connection(("127.0.0.1", port))
        stalled.sendall(f"POST /api/lesson HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: application/json"
                        "\r\nContent-Length: 100\r\n\r\n{\"signal\":".encode())
        time.sleep(0.5)  # the request reached the app (no assertion on time: the order of events)
        proc.send_signal(sig)
        time.sleep(0.5)
        proc.send_signal(sig)
        status = proc.wait(timeout=60)
    text = err.read_text()
    assert status == 128 + sig, text
    assert "Traceback" not in text and "CancelledError" not in text, text
    assert len(text.strip().splitlines()) == 1 and text.startswith("aileen: stopped by SIG"), text
    assert json.loads(memory.read_text()) and (tmp_path / "m.console.json").is_file()
    assert "red box" in (tmp_path / "m.console.json").read_text()


def test_a_body_that_does_not_arrive_in_time_is_a_408(monkeypatch) -> None:
    """A client that sends part of a body and stalls held the request (and a stop) for ever."""
    from starlette.requests import Request

    from aileen.web import app
    from aileen.web.app import BadRequest, _json_body

    monkeypatch.setattr(app, "BODY_SECONDS", 0.2)
    sent = []

    async def receive() -> dict:
        if not sent:
            sent.append(1)
            return {"type": "http.request", "body": b'{"signal":', "more_body": True}
        await asyncio.sleep(3600)
        raise AssertionError("unreachable")

    request = Request({"type": "http", "method": "POST", "headers": [], "path": "/api/lesson"}, receive)
    with pytest.raises(BadRequest, match="did not arrive") as err:
        asyncio.run(_json_body(request))
    assert err.value.status == 408


def test_a_server_stopped_with_a_directory_where_its_memory_was_names_the_recovery_file(tmp_path) -> None:
    """The probe's case: the line said "m.console.json: saved the memory, but not the table and
    transcript: Is a directory", never naming the recovery file where the lessons went."""
    memory = tmp_path / "m.json"
    proc, port, err = _started(memory)
    with _reaped(proc):
        assert b" 200 " in _post(port, "/api/scene", {"op": "add", "object": "red box"})
        assert b" 200 " in _post(port, "/api/lesson", {"signal": "inform", "content": "red box"})
        memory.unlink()
        memory.mkdir()
        proc.send_signal(signal.SIGTERM)
        status = proc.wait(timeout=60)
    text = err.read_text()
    recovered = next(tmp_path.glob("m.recovered-*[0-9].json"))
    assert status == 128 + signal.SIGTERM, text
    assert f"what this run learned is in {recovered}" in text and "Is a directory" not in text, text
    assert "red box" in (tmp_path / f"{recovered.stem}.console.json").read_text()


SLOW_LESSON = """
import pathlib, sys, time
from aileen.web import session
started = pathlib.Path(sys.argv[1])
given = session.Session.lesson
def slow(self, *args, **kw):  # a lesson long enough for both signals to come while it runs
    started.write_text("started")
    time.sleep(3)
    return given(self, *args, **kw)
session.Session.lesson = slow
from aileen.cli import main
sys.exit(main(sys.argv[2:]))
"""


def test_a_lesson_in_flight_when_the_stop_gives_up_waiting_is_answered_and_the_first_signal_named(tmp_path) -> None:
    """The probe's case: a react in flight, then SIGTERM and SIGINT 20 ms apart: the client got 503
    "the request was not carried out" though the lesson ran and was saved, and the server said
    "stopped by SIGINT" (exit 130) though SIGTERM came first."""
    import threading

    memory, started = tmp_path / "m.json", tmp_path / "started"
    proc, port, err = _started(memory, ("-c", SLOW_LESSON, str(started)))
    answer: list[bytes] = []
    try:
        assert b" 200 " in _post(port, "/api/scene", {"op": "add", "object": "red box"})
        client = threading.Thread(target=lambda: answer.append(
            _post(port, "/api/lesson", {"signal": "inform", "content": "red box"})))
        client.start()
        while not started.exists():  # the lesson's work is under way (an order of events, not a time)
            time.sleep(0.05)
        proc.send_signal(signal.SIGTERM)
        time.sleep(0.02)
        proc.send_signal(signal.SIGINT)
        status = proc.wait(timeout=120)
        client.join(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    text = err.read_text()
    assert status == 128 + signal.SIGTERM and text.startswith("aileen: stopped by SIGTERM"), text
    assert answer and b" 200 " in answer[0], answer
    head, _, body = answer[0].partition(b"\r\n\r\n")
    assert json.loads(body)["signal"] == "inform"
    assert [r["signal"] for r in json.loads((tmp_path / "m.console.json").read_text())["records"]] == ["inform"]

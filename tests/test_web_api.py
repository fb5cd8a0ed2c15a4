"""The console's HTTP API through Starlette's test client (needs the `web` extra and httpx)."""

from __future__ import annotations

import json

import pytest

pytest.importorskip("starlette")
try:  # the test client needs httpx2 (or httpx, deprecated)
    from starlette.testclient import TestClient
except (ImportError, RuntimeError):  # pragma: no cover - without the webtest extra
    pytest.skip("starlette's test client needs httpx2: pip install -e '.[webtest]'", allow_module_level=True)

from aileen.agent import Agent  # noqa: E402
from aileen.memory.concept import ConceptMemory  # noqa: E402
from aileen.web.app import MAX_BODY, create_app  # noqa: E402
from aileen.web.session import Session  # noqa: E402

BASE = "http://127.0.0.1:8765"  # the console answers only at this machine's names (guard.py)


@pytest.fixture()
def client(tmp_path):
    session = Session(Agent(), seed=3, memory_path=str(tmp_path / "memory.json"))
    with TestClient(create_app(session), base_url=BASE, raise_server_exceptions=False) as c:
        c.session = session
        yield c


def one_line_4xx(r) -> str:
    assert 400 <= r.status_code < 500, (r.status_code, r.text)
    msg = r.json()["error"]
    assert msg and "\n" not in msg and "Traceback" not in msg
    return msg


def test_teach_verify_inspect_and_save_through_the_api(client, tmp_path) -> None:
    assert client.post("/api/scene", json={"op": "add", "object": "red box"}).status_code == 200
    r = client.post("/api/lesson", json={"signal": "inform", "content": "red box"})
    assert r.status_code == 200 and set(r.json()["created"]) == {"r_red", "r_box"}
    client.post("/api/scene", json={"op": "clear"})
    client.post("/api/scene", json={"op": "add", "object": "blue cone", "at": [0.7, 0.5]})
    client.post("/api/lesson", json={"signal": "inform", "content": "blue cone"})
    scene = client.post("/api/scene", json={"op": "add", "object": "red box", "relation": "left of",
                                            "of": "blue cone"}).json()
    assert [o["name"] for o in scene["objects"]] == ["blue cone", "red box"]
    assert scene["objects"][1]["x"] < scene["objects"][0]["x"]
    client.post("/api/lesson", json={"signal": "inform", "content": "red box left of blue cone"})
    r = client.post("/api/lesson", json={"signal": "verify", "content": "red box left of blue cone"}).json()
    assert (r["result"], r["correct"]) == ("success", True)
    # the record is `aileen run --json`'s
    assert {"index", "signal", "content", "result", "reason", "commands", "created", "stored", "referents",
            "seen", "expected", "correct", "seconds"} <= r.keys()
    png = client.get("/api/scene.png?overlay=1")
    assert png.status_code == 200 and png.content[:8] == b"\x89PNG\r\n\x1a\n"
    assert png.content != client.get("/api/scene.png").content  # the overlay is drawn
    mem = client.get("/api/memory").json()["concepts"]
    assert {"r_red", "r_box", "r_blue", "r_cone", "r_left_of"} <= mem.keys()
    assert mem["r_left_of"]["word"] == "left_of" or mem["r_left_of"]["word"] == "left of"
    assert mem["r_left_of"]["quality"] == {"verify_right": 1, "verify_graded": 1}
    assert client.post("/api/save", json={}).status_code == 200
    saved = ConceptMemory.load(tmp_path / "memory.json")
    assert "r_left_of" in saved
    toml = client.get("/api/transcript.toml")
    assert toml.status_code == 200 and toml.text.count("[[lesson]]") == 4
    assert len(client.get("/api/lessons").json()["records"]) == 4


def test_the_page_and_its_files_are_served(client) -> None:
    r = client.get("/")
    assert r.status_code == 200 and 'id="scene"' in r.text
    for name in ("console.js", "console.css"):
        assert client.get(f"/static/{name}").status_code == 200
    one_line_4xx(client.get("/static/..%2Fsession.py"))
    one_line_4xx(client.get("/static/secret.txt"))


@pytest.mark.parametrize("body,why", [
    (b"{not json", "malformed JSON"),
    (b"[1, 2]", "JSON object"),
    (json.dumps({"signal": "shout", "content": "red box"}).encode(), "unknown signal"),
    (json.dumps({"signal": "inform"}).encode(), "content"),
    (json.dumps({"signal": "inform", "content": "red box", "path": "m.json"}).encode(), "cannot name files"),
    (json.dumps({"signal": "inform", "content": "/etc/passwd"}).encode(), "file path"),
    (json.dumps({"signal": "inform", "content": "red box", "extra": 1}).encode(), "unexpected"),
])
def test_bad_lessons_get_a_4xx_and_one_line_and_the_server_stays_up(client, body, why) -> None:
    r = client.post("/api/lesson", content=body, headers={"Content-Type": "application/json"})
    assert why in one_line_4xx(r)
    assert client.get("/api/scene").status_code == 200


def test_a_10_mb_body_is_refused(client) -> None:
    big = b'{"signal": "inform", "content": "' + b"a" * (10 * 1024 * 1024) + b'"}'
    r = client.post("/api/lesson", content=big, headers={"Content-Type": "application/json"})
    assert r.status_code == 413 and str(MAX_BODY) in one_line_4xx(r)
    assert client.get("/api/scene").status_code == 200


@pytest.mark.parametrize("body,why", [
    ({"op": "add", "object": "red box", "at": [5, 5]}, "off the table"),
    ({"op": "add", "object": "red box", "at": ["a", 1]}, "finite numbers"),
    ({"op": "add", "object": "rde box"}, "rde"),
    ({"op": "add", "object": "red box", "relation": "left of", "of": "blue cone"}, "exactly one"),
    ({"op": "move", "index": 7, "at": [0.5, 0.5]}, "no object"),
    ({"op": "shuffle", "distractors": -1}, "distractors"),
    ({"op": "undo"}, "nothing to undo"),
    ({"op": "add", "object": "red box", "memory": "x.json"}, "cannot name files"),
    ({"object": "red box"}, "op"),
])
def test_bad_scene_edits_get_a_4xx_and_one_line(client, body, why) -> None:
    assert why in one_line_4xx(client.post("/api/scene", json=body))
    assert client.get("/api/scene").json()["objects"] == []


def test_save_without_a_memory_file_and_unknown_frames_are_4xx() -> None:
    with TestClient(create_app(Session(Agent(), seed=0)), base_url=BASE, raise_server_exceptions=False) as c:
        assert "without --memory" in one_line_4xx(c.post("/api/save", json={}))
        assert "no frame" in one_line_4xx(c.get("/api/scene.png?frame=3"))
        assert "no lessons" in one_line_4xx(c.get("/api/transcript.toml"))
        assert "verdict on the last verify" in one_line_4xx(c.post("/api/lesson", json={"signal": "wrong", "content": "x"}))


def test_experiment_curves_are_listed_by_number(tmp_path) -> None:
    (tmp_path / "visual.png").write_bytes(b"\x89PNG\r\n\x1a\nfake")
    (tmp_path / "visual-summary.csv").write_text("lesson,mean\n1,0.5\n")
    (tmp_path / "summary.json").write_text('{"visual": {"final": 0.9}}')
    with TestClient(create_app(Session(Agent(), seed=0), experiment=tmp_path), base_url=BASE) as c:
        idx = c.get("/api/experiment").json()
        assert [f["name"] for f in idx["files"]] == ["visual-summary.csv", "visual.png"]
        assert idx["summary"] == {"visual": {"final": 0.9}}
        assert c.get("/api/experiment/1").content.startswith(b"\x89PNG")
        assert c.get("/api/experiment/9").status_code == 404


def test_serve_refuses_a_bad_port_with_one_line(capsys) -> None:
    from aileen.cli import main

    assert main(["serve", "--port", "70000"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("aileen:") and "--port" in err and "\n" not in err

"""The console's HTTP API through Starlette's test client (needs the `web` extra and httpx)."""

from __future__ import annotations

import json

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

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
    # the relation was dropped silently; a 300-digit number was printed in the message
    ({"op": "add", "object": "red box", "at": [0.1, 0.1], "relation": "right of", "of": "blue cone"}, "not both"),
    ({"op": "add", "object": "red box", "at": [1e308, 0.1]}, "finite numbers"),
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


# ---------------------------------------------------------------------------- who may ask (guard.py)

def test_same_origin_json_from_the_page_works_without_a_token(client) -> None:
    for host in ("127.0.0.1:8765", "localhost:8765"):
        r = client.post("/api/scene", json={"op": "clear"},
                        headers={"Host": host, "Origin": f"http://{host}"})
        assert r.status_code == 200, r.text


@pytest.mark.parametrize("host", ["evil.example:8765", "evil.example", "127.0.0.1.evil.example:8765",
                                  "localhost.:8765", "[::2]:8765", "10.0.0.7:8765", "", "127.0.0.1:x"])
def test_a_foreign_host_is_refused_even_for_reads(client, host) -> None:
    """DNS rebinding: a page at evil.example whose name now points at 127.0.0.1."""
    for r in (client.get("/api/memory", headers={"Host": host}),
              client.post("/api/lesson", json={"signal": "inform", "content": "red box"}, headers={"Host": host})):
        assert r.status_code == 403 and "answers only at" in one_line_4xx(r)
    assert client.session.records == []


@pytest.mark.parametrize("origin", ["http://evil.example", "http://127.0.0.1:3000", "http://localhost:8765",
                                    "https://127.0.0.1:8765", "null"])
def test_a_change_from_another_origin_is_refused(client, origin) -> None:
    client.post("/api/scene", json={"op": "add", "object": "red box"})
    for path, body in [("/api/lesson", {"signal": "inform", "content": "red box"}), ("/api/scene", {"op": "clear"}),
                       ("/api/save", {})]:
        r = client.post(path, json=body, headers={"Origin": origin})
        assert r.status_code == 403 and "another web page" in one_line_4xx(r)
    assert client.session.records == [] and len(client.session.table.objects) == 1
    assert not (client.session.memory_path and __import__("os").path.exists(client.session.memory_path))


@pytest.mark.parametrize("kind", ["text/plain", "application/x-www-form-urlencoded", "multipart/form-data; boundary=x",
                                  None, "application/json-patch+json", "text/json"])
def test_a_change_not_sent_as_json_is_refused(client, kind) -> None:
    """A cross-origin HTML form can send text/plain, urlencoded or multipart without asking first."""
    headers = {"Content-Type": kind} if kind else {}
    r = client.post("/api/lesson", content=b'{"signal": "inform", "content": "red box"}', headers=headers)
    assert r.status_code == 415 and "application/json" in one_line_4xx(r)
    r = client.post("/api/lesson", content=b'{"signal": "inform", "content": "red box"}',
                    headers={**headers, "Origin": "http://evil.example"})  # the form a foreign page sends
    assert r.status_code in (403, 415)
    assert client.session.records == []
    # JSON with a charset is JSON
    assert client.post("/api/scene", content=b'{"op": "clear"}',
                       headers={"Content-Type": "application/json; charset=utf-8"}).status_code == 200


def test_the_host_given_to_serve_is_accepted_and_a_wildcard_accepts_addresses_not_names() -> None:
    from aileen.web import guard

    s = Session(Agent(), seed=0)
    with TestClient(create_app(s, hosts=guard.allowed_hosts("192.168.1.5")), base_url="http://192.168.1.5:8765") as c:
        assert c.get("/api/scene").status_code == 200
        assert c.get("/api/scene", headers={"Host": "192.168.1.6:8765"}).status_code == 403
    with TestClient(create_app(s, hosts=guard.allowed_hosts("0.0.0.0")), base_url="http://10.1.2.3:8765") as c:
        assert c.get("/api/scene").status_code == 200
        assert c.get("/api/scene", headers={"Host": "[fe80::1]:8765"}).status_code == 200
        assert c.get("/api/scene", headers={"Host": "rebound.example:8765"}).status_code == 403


# ---------------------------------------------------------------------------- versions, the whole table, undo

def test_a_stale_edit_gets_409_and_changes_nothing(client) -> None:
    v0 = client.get("/api/scene").json()["version"]
    client.post("/api/scene", json={"op": "add", "object": "blue cylinder", "at": [0.7, 0.5], "version": v0})
    v1 = client.post("/api/scene", json={"op": "add", "object": "green sphere", "at": [0.3, 0.5]}).json()["version"]
    # another tab, still at v0, removes "object 0"
    r = client.post("/api/scene", json={"op": "remove", "index": 0, "version": v0})
    assert r.status_code == 409 and r.json()["version"] == v1 and "changed" in r.json()["error"]
    r = client.post("/api/lesson", json={"signal": "inform", "content": "green sphere", "version": v0})
    assert r.status_code == 409
    assert [o["name"] for o in client.get("/api/scene").json()["objects"]] == ["blue cylinder", "green sphere"]
    assert client.session.records == []
    assert client.post("/api/scene", json={"op": "remove", "index": 0, "version": v1}).status_code == 200
    assert "whole number" in one_line_4xx(client.post("/api/scene", json={"op": "clear", "version": "7"}))


def test_the_whole_table_in_one_call(client) -> None:
    scene = client.post("/api/scene", json={"objects": ["red box", "large blue cone"], "relation": "left of"}).json()
    names = {o["name"]: o for o in scene["objects"]}
    assert set(names) == {"red box", "large blue cone"} and names["red box"]["x"] < names["large blue cone"]["x"]
    scene = client.post("/api/scene", json={"objects": [{"object": "green sphere", "at": [0.3, 0.4]}, "yellow box"],
                                            "distractors": 2}).json()
    assert [o["name"] for o in scene["objects"]][:2] == ["green sphere", "yellow box"]
    assert (scene["objects"][0]["x"], scene["objects"][0]["y"]) == (0.3, 0.4)
    assert sum(o["distractor"] for o in scene["objects"]) == 2
    client.post("/api/scene", json={"op": "undo"})  # one call, one undo step
    assert [o["name"] for o in client.get("/api/scene").json()["objects"]] == ["red box", "large blue cone"]
    # the old ops still work beside it
    assert client.post("/api/scene", json={"op": "clear"}).json()["objects"] == []


@pytest.mark.parametrize("body,why", [
    ({"objects": []}, "non-empty list"),
    ({"objects": "red box"}, "non-empty list"),
    ({"objects": ["red box", "blue cone", "green sphere"], "relation": "left of"}, "exactly two"),
    ({"objects": ["red box", "blue cone"], "relation": "beside the point"}, "unknown relation"),
    ({"objects": ["red box", {"object": "blue cone", "at": [0.99, 0.5]}]}, "off the table"),
    ({"objects": ["red box"], "colour": "red"}, "unexpected"),
    ({"objects": [{"object": "red box", "size": "large"}]}, "unexpected"),
    ({"objects": [7]}, "description"),
    ({"objects": ["box"]}, "colour and shape"),
    ({"objects": ["red box"], "distractors": 99}, "distractors"),
])
def test_a_bad_whole_table_is_a_4xx_and_leaves_the_table(client, body, why) -> None:
    client.post("/api/scene", json={"op": "add", "object": "purple cylinder", "at": [0.5, 0.5]})
    assert why in one_line_4xx(client.post("/api/scene", json=body))
    assert [o["name"] for o in client.get("/api/scene").json()["objects"]] == ["purple cylinder"]


def test_undo_a_lesson_and_forget_a_concept(client) -> None:
    assert "no lesson to undo" in one_line_4xx(client.post("/api/lesson/undo", json={}))
    client.post("/api/scene", json={"op": "add", "object": "red box", "at": [0.5, 0.5]})
    client.post("/api/lesson", json={"signal": "inform", "content": "red box"})
    client.post("/api/scene", json={"op": "clear"})
    client.post("/api/scene", json={"op": "add", "object": "blue cone", "at": [0.4, 0.4]})
    before = client.get("/api/memory").json()["concepts"]
    client.post("/api/lesson", json={"signal": "inform", "content": "blue cone"})
    assert {"r_blue", "r_cone"} <= client.get("/api/memory").json()["concepts"].keys()
    u = client.post("/api/lesson/undo", json={}).json()
    assert u["undone"]["content"] == "blue cone" and u["scene"]["lessons"] == 1
    assert client.get("/api/memory").json()["concepts"] == before  # the memory as it was before it
    assert len(client.get("/api/lessons").json()["records"]) == 1

    f = client.post("/api/forget", json={"concept": "red"}).json()  # by word or by symbol
    assert (f["forgot"], f["word"]) == ("r_red", "red")
    assert "r_red" not in client.get("/api/memory").json()["concepts"]
    assert "no concept 'green'" in one_line_4xx(client.post("/api/forget", json={"concept": "green"}))
    assert "'concept'" in one_line_4xx(client.post("/api/forget", json={"concept": 3}))
    u = client.post("/api/lesson/undo", json={}).json()
    assert u["undone"] == {"signal": "forget", "content": "r_red", "word": "red"}
    assert client.get("/api/memory").json()["concepts"] == before
    assert "unexpected" in one_line_4xx(client.post("/api/lesson/undo", json={"steps": 2}))


# ---------------------------------------------------------------------------- malformed requests are 4xx

@pytest.mark.parametrize("path", ["/api/scene.png?frame=%C2%B2", "/api/scene.png?frame=-1", "/api/scene.png?frame=1e3",
                                  "/api/scene.png?frame=" + "9" * 5000, "/api/experiment/" + "9" * 5000,
                                  "/api/experiment/%C2%B2", "/api/experiment/-1"])
def test_odd_numbers_in_urls_are_4xx(client, path) -> None:
    one_line_4xx(client.get(path))


@pytest.mark.parametrize("body", [b"[" * 100_000, b'{"op": ' + b"[" * 5000 + b"]" * 5000 + b"}",
                                  b'{"op": "remove", "index": ' + b"9" * 5000 + b"}",
                                  b'{"op": "clear", "op": "clear"}', b'{"objects": [[[["red box"]]]]}',
                                  b"\xff\xfe", b'{"op": "remove", "index": 1e999}', b"NaN", b'"x"'])
def test_malformed_bodies_are_4xx(client, body) -> None:
    r = client.post("/api/scene", content=body, headers={"Content-Type": "application/json"})
    one_line_4xx(r)
    assert client.get("/api/scene").status_code == 200


JSON_LEAF = st.one_of(st.none(), st.booleans(), st.integers(-2**70, 2**70), st.floats(allow_nan=False),
                      st.text(max_size=30), st.sampled_from(["red box", "blue cone", "left of", "inform", "verify",
                                                             "describe", "wrong", "add", "remove", "r_red"]))
KEYS = st.sampled_from(["op", "object", "at", "px", "index", "relation", "of", "distractors", "content", "signal",
                        "version", "objects", "concept", "x"])
JSON_VALUE = st.recursive(JSON_LEAF, lambda inner: st.one_of(st.lists(inner, max_size=4),
                                                             st.dictionaries(KEYS, inner, max_size=4)), max_leaves=12)
ROUTES = ["/api/scene", "/api/lesson", "/api/lesson/undo", "/api/forget", "/api/save"]


def test_fuzzed_requests_never_get_a_5xx(tmp_path) -> None:
    """Random JSON bodies and bytes to every route that changes something, and random queries for
    the image: always an answer below 500, and the server keeps answering."""
    session = Session(Agent(), seed=1, memory_path=str(tmp_path / "m.json"))
    with TestClient(create_app(session), base_url=BASE, raise_server_exceptions=False) as c:
        @settings(max_examples=150, deadline=None, suppress_health_check=list(HealthCheck))
        @given(st.sampled_from(ROUTES), st.one_of(st.dictionaries(KEYS, JSON_VALUE, max_size=5), JSON_VALUE,
                                                  st.binary(max_size=200).map(lambda b: b"\x00RAW" + b)))
        def post(route, body) -> None:
            raw = body[4:] if isinstance(body, bytes) else json.dumps(body).encode()  # Infinity and NaN too
            r = c.post(route, content=raw, headers={"Content-Type": "application/json"})
            assert r.status_code < 500, (route, body, r.text)
            assert "error" in r.json() if r.status_code >= 400 else True

        @settings(max_examples=60, deadline=None, suppress_health_check=list(HealthCheck))
        @given(st.dictionaries(st.sampled_from(["frame", "overlay", "v"]), st.text(max_size=12), max_size=3))
        def image(query) -> None:
            r = c.get("/api/scene.png", params=query)
            assert r.status_code < 500, (query, r.text)

        post()
        image()
        assert c.get("/api/scene").status_code == 200


def test_the_page_gets_its_words_and_a_declared_channel_from_the_server(tmp_path) -> None:
    """GET /api/words reads the declarations; a channel declared for a while (docs/architecture.md,
    "Add a channel") reaches the console's table, its scene JSON, its state file and the
    lesson file it writes, which `aileen run` reads back."""
    from aileen.curriculum import lessonfile
    from aileen.domain import channels
    from aileen.errors import UserError
    from aileen.web import state

    texture = channels.Channel("texture", ("plain", "striped"), "aileen.perception.size:measure_size")
    plain = Session(Agent(), seed=3, memory_path=str(tmp_path / "m0.json"))
    with TestClient(create_app(plain), base_url=BASE) as c:
        words = c.get("/api/words").json()
    assert [ch["name"] for ch in words["channels"]] == ["shape", "colour", "size"]
    assert words["channels"][2]["default"] == "medium" and "sphere" in words["channels"][0]["values"]
    assert {"left of", "right of", "in front of", "behind"} <= set(words["relations"])
    assert "on" not in words["relations"] and "larger than" not in words["relations"]
    with channels.scope(texture):
        session = Session(Agent(), seed=3, memory_path=str(tmp_path / "m.json"))
        with TestClient(create_app(session), base_url=BASE) as c:
            assert [ch["name"] for ch in c.get("/api/words").json()["channels"]][-1] == "texture"
            scene = c.post("/api/scene", json={"op": "add", "object": "striped red box", "at": [0.3, 0.5]}).json()
            assert (scene["objects"][0]["texture"], scene["objects"][0]["name"]) == ("striped", "striped red box")
            r = c.post("/api/scene", json={"op": "add", "object": "red", "at": [0.7, 0.5]})
            assert r.json()["error"].startswith("say colour, shape and texture, e.g. 'plain red box'")
            c.post("/api/lesson", json={"signal": "inform", "content": "striped red box"})
            text = c.get("/api/transcript.toml").text
            assert 'texture = "striped"' in text
            assert lessonfile.loads(text).lessons[0].objects[0].appearance["texture"] == "striped"
            path = tmp_path / "state.json"
            state.write(path, state.Saved(1, session.table.objects, [], [], None))
            assert state.read(path).objects == session.table.objects
    with pytest.raises(UserError, match="must have shape, colour, size, x, y and distractor"):
        state.read(path)


def test_a_layout_with_a_relation_and_one_object_is_a_4xx_not_a_500(client) -> None:
    for content in ("red box left of", "red box near"):
        r = client.post("/api/scene", json={"op": "layout", "content": content})
        assert "needs a second object" in one_line_4xx(r)


def test_no_other_page_may_frame_the_console(client) -> None:
    # a page that framed the console under a lure got clicks from the console's own origin
    for r in (client.get("/"), client.get("/api/memory"), client.post("/api/lesson", json={}),
              client.get("/", headers={"Host": "evil.example"})):
        assert r.headers["x-frame-options"] == "DENY"
        assert r.headers["content-security-policy"] == "frame-ancestors 'none'"


def test_a_port_in_use_is_one_line_before_the_console_says_where_to_open_it() -> None:
    import socket

    from aileen.errors import UserError
    from aileen.web.app import listen

    taken = socket.socket()
    taken.bind(("127.0.0.1", 0))
    taken.listen()
    try:
        with pytest.raises(UserError, match="cannot serve on 127.0.0.1:.*address already in use"):
            listen("127.0.0.1", taken.getsockname()[1])
    finally:
        taken.close()
    free = listen("127.0.0.1", 0)
    free.close()


def test_confirm_after_a_react_that_missed_its_goal_is_refused(client) -> None:
    """It stored a "move" in which nothing moved, and the downloaded file, replayed, ignored
    it (a lesson file's confirm counts only where the goal holds)."""
    client.post("/api/scene", json={"op": "add", "object": "red box", "at": [0.3, 0.5]})
    client.post("/api/scene", json={"op": "add", "object": "blue cone", "at": [0.6, 0.5]})
    r = client.post("/api/lesson", json={"signal": "react", "content": "move the red box right of the blue cone"})
    assert r.status_code == 200 and r.json()["goal_holds"] is False  # 'move' was never shown
    msg = one_line_4xx(client.post("/api/lesson", json={"signal": "confirm", "content": ""}))
    assert "did not see it reached" in msg
    assert "r_move" not in client.get("/api/memory").json()["concepts"]


def test_the_trainer_lays_out_an_actions_start(client) -> None:
    """As `aileen teach`'s `scene move ...` and a lesson file do (it was refused: "expected
    '<colour> <shape> [<relation> <colour> <shape>]'")."""
    r = client.post("/api/scene", json={"op": "layout", "content": "move red box right of blue cone"})
    assert r.status_code == 200, r.text
    box, cone = (next(o for o in r.json()["objects"] if o["name"] == n) for n in ("red box", "blue cone"))
    # the mover starts clearly not right of the reference
    assert box["x"] < cone["x"] + 0.05 or abs(box["y"] - cone["y"]) > abs(box["x"] - cone["x"])
    assert "expected" in one_line_4xx(client.post("/api/scene", json={"op": "layout", "content": "move red box"}))


def test_a_client_that_hangs_up_mid_body_is_a_4xx_not_a_traceback() -> None:
    """starlette's ClientDisconnect went up as a 60-line traceback on the server's stderr."""
    import asyncio

    from starlette.requests import Request

    from aileen.web.app import BadRequest, _json_body

    async def receive() -> dict:
        return {"type": "http.disconnect"}

    request = Request({"type": "http", "method": "POST", "headers": [], "path": "/api/lesson"}, receive)
    with pytest.raises(BadRequest, match="closed the connection"):
        asyncio.run(_json_body(request))


@pytest.mark.parametrize("body", [
    b'{"signal": "verify", "content": "red \\ud800 box"}',
    b'{"signal": "inform", "content": "red box", "\\udc00": 1}',
    b'{"op": "add", "object": "red \\udfff box"}',
])
def test_text_with_a_lone_surrogate_is_refused_and_nothing_is_recorded(client, body) -> None:
    # it was stored, and every later transcript, lessons list and save answered 500 (UnicodeEncodeError)
    client.post("/api/scene", json={"op": "add", "object": "red box"})
    client.post("/api/lesson", json={"signal": "inform", "content": "red box"})
    path = "/api/scene" if b'"op"' in body else "/api/lesson"
    r = client.post(path, content=body, headers={"Content-Type": "application/json"})
    assert r.status_code == 400 and "surrogate" in one_line_4xx(r)
    assert len(client.get("/api/lessons").json()["records"]) == 1
    assert client.get("/api/transcript.toml").status_code == 200
    assert client.post("/api/save", json={}).status_code == 200


@pytest.mark.parametrize("content", ["red box / blue cone", "red/blue box", "red box left/right of blue cone"])
def test_a_sentence_with_a_slash_is_a_sentence_not_a_file_path(client, content) -> None:
    # it was refused as "looks like a file path": the agent answers it, as any sentence
    client.post("/api/scene", json={"op": "add", "object": "red box"})
    r = client.post("/api/lesson", json={"signal": "verify", "content": content})
    assert "file path" not in r.text and r.status_code == 200, r.text


@pytest.mark.parametrize("content", ["/etc/passwd", "~/m.json", "../m.json", "./m.json", "a\\b", "x/../../etc"])
def test_a_string_that_looks_like_a_path_is_refused(client, content) -> None:
    r = client.post("/api/lesson", json={"signal": "inform", "content": content})
    assert "file path" in one_line_4xx(r)


@pytest.mark.parametrize("method", ["DELETE", "PATCH", "PUT"])
def test_a_method_the_console_does_not_take_is_405_not_415(client, method) -> None:
    # DELETE /api/scene answered 415 "send the body as application/json"
    r = client.request(method, "/api/scene")
    assert r.status_code == 405 and "only GET, HEAD, OPTIONS and POST requests" in one_line_4xx(r)  # as docs/console.md says
    assert client.request(method, "/api/scene", headers={"Host": "evil.example"}).status_code == 403


@pytest.mark.parametrize("op", ["remove", "move"])
@pytest.mark.parametrize("index", [True, "0", 1.0, None])
def test_an_index_that_is_no_whole_number_is_a_type_error(client, op, index) -> None:
    # {"op": "remove", "index": true} said "no object True on the table"
    client.post("/api/scene", json={"op": "add", "object": "red box"})
    r = client.post("/api/scene", json={"op": op, "index": index, "at": [0.5, 0.5]} if op == "move"
                    else {"op": op, "index": index})
    assert "'index' must be a whole number" in one_line_4xx(r)
    assert len(client.get("/api/scene").json()["objects"]) == 1


def test_the_limits_the_api_holds_to_are_the_documented_ones(client) -> None:
    """console.md did not say the 200-character sentence or the distractor limits (0-8 laid
    out, 0-12 scattered); the refusals say the declared limits."""
    from pathlib import Path

    from aileen.web.session import MAX_CONTENT
    from aileen.web.table import LAID_OUT_DISTRACTORS, MAX_OBJECTS

    doc = (Path(__file__).resolve().parents[1] / "docs" / "console.md").read_text()
    assert f"{MAX_CONTENT} characters at most" in doc
    assert f"(0-{LAID_OUT_DISTRACTORS})" in doc and f"(0-{MAX_OBJECTS}," in doc
    assert f"0 to {LAID_OUT_DISTRACTORS}" in one_line_4xx(client.post("/api/scene", json={
        "op": "layout", "content": "red box", "distractors": LAID_OUT_DISTRACTORS + 1}))
    assert f"0 to {LAID_OUT_DISTRACTORS}" in one_line_4xx(client.post("/api/scene", json={
        "objects": ["red box"], "distractors": LAID_OUT_DISTRACTORS + 1}))
    assert f"0 to {MAX_OBJECTS}" in one_line_4xx(client.post("/api/scene", json={
        "op": "shuffle", "distractors": MAX_OBJECTS + 1}))
    assert f"{MAX_CONTENT} characters" in one_line_4xx(client.post("/api/lesson", json={
        "signal": "inform", "content": "red box " * 30}))


def test_a_memory_file_removed_under_the_server_is_said_so_and_save_works_again(tmp_path) -> None:
    """m.json deleted under serve: every Save said the file "was changed ... left as that program
    wrote it" (it no longer existed), as a 400, and no Save ever worked again."""
    from aileen.memory.store import MemoryFile

    mem = tmp_path / "m.json"
    with MemoryFile.open(mem) as held:
        session = Session(Agent(), seed=3, memory_path=str(mem), memory_file=held)
        with TestClient(create_app(session), base_url=BASE, raise_server_exceptions=False) as c:
            c.post("/api/scene", json={"op": "add", "object": "red box"})
            c.post("/api/lesson", json={"signal": "inform", "content": "red box"})
            assert c.post("/api/save", json={}).status_code == 200
            mem.unlink()
            r = c.post("/api/save", json={})
            assert r.status_code == 409, r.text  # a conflict with another program, not the client's error
            said = r.json()["error"]
            recovered = next(tmp_path.glob("m.recovered-*[0-9].json"))
            assert "was removed by another program" in said and f"is in {recovered}" in said, said
            assert "left as that program wrote it" not in said
            assert c.post("/api/save", json={}).status_code == 200  # nothing left to overwrite: it is written anew
            assert "r_red" in mem.read_text()
            Agent().save(str(mem))  # another program writes it
            r = c.post("/api/save", json={})
            assert r.status_code == 409 and "changed by another program" in r.json()["error"]


def test_a_save_the_disk_refuses_is_a_server_error_not_the_clients(tmp_path, monkeypatch) -> None:
    import errno

    from aileen.memory.store import MemoryFile

    mem = tmp_path / "m.json"
    with MemoryFile.open(mem) as held:
        session = Session(Agent(), seed=3, memory_path=str(mem), memory_file=held)

        def full(path: str) -> None:
            raise OSError(errno.ENOSPC, "No space left on device")

        monkeypatch.setattr(session.agent, "save", full)
        with TestClient(create_app(session), base_url=BASE, raise_server_exceptions=False) as c:
            r = c.post("/api/save", json={})
    assert r.status_code == 507 and "No space left on device" in r.json()["error"], r.text


@pytest.mark.parametrize("refusal", ["port", "experiment"])
def test_a_refused_serve_start_leaves_no_files(tmp_path, capsys, refusal) -> None:
    """The port in use: the start said so only after writing new.console.start.json and the
    lock file .new.json.lock beside the memory, and left them there."""
    import socket

    from aileen.cli import main

    folder = tmp_path / "d"
    folder.mkdir()
    taken = socket.socket()
    taken.bind(("127.0.0.1", 0))
    taken.listen()
    port = taken.getsockname()[1]
    try:
        if refusal == "port":
            args = ["--port", str(port)]
        else:
            taken.close()
            args = ["--port", str(port), "--experiment", str(tmp_path / "nowhere")]
        assert main(["serve", "--memory", str(folder / "new.json"), *args]) == 2
    finally:
        taken.close()
    err = capsys.readouterr().err
    assert ("address already in use" if refusal == "port" else "no such experiment folder") in err, err
    assert sorted(p.name for p in folder.iterdir()) == []


@pytest.mark.parametrize("frame", ["12345678901234567890123", "9" * 5000])
def test_a_frame_number_too_long_is_out_of_range_not_no_whole_number(client, frame) -> None:
    """?frame=12345678901234567890123 was told "'frame' must be a whole number"; it is one."""
    said = one_line_4xx(client.get(f"/api/scene.png?frame={frame}"))
    assert "out of range" in said and "the last lesson has 0 frames" in said and len(said) < 200, said
    assert "must be a whole number" in one_line_4xx(client.get("/api/scene.png?frame=-1"))


def test_options_is_answered_with_the_paths_methods_as_the_docs_list_it_allowed(client) -> None:
    """OPTIONS, which docs/console.md lists as allowed, got a bare 405."""
    r = client.options("/api/scene")
    assert r.status_code == 204 and r.headers["allow"] == "GET, HEAD, OPTIONS, POST", r.headers
    assert client.options("/api/save").headers["allow"] == "OPTIONS, POST"
    assert "access-control-allow-origin" not in r.headers  # no other page is granted anything
    assert client.options("/api/nothing").status_code == 404
    assert client.options("/api/scene", headers={"Host": "evil.example"}).status_code == 403


def test_the_lessons_answer_has_the_shape_the_docs_give_it(client) -> None:
    """docs/console.md said "every record so far" of GET /api/lessons, not that they come as
    {"records": [...]}."""
    from pathlib import Path

    doc = (Path(__file__).resolve().parents[1] / "docs" / "console.md").read_text()
    row = next(line for line in doc.splitlines() if line.startswith("| `GET /api/lessons`"))
    client.post("/api/scene", json={"op": "add", "object": "red box"})
    given = client.post("/api/lesson", json={"signal": "inform", "content": "red box"}).json()
    answer = client.get("/api/lessons").json()
    assert '`{"records": [...]}`' in row and list(answer) == ["records"] and answer["records"] == [given]

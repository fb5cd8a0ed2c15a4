"""The console's page in a real browser, through `aileen serve` itself: Playwright (PyPI)
driving Debian's chromium.

Each test starts `python -m aileen serve --memory ...` as its own process, so the memory
file's lock, the save when the server stops (Ctrl-C) and the table and transcript kept
beside the memory are what a person gets. Skips cleanly without the `webtest` extra or
without /usr/bin/chromium (CI installs both). Prints the scene-update latency: from the
lesson's answer reaching the page to the new camera image shown. With
AILEEN_SCREENSHOTS=DIR it also writes the page's screenshots there (docs/console*.png were
taken this way).
"""

from __future__ import annotations

import http.client
import http.server
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")
sync_api = pytest.importorskip("playwright.sync_api")

from aileen.cli import main  # noqa: E402
from aileen.memory.concept import ConceptMemory  # noqa: E402

CHROMIUM = os.environ.get("AILEEN_CHROMIUM", "/usr/bin/chromium")
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]
ROOT = Path(__file__).resolve().parents[1]
SHOTS = os.environ.get("AILEEN_SCREENSHOTS")

if not (os.path.isfile(CHROMIUM) or shutil.which(CHROMIUM)):
    pytest.skip(f"no chromium at {CHROMIUM} (apt-get install chromium)", allow_module_level=True)


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Served:
    """One `aileen serve` process on a free port."""

    def __init__(self, memory: Path, *, seed: int = 7) -> None:
        self.memory = memory
        self.port = _free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])))
        self.err_path = memory.with_name(f"serve-{self.port}.err")
        self._err = open(self.err_path, "w")
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "aileen", "serve", "--memory", str(memory), "--port", str(self.port),
             "--seed", str(seed)], env=env, stdout=subprocess.PIPE, stderr=self._err, text=True)
        line = self.proc.stdout.readline()  # "aileen serve: open http://...", printed once it is about to listen
        assert "open http://" in line, (line, self.stderr())
        for _ in range(300):
            try:
                self.get("/api/scene")
                break
            except OSError:
                time.sleep(0.05)

    def stderr(self) -> str:
        self._err.flush()
        return self.err_path.read_text()

    def request(self, method: str, path: str, body: bytes | None = None, headers: dict | None = None):
        c = http.client.HTTPConnection("127.0.0.1", self.port, timeout=60)
        try:
            c.request(method, path, body=body, headers=headers or {})
            r = c.getresponse()
            return r.status, r.read()
        finally:
            c.close()

    def get(self, path: str):
        status, data = self.request("GET", path)
        assert status == 200, (status, data)
        return json.loads(data)

    def stop(self) -> tuple[int, str]:
        """Ctrl-C, as a person stops it; (exit status, stderr)."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(timeout=60)
            except subprocess.TimeoutExpired:  # pragma: no cover - a hang is the failure
                self.proc.kill()
                self.proc.wait()
        self._err.close()
        return self.proc.returncode, self.err_path.read_text()


@pytest.fixture()
def serve(tmp_path):
    started: list[Served] = []

    def start(memory: Path | None = None, **kw) -> Served:
        s = Served(memory or tmp_path / "memory.json", **kw)
        started.append(s)
        return s

    yield start
    for s in started:
        s.stop()


@pytest.fixture()
def browser():
    with sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=ARGS, headless=True)
        yield b
        b.close()


@pytest.fixture()
def page(browser):
    pg = browser.new_page(viewport={"width": 1280, "height": 1100}, accept_downloads=True)
    errors: list[str] = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    yield pg
    assert not errors, errors  # no script error on the page


def open_console(page, url: str) -> None:
    page.goto(url + "/")
    page.wait_for_function("window.aileenReady === true && document.getElementById('scene').complete")


def click_table(page, x: float, y: float) -> None:
    """Click the table at (x, y) metres (1 m table, 256 px camera shown twice as large)."""
    box = page.locator("#scene").bounding_box()
    page.mouse.click(box["x"] + x * 512, box["y"] + (1 - y) * 512)


def add_at(page, description: str, x: float, y: float) -> None:
    n = len(objects(page))
    page.fill("#object", description)
    click_table(page, x, y)
    page.wait_for_function(f"document.querySelectorAll('#objects li').length === {n + 1}")


def clear(page) -> None:
    page.click("#clear")
    page.wait_for_function("document.querySelectorAll('#objects li').length === 0")


def say(page, signal_: str, content: str = "") -> float:
    """Give a lesson through the form; returns ms from the answer to the new image shown."""
    n = page.locator("#transcript li").count()
    page.select_option("#signal", signal_)
    page.fill("#content", content)
    page.evaluate("window.aileenTiming = {answerAt: null, sceneAt: null, sceneMs: null}")
    page.click("#send")
    page.wait_for_function("window.aileenTiming.sceneMs !== null", timeout=60_000)
    page.wait_for_function(f"document.querySelectorAll('#transcript li').length === {n + 1}")
    page.wait_for_function("!document.body.classList.contains('busy')")
    return page.evaluate("window.aileenTiming.sceneMs")


def verdict(page, what: str) -> None:
    """`wrong` or `confirm`: a lesson without a new image."""
    n = page.locator("#transcript li").count()
    page.select_option("#signal", what)
    page.fill("#content", "")
    page.click("#send")
    page.wait_for_function(f"document.querySelectorAll('#transcript li').length === {n + 1}", timeout=60_000)
    page.wait_for_function("!document.body.classList.contains('busy')")


def objects(page) -> list[str]:
    return page.locator("#objects li").all_inner_texts()


def shot(page, name: str, selector: str | None = None) -> None:
    """The page as a person sees it (the window), or one part of it, for docs/console.md."""
    if SHOTS:
        Path(SHOTS).mkdir(parents=True, exist_ok=True)
        target = page.locator(selector) if selector else page
        target.screenshot(path=str(Path(SHOTS) / name))


def test_teach_red_box_and_left_of_in_the_browser(serve, page, tmp_path, capsys) -> None:
    console = serve()
    open_console(page, console.url)
    times = []

    add_at(page, "red box", 0.5, 0.5)  # add by clicking a spot
    times.append(say(page, "inform", "red box"))
    # learning is shown as learning, not as a failure
    assert page.inner_text("#result") == "learned"
    assert "r_red" in page.inner_text("#verdict") and "r_box" in page.inner_text("#verdict")
    assert page.get_attribute("#answer", "class") == "learned"

    clear(page)
    add_at(page, "blue cone", 0.7, 0.6)
    times.append(say(page, "inform", "blue cone"))

    page.fill("#object", "red box")
    page.select_option("#relation", "left of")
    page.fill("#of", "blue cone")
    page.click("#add")  # add by description, in a relation to another object
    page.wait_for_function("document.querySelectorAll('#objects li').length === 2")
    times.append(say(page, "inform", "red box left of blue cone"))
    assert "r_left_of" in page.inner_text("#answer")

    # the object list names objects as the agent does
    assert sorted(t.split()[0] for t in objects(page)) == ["o1", "o2"]

    # drag the blue cone somewhere else, then verify on the new table
    cone = next(o for o in console.get("/api/scene")["objects"] if o["name"] == "blue cone")
    box = page.locator("#scene").bounding_box()
    page.mouse.move(box["x"] + cone["x"] * 512, box["y"] + (1 - cone["y"]) * 512)
    page.mouse.down()
    page.mouse.move(box["x"] + 0.85 * 512, box["y"] + (1 - 0.55) * 512, steps=5)
    page.mouse.up()
    page.wait_for_function("document.getElementById('objects').innerText.includes('(0.85, 0.55)')")
    moved = next(o for o in console.get("/api/scene")["objects"] if o["name"] == "blue cone")
    assert (moved["x"], moved["y"]) == pytest.approx((0.85, 0.55), abs=0.01)

    times.append(say(page, "verify", "red box left of blue cone"))
    assert page.inner_text("#result") == "success", page.inner_text("#answer")
    assert "the trainer expected success: right" in page.inner_text("#answer")
    highlighted = page.inner_text("#highlight")
    assert highlighted.startswith("grounded (highlighted): o")  # the grounded objects are drawn highlighted
    assert "left of" in highlighted  # and the relation between them, as an arrow on the image
    times.append(say(page, "verify", "blue cone left of red box"))
    assert page.inner_text("#result") == "failure" and "right" in page.inner_text("#answer")

    page.click("#memory-open")
    concept = "#memory details[data-symbol='r_left_of']"
    page.wait_for_selector(concept)
    assert page.locator(f"{concept} table.facts td.bar div").count() >= 1  # facts with probability bars
    assert "examples seen" in page.inner_text(f"{concept} table.quality")
    assert "verify this session" in page.inner_text(f"{concept} table.quality")
    shot(page, "console.png")
    shot(page, "console-memory.png", concept)

    page.click("#save")
    page.wait_for_function("document.getElementById('status').textContent.startsWith('saved')")
    assert "r_left_of" in ConceptMemory.load(console.memory)

    with page.expect_download() as dl:
        page.click("#download")
    lesson_file = tmp_path / "session.toml"
    dl.value.save_as(lesson_file)
    shown = console.get("/api/lessons")["records"]
    with capsys.disabled():
        print(f"\nscene update after a lesson's answer: {', '.join(f'{t:.1f}' for t in times)} ms "
              f"(median {sorted(times)[len(times) // 2]:.1f}, max {max(times):.1f} ms, {len(times)} lessons)")
    rc = main(["run", str(lesson_file), "--json"])
    replay = [json.loads(line) for line in capsys.readouterr().out.splitlines() if line.strip()]
    assert rc == 0
    keys = ("signal", "content", "result", "reason", "referents", "created", "stored", "expected", "correct")
    assert [{k: r[k] for k in keys} for r in replay] == [{k: r[k] for k in keys} for r in shown]


def test_react_describe_wrong_confirm_and_undo_in_the_browser(serve, page) -> None:
    console = serve()
    open_console(page, console.url)
    add_at(page, "red box", 0.5, 0.5)
    say(page, "inform", "red box")
    clear(page)
    add_at(page, "blue cone", 0.5, 0.5)
    say(page, "inform", "blue cone")
    add_at(page, "red box", 0.2, 0.3)
    say(page, "inform", "move the red box right of the blue cone")  # demonstrated, then told
    assert "r_move" in page.inner_text("#verdict")

    # react: the agent moves the red box right of the blue cone on a new table
    clear(page)
    add_at(page, "blue cone", 0.6, 0.6)
    add_at(page, "red box", 0.3, 0.3)
    say(page, "react", "move the red box right of the blue cone")
    assert "the goal was reached" in page.inner_text("#answer"), page.inner_text("#answer")
    assert "right of" in page.inner_text("#highlight")
    shot(page, "console-react.png")
    verdict(page, "confirm")
    assert "kept its plan as an example" in page.inner_text("#verdict")

    # a lesson the trainer cannot give: the reason beside the lesson box, in plain words
    page.select_option("#signal", "react")
    page.fill("#content", "red box")
    page.click("#send")
    page.wait_for_selector("#lesson-error:not([hidden])")
    error = page.inner_text("#lesson-error")
    assert error.startswith("react needs something to do") and "<console>" not in error and "lesson" not in error
    assert page.get_attribute("#answer", "class") == "stale"  # the previous answer is not shown as this one's
    shot(page, "console-error.png")

    # describe three objects: "A and B and C" is graded, and true
    clear(page)
    add_at(page, "green sphere", 0.2, 0.8)
    say(page, "inform", "green sphere")
    add_at(page, "red box", 0.5, 0.5)
    add_at(page, "blue cone", 0.8, 0.3)
    say(page, "describe")
    said = page.inner_text("#verdict")
    assert said.count(" and ") == 2 and said.endswith("true of the table") and "NOT" not in said, said

    # verify a sentence with new words: the agent says no, the trainer says that is wrong
    clear(page)
    add_at(page, "yellow cylinder", 0.4, 0.4)
    say(page, "verify", "yellow cylinder")
    assert "WRONG" in page.inner_text("#answer")
    verdict(page, "wrong")
    assert "r_yellow" in page.inner_text("#verdict") and "r_cylinder" in page.inner_text("#verdict")
    assert "r_yellow" in console.get("/api/memory")["concepts"]

    # undo the correction: the memory is as it was before it
    lessons = page.locator("#transcript li").count()
    page.click("#undo-lesson")
    page.wait_for_function(f"document.querySelectorAll('#transcript li').length === {lessons - 1}")
    assert page.inner_text("#undone").startswith("undid wrong")
    assert "r_yellow" not in console.get("/api/memory")["concepts"]
    assert len(console.get("/api/lessons")["records"]) == lessons - 1
    rc, err = console.stop()
    assert rc == 128 + signal.SIGINT and "what was learned is saved in" in err, err  # Ctrl-C: saved, exit 130
    assert "r_yellow" not in ConceptMemory.load(console.memory) and "r_move" in ConceptMemory.load(console.memory)


def test_a_stale_tab_reloads_the_table_and_a_double_click_teaches_once(serve, browser) -> None:
    console = serve()
    a = browser.new_page(viewport={"width": 1280, "height": 1100})
    b = browser.new_page(viewport={"width": 1280, "height": 1100})
    open_console(a, console.url)
    add_at(a, "red box", 0.3, 0.5)
    add_at(a, "blue cylinder", 0.7, 0.5)
    open_console(b, console.url)
    assert len(objects(b)) == 2
    # tab a removes the red box; tab b, still showing it, asks to remove "the red box" (index 0)
    a.locator("#objects li", has_text="red box").locator("button").click()
    a.wait_for_function("document.querySelectorAll('#objects li').length === 1")
    b.locator("#objects li", has_text="red box").locator("button").click()
    b.wait_for_selector("#scene-error:not([hidden])")
    assert "changed in another tab" in b.inner_text("#scene-error")
    b.wait_for_function("document.querySelectorAll('#objects li').length === 1")
    assert "blue cylinder" in objects(b)[0]  # the blue cylinder was not removed in its place
    assert [o["name"] for o in console.get("/api/scene")["objects"]] == ["blue cylinder"]

    # a double click on "say" gives one lesson; the buttons are disabled meanwhile
    b.select_option("#signal", "inform")
    b.fill("#content", "blue cylinder")
    b.evaluate("window.seenDisabled = false; new MutationObserver(() => { if (document.getElementById('send').disabled)"
               " window.seenDisabled = true; }).observe(document.getElementById('send'), {attributes: true})")
    b.dblclick("#send")
    b.wait_for_function("document.querySelectorAll('#transcript li').length === 1", timeout=60_000)
    b.wait_for_function("!document.body.classList.contains('busy')")
    time.sleep(0.5)
    assert b.evaluate("window.seenDisabled")
    assert len(console.get("/api/lessons")["records"]) == 1
    # a lesson given in another tab: this tab's next edit is refused and reloaded, not applied blind
    a.click("#clear")
    a.wait_for_selector("#scene-error:not([hidden])")
    assert "changed in another tab" in a.inner_text("#scene-error")
    assert len(objects(a)) == 1
    for p in (a, b):
        p.close()


def test_a_restart_restores_the_table_and_transcript(serve, page, tmp_path) -> None:
    memory = tmp_path / "m.json"
    first = serve(memory)
    open_console(page, first.url)
    add_at(page, "red box", 0.4, 0.4)
    say(page, "inform", "red box")
    add_at(page, "blue cone", 0.7, 0.6)
    # while it runs, the memory file is locked: another run is refused at once
    other = subprocess.run([sys.executable, "-m", "aileen", "run", str(ROOT / "lessons" / "visual.toml"),
                            "--memory", str(memory)], capture_output=True, text=True, timeout=120,
                           env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert other.returncode == 2 and "in use by another aileen run" in other.stderr
    rc, err = first.stop()
    assert rc == 128 + signal.SIGINT and "what was learned is saved in" in err, err
    assert (tmp_path / "m.console.json").is_file()

    second = serve(memory)
    assert "restored the table (2 objects) and 1 lesson from" in second.stderr()
    open_console(page, second.url)
    page.wait_for_function("document.querySelectorAll('#transcript li').length === 1")
    assert 'inform "red box"' in page.inner_text("#transcript")
    assert sorted(" ".join(t.split()[1:3]) for t in objects(page)) == ["blue cone", "red box"]
    say(page, "verify", "red box")
    assert page.inner_text("#result") == "success"


class _Evil(http.server.BaseHTTPRequestHandler):
    """A web page on another origin of this machine that tries to teach the console."""

    target = ""

    def do_GET(self) -> None:  # noqa: N802 - the http.server API
        page = f"""<!doctype html><html><body>
<form id="f" method="POST" action="{self.target}/api/lesson" enctype="text/plain">
<input name='{{"signal": "inform", "content": "evil", "x": "' value='"}}'></form>
<script>
fetch("{self.target}/api/scene", {{method: "POST", mode: "no-cors", headers: {{"Content-Type": "text/plain"}},
       body: JSON.stringify({{op: "clear"}})}}).catch(() => {{}});
fetch("{self.target}/api/save", {{method: "POST", mode: "no-cors", body: "{{}}"}}).catch(() => {{}});
setTimeout(() => document.getElementById("f").submit(), 300);
</script></body></html>"""
        data = page.encode()
        self.send_response(200)
        self.send_header("Content-Type", "text/html")
        self.send_header("Content-Length", str(len(data)))
        self.end_headers()
        self.wfile.write(data)

    def log_message(self, *args) -> None:
        pass


def test_a_page_on_another_origin_cannot_teach_the_console(serve, page) -> None:
    console = serve()
    console.request("POST", "/api/scene", json.dumps({"op": "add", "object": "red box"}).encode(),
                    {"Content-Type": "application/json"})
    _Evil.target = console.url
    evil = http.server.ThreadingHTTPServer(("127.0.0.1", 0), _Evil)
    threading.Thread(target=evil.serve_forever, daemon=True).start()
    try:
        page.goto(f"http://localhost:{evil.server_address[1]}/")
        page.wait_for_url(f"{console.url}/api/lesson", timeout=30_000)  # the form was sent, and refused
        assert "another web page" in page.content() or "Content-Type" in page.content()
    finally:
        evil.shutdown()
    assert console.get("/api/lessons")["records"] == []
    assert [o["name"] for o in console.get("/api/scene")["objects"]] == ["red box"]
    assert not console.memory.exists()
    # DNS rebinding: the console's address under another name
    status, body = console.request("GET", "/api/memory", headers={"Host": f"evil.example:{console.port}"})
    assert status == 403 and b"answers only at" in body
    status, _ = console.request("POST", "/api/lesson", b'{"signal": "inform", "content": "red box"}',
                                {"Content-Type": "text/plain"})
    assert status == 415

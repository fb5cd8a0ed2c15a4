"""The console's page in a real browser: Playwright (PyPI) driving Debian's chromium.

Skips cleanly without the `webtest` extra or without /usr/bin/chromium (CI installs both).
Prints the scene-update latency: from the lesson's answer reaching the page to the new
camera image shown. With AILEEN_SCREENSHOT=PATH it also writes the page's screenshot there
(docs/console.png was taken this way).
"""

from __future__ import annotations

import json
import os
import shutil
import socket
import threading
import time

import pytest

pytest.importorskip("starlette")
uvicorn = pytest.importorskip("uvicorn")
sync_api = pytest.importorskip("playwright.sync_api")

from aileen.agent import Agent  # noqa: E402
from aileen.cli import main  # noqa: E402
from aileen.memory.concept import ConceptMemory  # noqa: E402
from aileen.web.app import create_app  # noqa: E402
from aileen.web.session import Session  # noqa: E402

CHROMIUM = os.environ.get("AILEEN_CHROMIUM", "/usr/bin/chromium")
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]

if not (os.path.isfile(CHROMIUM) or shutil.which(CHROMIUM)):
    pytest.skip(f"no chromium at {CHROMIUM} (apt-get install chromium)", allow_module_level=True)


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture()
def server(tmp_path):
    session = Session(Agent(), seed=7, memory_path=str(tmp_path / "memory.json"))
    port = _free_port()
    srv = uvicorn.Server(uvicorn.Config(create_app(session), host="127.0.0.1", port=port, log_level="warning"))
    thread = threading.Thread(target=srv.run, daemon=True)
    thread.start()
    for _ in range(200):
        if srv.started:
            break
        time.sleep(0.02)
    yield f"http://127.0.0.1:{port}", session
    srv.should_exit = True
    thread.join(timeout=10)


@pytest.fixture()
def page():
    with sync_api.sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=ARGS, headless=True)
        pg = browser.new_page(viewport={"width": 1280, "height": 1100}, accept_downloads=True)
        yield pg
        browser.close()


def click_table(page, x: float, y: float) -> None:
    """Click the table at (x, y) metres (1 m table, 256 px camera shown twice as large)."""
    box = page.locator("#scene").bounding_box()
    page.mouse.click(box["x"] + x * 512, box["y"] + (1 - y) * 512)


def say(page, signal: str, content: str) -> float:
    """Give a lesson through the form; returns ms from the answer to the new image shown."""
    page.select_option("#signal", signal)
    page.fill("#content", content)
    page.evaluate("window.aileenTiming = {answerAt: null, sceneAt: null, sceneMs: null}")
    page.click("#send")
    page.wait_for_function("window.aileenTiming.sceneMs !== null", timeout=30_000)
    return page.evaluate("window.aileenTiming.sceneMs")


def objects(page) -> list[str]:
    return page.locator("#objects li").all_inner_texts()


def test_teach_red_box_and_left_of_in_the_browser(server, page, tmp_path, capsys) -> None:
    url, session = server
    page.goto(url + "/")
    page.wait_for_function("document.getElementById('scene').complete")
    times = []

    page.fill("#object", "red box")
    click_table(page, 0.5, 0.5)  # add by clicking a spot
    page.wait_for_function("document.querySelectorAll('#objects li').length === 1")
    times.append(say(page, "inform", "red box"))
    assert "created" in page.inner_text("#answer")

    page.click("#clear")
    page.fill("#object", "blue cone")
    click_table(page, 0.7, 0.6)
    page.wait_for_function("document.querySelectorAll('#objects li').length === 1")
    times.append(say(page, "inform", "blue cone"))

    page.fill("#object", "red box")
    page.select_option("#relation", "left of")
    page.fill("#of", "blue cone")
    page.click("#add")  # add by description, in a relation to another object
    page.wait_for_function("document.querySelectorAll('#objects li').length === 2")
    times.append(say(page, "inform", "red box left of blue cone"))
    assert "r_left_of" in page.inner_text("#answer")

    # drag the blue cone somewhere else, then verify on the new table
    before = objects(page)
    box = page.locator("#scene").bounding_box()
    cone = session.table.objects[0]
    page.mouse.move(box["x"] + cone.x * 512, box["y"] + (1 - cone.y) * 512)
    page.mouse.down()
    page.mouse.move(box["x"] + 0.85 * 512, box["y"] + (1 - 0.55) * 512, steps=5)
    page.mouse.up()
    page.wait_for_function(f"document.querySelector('#objects li').innerText !== {json.dumps(before[0])}")
    assert (session.table.objects[0].x, session.table.objects[0].y) == pytest.approx((0.85, 0.55), abs=0.01)

    times.append(say(page, "verify", "red box left of blue cone"))
    assert page.inner_text("#result") == "success", page.inner_text("#answer")
    assert "expected success: right" in page.inner_text("#answer")
    highlighted = page.inner_text("#highlight")
    assert highlighted.startswith("grounded (highlighted): o")  # the grounded objects are drawn highlighted
    times.append(say(page, "verify", "blue cone left of red box"))
    assert page.inner_text("#result") == "failure"

    page.click("#memory-open")
    page.wait_for_selector("#memory details[data-symbol='r_left_of']")
    assert "generalization" in page.inner_text("#memory details[data-symbol='r_left_of']") or \
        "example" in page.inner_text("#memory details[data-symbol='r_left_of']")
    shot = os.environ.get("AILEEN_SCREENSHOT")
    if shot:
        page.screenshot(path=shot, full_page=True)

    page.click("#save")
    page.wait_for_function("document.getElementById('status').textContent.startsWith('saved')")
    assert "r_left_of" in ConceptMemory.load(tmp_path / "memory.json")

    with page.expect_download() as dl:
        page.click("#download")
    lesson_file = tmp_path / "session.toml"
    dl.value.save_as(lesson_file)
    shown = session.records
    with capsys.disabled():
        print(f"\nscene update after a lesson's answer: {', '.join(f'{t:.1f}' for t in times)} ms "
              f"(median {sorted(times)[len(times) // 2]:.1f}, max {max(times):.1f} ms, {len(times)} lessons)")
    rc = main(["run", str(lesson_file), "--json"])
    replay = [json.loads(line) for line in capsys.readouterr().out.splitlines() if line.strip()]
    assert rc == 0
    keys = ("signal", "content", "result", "reason", "referents", "created", "stored", "expected", "correct")
    assert [{k: r[k] for k in keys} for r in replay] == [{k: r[k] for k in keys} for r in shown]

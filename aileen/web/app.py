"""The console's HTTP app: the JSON API (docs/console.md) and the page's files.

The only module that imports the ASGI stack (Starlette). It holds one `Session`; requests
run one at a time (an asyncio lock, the work itself in a worker thread so the event loop
stays free). Every failure is a 4xx (bad request) or 500 with a one-line JSON reason, never a
traceback page; request bodies are size-limited and may not name files.
"""

from __future__ import annotations

import asyncio
import json
from importlib import resources
from pathlib import Path
from typing import Any

from starlette.applications import Starlette
from starlette.concurrency import run_in_threadpool
from starlette.exceptions import HTTPException
from starlette.requests import Request
from starlette.responses import JSONResponse, PlainTextResponse, Response
from starlette.routing import Route

from aileen.errors import UserError
from aileen.web.session import Session

MAX_BODY = 64 * 1024  # bytes: a sentence or a scene edit is tiny
# Keys that would name a file; the memory path is fixed when the server starts.
FILE_KEYS = frozenset({"path", "file", "filename", "memory", "dir", "out", "rules", "url"})
PAGE_FILES = {"index.html": "text/html; charset=utf-8", "console.js": "text/javascript; charset=utf-8",
              "console.css": "text/css; charset=utf-8"}


class BadRequest(Exception):
    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status
        self.message = message


def _error(status: int, message: str) -> JSONResponse:
    return JSONResponse({"error": " ".join(str(message).split())}, status_code=status)


async def _json_body(request: Request) -> dict[str, Any]:
    """The request's JSON object, read at most MAX_BODY bytes."""
    declared = request.headers.get("content-length")
    if declared is not None and declared.isdigit() and int(declared) > MAX_BODY:
        raise BadRequest(413, f"request body over {MAX_BODY} bytes")
    chunks, size = [], 0
    async for chunk in request.stream():
        size += len(chunk)
        if size > MAX_BODY:
            raise BadRequest(413, f"request body over {MAX_BODY} bytes")
        chunks.append(chunk)
    raw = b"".join(chunks)
    if not raw.strip():
        return {}
    try:
        data = json.loads(raw)
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise BadRequest(400, f"malformed JSON: {exc}") from None
    if not isinstance(data, dict):
        raise BadRequest(400, "the request body must be a JSON object")
    _no_paths(data)
    return data


def _no_paths(value: Any, key: str = "") -> None:
    """Refuse anything that names a file: keys like 'path', strings with slashes."""
    if isinstance(value, dict):
        for k, v in value.items():
            if str(k).lower() in FILE_KEYS:
                raise BadRequest(400, f"requests cannot name files ('{k}'); the memory file is fixed at start")
            _no_paths(v, str(k))
    elif isinstance(value, list):
        for v in value:
            _no_paths(v, key)
    elif isinstance(value, str) and ("/" in value or "\\" in value or value.startswith("~")):
        raise BadRequest(400, f"'{key}' looks like a file path; requests cannot name files")


def create_app(session: Session, *, experiment: str | Path | None = None) -> Starlette:
    """The app around one session. `experiment`: an `aileen experiment` output folder to show."""
    lock = asyncio.Lock()
    exp = _experiment_files(Path(experiment)) if experiment is not None else []

    async def call(fn, *args, **kw):
        async with lock:
            return await run_in_threadpool(fn, *args, **kw)

    async def page(request: Request) -> Response:
        name = request.path_params.get("name", "index.html")
        if name not in PAGE_FILES:
            return _error(404, f"no page file {name!r}")
        text = resources.files("aileen.web").joinpath("static", name).read_bytes()
        return Response(text, media_type=PAGE_FILES[name], headers={"Cache-Control": "no-store"})

    async def get_scene(request: Request) -> Response:
        return JSONResponse(await call(session.scene))

    async def post_scene(request: Request) -> Response:
        data = await _json_body(request)
        op = data.pop("op", None)
        if not isinstance(op, str):
            raise BadRequest(400, "expected {\"op\": \"add\"|\"move\"|\"remove\"|\"clear\"|\"shuffle\"|\"layout\"|\"undo\", ...}")
        return JSONResponse(await call(session.edit, op, **data))

    async def scene_png(request: Request) -> Response:
        q = request.query_params
        frame = q.get("frame")
        if frame is not None and not frame.isdigit():
            raise BadRequest(400, "'frame' must be a whole number")
        png = await call(session.image, overlay_on=q.get("overlay", "0") == "1",
                         frame=int(frame) if frame is not None else None)
        return Response(png, media_type="image/png", headers={"Cache-Control": "no-store"})

    async def post_lesson(request: Request) -> Response:
        data = await _json_body(request)
        extra = sorted(set(data) - {"signal", "content"})
        if extra:
            raise BadRequest(400, f"unexpected field(s): {', '.join(extra)}; expected signal and content")
        return JSONResponse(await call(session.lesson, data.get("signal"), data.get("content")))

    async def lessons(request: Request) -> Response:
        return JSONResponse({"records": session.records})

    async def lesson_file(request: Request) -> Response:
        text = await call(session.lesson_file)
        return PlainTextResponse(text, media_type="application/toml",
                                 headers={"Content-Disposition": 'attachment; filename="session.toml"'})

    async def memory(request: Request) -> Response:
        return JSONResponse(await call(session.memory))

    async def save(request: Request) -> Response:
        await _json_body(request)
        return JSONResponse({"saved": await call(session.save)})

    async def experiment_index(request: Request) -> Response:
        if experiment is None:
            return JSONResponse({"files": [], "summary": None, "note": "start with --experiment DIR to show curves"})
        summary = None
        s = Path(experiment) / "summary.json"
        if s.is_file():
            try:
                summary = json.loads(s.read_text(encoding="utf-8"))
            except (OSError, ValueError):
                summary = None
        return JSONResponse({"files": [{"index": i, "name": n} for i, (n, _) in enumerate(exp)], "summary": summary})

    async def experiment_file(request: Request) -> Response:
        k = request.path_params["k"]
        if not 0 <= k < len(exp):
            raise BadRequest(404, f"no experiment file {k}")
        name, path = exp[k]
        kind = "image/png" if name.endswith(".png") else "text/csv; charset=utf-8"
        return Response(path.read_bytes(), media_type=kind)

    async def on_user_error(request: Request, exc: Exception) -> Response:
        assert isinstance(exc, UserError)
        return _error(400, exc.format())

    async def on_bad(request: Request, exc: Exception) -> Response:
        assert isinstance(exc, BadRequest)
        return _error(exc.status, exc.message)

    async def on_http(request: Request, exc: Exception) -> Response:
        assert isinstance(exc, HTTPException)
        return _error(exc.status_code, exc.detail)

    async def on_other(request: Request, exc: Exception) -> Response:
        return _error(500, f"internal error: {type(exc).__name__}: {exc}")

    routes = [
        Route("/", page),
        Route("/static/{name}", page),
        Route("/api/scene", get_scene, methods=["GET"]),
        Route("/api/scene", post_scene, methods=["POST"]),
        Route("/api/scene.png", scene_png),
        Route("/api/lesson", post_lesson, methods=["POST"]),
        Route("/api/lessons", lessons),
        Route("/api/transcript.toml", lesson_file),
        Route("/api/memory", memory),
        Route("/api/save", save, methods=["POST"]),
        Route("/api/experiment", experiment_index),
        Route("/api/experiment/{k:int}", experiment_file),
    ]
    return Starlette(routes=routes, exception_handlers={
        UserError: on_user_error, BadRequest: on_bad, HTTPException: on_http, Exception: on_other})


def _experiment_files(folder: Path) -> list[tuple[str, Path]]:
    """The PNG curves and summary CSVs of an experiment folder (two levels deep), by index:
    requests name them by number, never by path."""
    if not folder.is_dir():
        raise UserError("no such experiment folder", path=str(folder))
    found = [p for pat in ("*.png", "*/*.png", "*summary*.csv", "*/*summary*.csv") for p in folder.glob(pat)]
    return [(str(p.relative_to(folder)), p) for p in sorted(set(found))]


def serve(app: Starlette, *, host: str, port: int) -> int | None:
    """Run until stopped; returns the stop signal that ended it (None: none did). Uvicorn
    shuts down gracefully on SIGINT and SIGTERM (the request in flight finishes) and re-raises
    the signal afterwards, past the caller's save; here SIGHUP and SIGQUIT shut it down the
    same way, and the signal is handed back instead, so the caller saves first."""
    import signal

    import uvicorn

    from aileen.lifecycle import STOP_SIGNALS

    server = uvicorn.Server(uvicorn.Config(app, host=host, port=port, log_level="warning"))
    got: list[int] = []

    def stop(sig: int, frame: Any) -> None:
        got.append(sig)
        server.handle_exit(sig, frame)

    before = {s: signal.signal(s, stop) for s in STOP_SIGNALS}
    try:
        server.run()
    finally:
        for s, h in before.items():
            signal.signal(s, h)
    return got[0] if got else None

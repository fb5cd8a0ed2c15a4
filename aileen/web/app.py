"""The console's HTTP app: the JSON API (docs/console.md) and the page's files.

The only module that imports the ASGI stack (Starlette). It holds one `Session`; requests
run one at a time (an asyncio lock, the work itself in a worker thread so the event loop
stays free). Every failure is a 4xx (bad request; 409 for a stale table or a memory file another
program changed) or a 5xx (a save the disk refused, a defect) with a one-line JSON reason, never a
traceback page; request bodies are size-limited, nest a few levels at most and may not name
files. Before any route, `guard.refusal` turns away requests addressed to a foreign host (DNS
rebinding) and changes from another origin or not sent as JSON (403, 415).
"""

from __future__ import annotations

import asyncio
import errno
import json
import re
import socket
from functools import partial
from importlib import resources
from pathlib import Path
from typing import Any

from starlette.applications import Starlette
from starlette.exceptions import HTTPException
from starlette.requests import ClientDisconnect, Request
from starlette.responses import JSONResponse, PlainTextResponse, Response
from starlette.routing import Match, Route

from aileen.errors import UserError
from aileen.memory.store import SaveRefused
from aileen.strictjson import deeper_than, no_duplicates
from aileen.web import guard
from aileen.web.session import Session, Stale

MAX_BODY = 64 * 1024  # bytes: a sentence or a scene edit is tiny
BODY_SECONDS = 10.0  # a body must arrive within this: a client that stalls half-way held a stop for ever
GRACE_SECONDS = 60  # a stop waits this long for requests in flight (a lesson's work runs on: `Session.busy`)
WHOLE = re.compile(r"[0-9]{1,9}")  # a frame or file number, ASCII digits ("²" is a digit to str.isdigit)
MAX_DEPTH = 4  # {"objects": [{"object": ..., "at": [x, y]}]} is the deepest body the API takes
# Keys that would name a file; the memory path is fixed when the server starts.
FILE_KEYS = frozenset({"path", "file", "filename", "memory", "dir", "out", "rules", "url"})
# A string that looks like a path: from the root, home or here (`/`, `~`, `./`, `../`), a step
# up anywhere, or a backslash. Not any "/": "red box / blue cone" is a sentence (it was refused).
PATH_LIKE = re.compile(r"^\s*(?:[/~]|\.\.?/)|(?:^|/)\.\.(?:/|$)|\\")
PAGE_FILES = {"index.html": "text/html; charset=utf-8", "console.js": "text/javascript; charset=utf-8",
              "console.css": "text/css; charset=utf-8"}


class BadRequest(Exception):
    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status
        self.message = message


async def _answer_of(work: asyncio.Future) -> Any:
    """The result of a request's work, running in a worker thread. A stop that gives up waiting
    for the request (a second signal, or GRACE_SECONDS past) cancels it, but the work runs on
    (a thread cannot be stopped) and the save on leaving waits for it (`Session.busy`): the
    client was told 503 "not carried out" of a lesson that ran and was saved. So the answer
    still waits for the work, GRACE_SECONDS more at most, and is then its result."""
    loop = asyncio.get_running_loop()
    deadline: float | None = None
    while not work.done():
        try:
            await asyncio.wait({work}, timeout=None if deadline is None else max(0.0, deadline - loop.time()))
        except asyncio.CancelledError:
            task = asyncio.current_task()
            if task is not None:
                task.uncancel()
            deadline = deadline if deadline is not None else loop.time() + GRACE_SECONDS
            continue
        if deadline is not None and not work.done() and loop.time() >= deadline:
            raise BadRequest(503, "the server stopped while this request was still being carried out; "
                             "whatever it finishes is saved with the memory (the server's last line says where)")
    return work.result()


def _error(status: int, message: str) -> JSONResponse:
    return JSONResponse({"error": " ".join(str(message).split())}, status_code=status)


async def _json_body(request: Request) -> dict[str, Any]:
    """The request's JSON object, read at most MAX_BODY bytes."""
    declared = request.headers.get("content-length")
    if declared is not None and declared.isdigit() and int(declared) > MAX_BODY:
        raise BadRequest(413, f"request body over {MAX_BODY} bytes")
    chunks, size = [], 0
    try:
        async with asyncio.timeout(BODY_SECONDS):
            async for chunk in request.stream():
                size += len(chunk)
                if size > MAX_BODY:
                    raise BadRequest(413, f"request body over {MAX_BODY} bytes")
                chunks.append(chunk)
    except TimeoutError:  # the request in flight kept a stop (SIGTERM, twice) waiting for ever
        raise BadRequest(408, f"the request body did not arrive within {BODY_SECONDS:g} s") from None
    except ClientDisconnect:  # the client hung up mid-body: nobody to answer (it was a traceback)
        raise BadRequest(400, "the client closed the connection before the body was sent") from None
    raw = b"".join(chunks)
    if not raw.strip():
        return {}
    try:
        data = json.loads(raw, object_pairs_hook=no_duplicates)
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise BadRequest(400, f"malformed JSON: {exc}") from None
    except RecursionError:  # the parser recurses per level
        raise BadRequest(400, f"malformed JSON: nested deeper than {MAX_DEPTH} levels") from None
    except ValueError as exc:  # a key twice, a number of thousands of digits
        raise BadRequest(400, f"malformed JSON: {exc}") from None
    if not isinstance(data, dict):
        raise BadRequest(400, "the request body must be a JSON object")
    if deeper_than(data, MAX_DEPTH):
        raise BadRequest(400, f"malformed JSON: nested deeper than {MAX_DEPTH} levels")
    _no_surrogates(data)
    _no_paths(data)
    return data


def _no_surrogates(value: Any) -> None:
    """Refuse text with a lone surrogate (JSON's "\\ud800" escape): it has no UTF-8, so a
    sentence holding one was recorded and then every transcript, lesson list and save, and
    the save on leaving, failed on it (500s, the session lost)."""
    if isinstance(value, dict):
        for k, v in value.items():
            _no_surrogates(k)
            _no_surrogates(v)
    elif isinstance(value, list):
        for v in value:
            _no_surrogates(v)
    elif isinstance(value, str) and not value.isascii():
        try:
            value.encode("utf-8")
        except UnicodeEncodeError:
            raise BadRequest(400, f"malformed JSON: the text {ascii(value)[:60]} holds a lone surrogate "
                             "(\\ud800-\\udfff), which is not a character") from None


def _no_paths(value: Any, key: str = "") -> None:
    """Refuse anything that names a file: keys like 'path', strings that look like paths."""
    if isinstance(value, dict):
        for k, v in value.items():
            if str(k).lower() in FILE_KEYS:
                raise BadRequest(400, f"requests cannot name files ('{k}'); the memory file is fixed at start")
            _no_paths(v, str(k))
    elif isinstance(value, list):
        for v in value:
            _no_paths(v, key)
    elif isinstance(value, str) and PATH_LIKE.search(value):
        raise BadRequest(400, f"'{key}' looks like a file path; requests cannot name files")


def create_app(session: Session, *, experiment: str | Path | None = None,
               hosts: frozenset[str] | None = None) -> Starlette:
    """The app around one session. `experiment`: an `aileen experiment` output folder to show.
    `hosts`: the host names requests may be addressed to (`guard.allowed_hosts(--host)`;
    default this machine's)."""
    lock = asyncio.Lock()
    exp = experiment_files(Path(experiment)) if experiment is not None else []
    allowed = hosts if hosts is not None else guard.allowed_hosts("127.0.0.1")

    def busy(fn, *args, **kw):
        with session.busy:
            return fn(*args, **kw)

    async def call(fn, *args, **kw):
        async with lock:  # a stop while waiting here: the request was not carried out (`Guard`, 503)
            return await _answer_of(asyncio.get_running_loop().run_in_executor(None, partial(busy, fn, *args, **kw)))

    def checked(version: object, fn, *args, **kw):
        """`fn` on the table this version names (the check and the change under one lock)."""
        session.check_version(version)
        return fn(*args, **kw)

    async def page(request: Request) -> Response:
        name = request.path_params.get("name", "index.html")
        if name not in PAGE_FILES:
            return _error(404, f"no page file {name!r}")
        text = resources.files("aileen.web").joinpath("static", name).read_bytes()
        return Response(text, media_type=PAGE_FILES[name], headers={"Cache-Control": "no-store"})

    async def words(request: Request) -> Response:
        return JSONResponse(session.words())

    async def get_scene(request: Request) -> Response:
        return JSONResponse(await call(session.scene))

    async def post_scene(request: Request) -> Response:
        data = await _json_body(request)
        version = data.pop("version", None)
        if "op" not in data and "objects" in data:  # the whole table in one call
            extra = sorted(set(data) - {"objects", "relation", "distractors"})
            if extra:
                raise BadRequest(400, f"unexpected field(s): {', '.join(extra)}; expected objects, "
                                 "relation, distractors and version")
            return JSONResponse(await call(checked, version, session.set_table, data["objects"],
                                           data.get("relation"), data.get("distractors", 0)))
        op = data.pop("op", None)
        if not isinstance(op, str):
            raise BadRequest(400, "expected {\"op\": \"add\"|\"move\"|\"remove\"|\"clear\"|\"shuffle\"|\"layout\"|"
                             "\"undo\", ...} or {\"objects\": [...], \"relation\": ...}")
        return JSONResponse(await call(checked, version, session.edit, op, **data))

    async def scene_png(request: Request) -> Response:
        q = request.query_params
        frame = q.get("frame")
        if frame is not None and not WHOLE.fullmatch(frame):
            if frame.isascii() and frame.isdigit():  # a whole number, too long to be a frame's
                frames = await call(lambda: len(session.view().frames))
                shown = frame if len(frame) <= 20 else f"{frame[:20]}... ({len(frame)} digits)"
                raise BadRequest(400, f"'frame' {shown} is out of range: the last lesson has {frames} frames")
            raise BadRequest(400, "'frame' must be a whole number")
        png = await call(session.image, overlay_on=q.get("overlay", "0") == "1",
                         frame=int(frame) if frame is not None else None)
        return Response(png, media_type="image/png", headers={"Cache-Control": "no-store"})

    async def post_lesson(request: Request) -> Response:
        data = await _json_body(request)
        extra = sorted(set(data) - {"signal", "content", "version"})
        if extra:
            raise BadRequest(400, f"unexpected field(s): {', '.join(extra)}; expected signal and content")
        return JSONResponse(await call(checked, data.get("version"), session.lesson, data.get("signal"),
                                       data.get("content")))

    async def undo_lesson(request: Request) -> Response:
        data = await _json_body(request)
        extra = sorted(set(data) - {"version"})
        if extra:
            raise BadRequest(400, f"unexpected field(s): {', '.join(extra)}; expected only version")
        return JSONResponse(await call(checked, data.get("version"), session.undo_lesson))

    async def forget(request: Request) -> Response:
        data = await _json_body(request)
        extra = sorted(set(data) - {"concept", "version"})
        if extra:
            raise BadRequest(400, f"unexpected field(s): {', '.join(extra)}; expected concept")
        return JSONResponse(await call(checked, data.get("version"), session.forget, data.get("concept")))

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
        text = request.path_params["k"]
        k = int(text) if WHOLE.fullmatch(text) else -1
        if not 0 <= k < len(exp):
            raise BadRequest(404, f"no experiment file {text[:20]!r}")
        name, path = exp[k]
        kind = "image/png" if name.endswith(".png") else "text/csv; charset=utf-8"
        return Response(path.read_bytes(), media_type=kind)

    async def on_user_error(request: Request, exc: Exception) -> Response:
        assert isinstance(exc, UserError)
        return _error(_status_of(exc), exc.format())

    async def on_stale(request: Request, exc: Exception) -> Response:
        assert isinstance(exc, Stale)
        return JSONResponse({"error": exc.message, "version": exc.version}, status_code=409)

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
        Route("/api/words", words),
        Route("/api/scene", get_scene, methods=["GET"]),
        Route("/api/scene", post_scene, methods=["POST"]),
        Route("/api/scene.png", scene_png),
        Route("/api/lesson", post_lesson, methods=["POST"]),
        Route("/api/lesson/undo", undo_lesson, methods=["POST"]),
        Route("/api/lessons", lessons),
        Route("/api/transcript.toml", lesson_file),
        Route("/api/memory", memory),
        Route("/api/forget", forget, methods=["POST"]),
        Route("/api/save", save, methods=["POST"]),
        Route("/api/experiment", experiment_index),
        Route("/api/experiment/{k}", experiment_file),
    ]
    app = Starlette(routes=routes, exception_handlers={
        UserError: on_user_error, Stale: on_stale, BadRequest: on_bad, HTTPException: on_http, Exception: on_other})
    def methods_of(scope: dict) -> frozenset[str]:
        """The methods a path takes (`OPTIONS` answers them; none: no such path)."""
        found: set[str] = set()
        for route in routes:
            if route.matches(scope)[0] != Match.NONE:
                found |= route.methods or set()
        return frozenset(found)

    app.add_middleware(Guard, hosts=allowed, methods_of=methods_of)
    return app


#: Sent with every response: no other page may show the console in a frame (a page that
#: framed it under a lure got clicks from the console's own origin, which the guard lets in).
NO_FRAMING = [(b"x-frame-options", b"DENY"), (b"content-security-policy", b"frame-ancestors 'none'")]


class Guard:
    """ASGI middleware: `guard.refusal` before any route (a refused request never reaches one),
    and `NO_FRAMING` on every response."""

    def __init__(self, app, hosts: frozenset[str], methods_of=None) -> None:  # noqa: ANN001
        self.app = app
        self.hosts = hosts
        self.methods_of = methods_of  # a path's methods, for OPTIONS (None: every method the console takes)

    async def __call__(self, scope, receive, send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return

        async def unframed(message) -> None:  # noqa: ANN001
            if message["type"] == "http.response.start":
                message = {**message, "headers": [*message.get("headers", []), *NO_FRAMING]}
            await send(message)

        headers = [(k.decode("latin-1"), v.decode("latin-1")) for k, v in scope.get("headers", [])]
        refused = guard.refusal(scope.get("method", "GET"), headers, self.hosts)
        if refused is not None:
            await _error(*refused)(scope, receive, unframed)
            return
        if scope.get("method") == "OPTIONS":  # allowed (guard.METHODS), so answered: a bare 405 it was
            await _options(scope, self.methods_of)(scope, receive, unframed)
            return
        started = []

        async def sent(message) -> None:  # noqa: ANN001
            started.append(message["type"])
            await unframed(message)

        try:
            await self.app(scope, receive, sent)
        except asyncio.CancelledError:  # the server is stopping and gave up waiting for it
            # uvicorn printed a traceback of the cancellation for each such request
            if "http.response.start" not in started:
                await _error(503, "the server is stopping; the request was not carried out")(scope, receive, unframed)


def _status_of(exc: UserError) -> int:
    """A user error's HTTP status: 400, but a save that did not reach the memory file is none of
    the client's doing (every save failure was a 400): 409 when another program changed or
    removed the file, 507 when the disk is full, else 500. The body is `{"error": ...}` all the same."""
    if not isinstance(exc, SaveRefused):
        return 400
    if exc.conflict:
        return 409
    return 507 if exc.errno in (errno.ENOSPC, errno.EDQUOT) else 500


def _options(scope: dict, methods_of) -> Response:  # noqa: ANN001
    """The answer to OPTIONS: `204` and `Allow`, the path's methods; no CORS header, so it lets
    no other page do anything. A path the console does not have is `404`."""
    taken = methods_of(scope) if methods_of is not None else frozenset(guard.METHODS)
    if not taken:
        return _error(404, f"no such path {scope.get('path', '')[:60]!r}")
    allow = ", ".join(sorted(taken | {"OPTIONS"}))
    return Response(status_code=204, headers={"Allow": allow})


def listen(host: str, port: int) -> socket.socket:
    """The server's listening socket, bound before the console says where to open it: a port
    in use was reported by uvicorn's own error after "open http://..." (exit 3)."""
    try:
        family = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)[0][0]
        sock = socket.socket(family, socket.SOCK_STREAM)
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind((host, port))
    except OSError as exc:
        raise UserError(f"cannot serve on {host}:{port}: {(exc.strerror or str(exc)).lower()}"
                        + ("; another program uses the port: try --port with another number"
                           if exc.errno == errno.EADDRINUSE else "")) from None
    sock.set_inheritable(True)
    return sock


def experiment_files(folder: Path) -> list[tuple[str, Path]]:
    """The PNG curves and summary CSVs of an experiment folder (two levels deep), by index:
    requests name them by number, never by path."""
    if not folder.is_dir():
        raise UserError("no such experiment folder", path=str(folder))
    found = [p for pat in ("*.png", "*/*.png", "*summary*.csv", "*/*summary*.csv") for p in folder.glob(pat)]
    return [(str(p.relative_to(folder)), p) for p in sorted(set(found))]


def serve(app: Starlette, *, host: str, port: int, sock: socket.socket | None = None) -> int | None:
    """Run until stopped; returns the stop signal that ended it (None: none did). Uvicorn
    shuts down gracefully on SIGINT and SIGTERM (the request in flight finishes, for
    GRACE_SECONDS at most; a second signal stops waiting) and re-raises
    the signal afterwards, past the caller's save; here SIGHUP and SIGQUIT shut it down the
    same way, and the signal is handed back instead, so the caller saves first."""
    import signal

    import uvicorn

    from aileen.lifecycle import listened

    # no lifespan: the app has no start-up or shutdown work, and a forced stop printed the
    # cancelled lifespan task's traceback
    got: list[int] = []

    class Server(uvicorn.Server):
        """Uvicorn's server, its stop signals noted as they come: it handles SIGINT and SIGTERM
        itself while it runs and raises them again afterwards, last first, so SIGTERM then
        SIGINT was said to be a stop by SIGINT (exit 130)."""

        def handle_exit(self, sig: int, frame: Any) -> None:
            stop(sig, frame)

    server = Server(uvicorn.Config(app, host=host, port=port, log_level="warning", lifespan="off",
                                   timeout_graceful_shutdown=GRACE_SECONDS))

    def stop(sig: int, frame: Any) -> None:
        got.append(sig)
        uvicorn.Server.handle_exit(server, sig, frame)
        if len(got) > 1:  # a second stop signal, of any kind, stops waiting for requests in flight
            server.force_exit = True

    before = {s: signal.signal(s, stop) for s in listened()}
    try:
        server.run(sockets=[sock] if sock is not None else None)
    finally:
        for s, h in before.items():
            signal.signal(s, h)
    return got[0] if got else None

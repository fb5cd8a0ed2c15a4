"""`aileen serve`: the teaching console in the browser (needs the `web` extra)."""

from __future__ import annotations

import argparse
import importlib.util
import sys

from aileen import argtypes, lifecycle
from aileen.errors import UserError

LOCAL = ("127.0.0.1", "localhost", "::1")


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "serve",
        help="a teaching console in the browser: see the table, teach by typing, watch the memory",
        description="Start a local web server holding one agent and one table, and print the address to "
        "open. The memory file is fixed here; requests cannot name files. Needs the 'web' extra.",
    )
    p.add_argument("--memory", metavar="PATH", help="load the memory from PATH if it exists; the page's Save "
                   "button and leaving the server save it there")
    p.add_argument("--port", type=int, default=8765, help="TCP port (default 8765)")
    p.add_argument("--host", default="127.0.0.1", help="address to bind (default 127.0.0.1: this machine only)")
    p.add_argument("--rules", metavar="DIR", help="a directory of .lp files overriding the shipped asp/ rules")
    from aileen.reasoning.guard import add_limit_args

    add_limit_args(p)
    p.add_argument("--seed", type=argtypes.seed, default=0, help="seed for the table, layouts and camera noise")
    p.add_argument("--experiment", metavar="DIR", help="an `aileen experiment` output folder whose curves to show")
    from aileen.curriculum.commands import add_autosave, add_senses

    add_senses(p)
    add_autosave(p, "every lesson, verdict, undo and forget, with the table and transcript")
    p.set_defaults(handler=_serve)


def replay_options(args: argparse.Namespace) -> tuple[str, ...]:
    """The options of `aileen serve` that `aileen run` needs to replay the session to the same
    answers (`--senses`, `--rules`): the lesson format has no key for them, so the downloaded
    file's description says them (it did not, and the replay answered otherwise)."""
    options: list[str] = []
    if args.senses is not None:
        options += ["--senses", args.senses]
    if args.rules is not None:
        options += ["--rules", args.rules]
    return tuple(options)


def _serve(args: argparse.Namespace) -> int:
    if importlib.util.find_spec("starlette") is None or importlib.util.find_spec("uvicorn") is None:
        raise UserError("aileen serve needs the 'web' extra: pip install -e \".[web]\"")
    if not 1 <= args.port <= 65535:
        raise UserError(f"--port must be 1-65535, got {args.port}")
    from pathlib import Path

    from aileen.web.app import experiment_files, listen

    args.perception, args.agent, args.without = "detector", "asp", []
    # what can refuse the start before anything is written: a refused start (the port in use)
    # wrote the console's start copy and the memory's lock file before it said so, and left them
    if args.experiment is not None:
        experiment_files(Path(args.experiment))
    sock = listen(args.host, args.port)
    try:
        return _serve_on(args, sock)
    finally:
        sock.close()


def _serve_on(args: argparse.Namespace, sock) -> int:  # noqa: ANN001 - a bound socket.socket
    """`aileen serve` on the socket bound for it: open the memory, resume, serve, save on leaving."""
    from aileen.curriculum.commands import keep, make_agent, open_memory
    from aileen.web import guard
    from aileen.web.app import GRACE_SECONDS, create_app, serve
    from aileen.web.session import Session

    memory_file = open_memory(args)  # locked while the server runs, like `aileen run`
    try:
        agent, _ = make_agent(args, memory_file)
        session = Session(agent, seed=args.seed, memory_path=args.memory, memory_file=memory_file,
                          replay=replay_options(args), autosave=args.autosave)
        # before `resume` writes the start copy: a missing --experiment folder refuses the start
        app = create_app(session, experiment=args.experiment, hosts=guard.allowed_hosts(args.host))
        resumed = session.resume()  # the table and transcript saved beside the memory file
        if resumed:
            print(f"aileen serve: {resumed}", file=sys.stderr)

        def keep_all(stopped: bool = True) -> str | None:
            """The memory, then the table and transcript beside it, once the lesson in flight
            (if any) is done (waiting GRACE_SECONDS at most: the reasoning limits end a lesson)."""
            idle = session.busy.acquire(timeout=GRACE_SECONDS)
            try:
                note = session.keep() if memory_file is not None else keep(memory_file, agent, stopped=stopped)
            finally:
                if idle:
                    session.busy.release()
            return note

        if args.host not in LOCAL:
            print(f"aileen serve: warning: binding {args.host}: anyone who can reach this machine can teach "
                  "the agent and save its memory", file=sys.stderr)
        shown = f"[{args.host}]" if ":" in args.host else args.host
        print(f"aileen serve: open http://{shown}:{args.port}/  (Ctrl-C to stop)", flush=True)
        try:
            with lifecycle.keeper(keep_all):  # rules stuck in clingo
                stopped = serve(app, host=args.host, port=args.port, sock=sock)
        except (KeyboardInterrupt, UserError) as exc:  # a signal before the server took over
            if lifecycle.kept(exc) is None:
                lifecycle.set_kept(exc, keep_all(stopped=isinstance(exc, KeyboardInterrupt)))
            raise
        # Leaving saves (the server has finished the request in flight). A signal during the
        # save waits for it (lifecycle.deferred) and is then raised saying where it went.
        note = keep_all(stopped=stopped is not None)
        if stopped is not None:
            raise lifecycle.Stopped(stopped, note)
        if note:
            print(f"aileen serve: {note}", file=sys.stderr)
    finally:
        if memory_file is not None:
            memory_file.close()
    return 0

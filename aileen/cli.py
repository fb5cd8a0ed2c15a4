"""The `aileen` command.

Each area of the package contributes its subcommands through a `commands` module with a
`register(subparsers)` function; handlers import their heavy dependencies lazily so that
`aileen --help` stays fast. A `UserError` becomes one line on stderr and exit code 2; a stop
signal (SIGINT, SIGTERM, SIGHUP, SIGQUIT: `aileen.lifecycle`) one line saying what was kept
and exit code 128 + the signal's number.
"""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import signal
import sys
from collections.abc import Sequence

from aileen import __version__, lifecycle
from aileen.domain import extensions
from aileen.errors import UserError

# Order = order in `aileen --help`.
COMMAND_MODULES: tuple[str, ...] = (
    "aileen.curriculum.commands",  # run, teach
    "aileen.experiments.commands",  # experiment
    "aileen.world.commands",  # render
    "aileen.perception.commands",  # perception dataset|train|eval|tune-color
    "aileen.memory.commands",  # memory show
    "aileen.reasoning.commands",  # asp check|comprehend|plan
    "aileen.web.commands",  # serve
)


#: What a closed output cut short, for a command that does not say (its parser's default
#: `closed_output`, beside `handler`: "so the lessons after it were not given").
CLOSED_DEFAULT = "so the command stopped before its end"


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="aileen",
        description="An interactive concept learner for embodied agents (AILEEN, re-created).",
    )
    parser.add_argument("--version", action="version", version=f"aileen {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in COMMAND_MODULES:
        if importlib.util.find_spec(name) is None:
            continue
        importlib.import_module(name).register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    # The stop signals are answered from the first moment: reading the commands imports the
    # heavy modules (about a second), and a SIGTERM then ended the process with no line.
    lifecycle.install()
    listening = lifecycle.listened()
    args: argparse.Namespace | None = None
    try:
        try:  # declarations of the user's own, before the commands read the domain (`AILEEN_DOMAIN`)
            if extensions.entries():
                # the lesson readers first: the keys they read (`channels.reserve_keys`) are then
                # there when a channel of one's own is declared, and its module is named
                from aileen.curriculum import legacy, lessonfile  # noqa: F401
            extensions.load()
        except UserError as exc:
            _say(f"aileen: {exc.format()}", None)
            return 2
        parser = build_parser()
        args = parser.parse_args(argv)
        handler = getattr(args, "handler", None)
        if handler is None:
            parser.print_help()
            return 0
        result = handler(args)
    except UserError as exc:
        _say(f"aileen: {exc.format()}", lifecycle.kept(exc))
        return 2
    except KeyboardInterrupt as exc:  # lifecycle.Stopped for every stop signal
        signum = getattr(exc, "signum", None) or lifecycle.stopping() or signal.SIGINT
        _say(f"aileen: stopped by {lifecycle.signal_name(signum)}", lifecycle.kept(exc))
        return lifecycle.exit_status(signum)
    except BrokenPipeError as exc:
        # nobody reads the output any more (`aileen run ... | head`): the command did not do
        # all it was asked (a run gave only some of its lessons), so it is no success; what
        # was learned is saved. What was cut short is the command's to say (`closed_output`).
        _say("aileen: stopped: the output was closed (nobody reads it any more), "
             + (getattr(args, "closed_output", None) or CLOSED_DEFAULT), lifecycle.kept(exc))
        return 128 + signal.SIGPIPE
    finally:
        lifecycle.uninstall()
        if argv is None:  # the `aileen` command (tests pass their own arguments and go on)
            lifecycle.ended(listening)
    return int(result or 0)


def _say(line: str, note: str | None) -> None:
    """The one line an error or a stop ends with, and where what was learned went. A closed
    terminal (SIGHUP) makes stderr fail: the exit status still tells."""
    try:
        print(line + (f"; {note}" if note else ""), file=sys.stderr, flush=True)
    except (OSError, ValueError):
        pass


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())

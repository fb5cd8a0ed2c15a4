"""The teaching console in the browser (`aileen serve`, docs/console.md).

`session` holds the agent, the trainer's table and the transcript and gives the lessons (no web
framework); beside it, one job each: `table` and `edits` (the trainer's table and the page's
edits of it), `view` and `overlay` (what the page shows of the agent's perception), `history`
(undo), `transcript` (the lesson file), `concepts` (the memory panel), `state` (kept beside the
memory file), `guard` (which requests are answered). `app` is the one module that imports the
ASGI stack (the `web` extra); `static/` is the page.
"""

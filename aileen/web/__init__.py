"""The teaching console in the browser (`aileen serve`, docs/console.md).

`session` holds the agent, the trainer's table and the transcript (no web framework);
`app` is the one module that imports the ASGI stack (the `web` extra); `static/` is the page.
"""

"""The command line (typer), thin: parse arguments, call the core, hand results to report.

``app.py`` holds the shared typer app and ``main``; each command (or command group) is a
small module with a ``register(app)`` function, listed in ``app.COMMAND_MODULES``.
"""

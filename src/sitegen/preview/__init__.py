"""The author's preview: serving a built site (server.py) and, with --watch, rebuilding it when the
book changes and reloading the open pages (watch.py, reload.js)."""

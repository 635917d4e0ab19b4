"""A small web server for the built site, run in a thread of the test session.

It serves _site the way GitHub Pages does in the ways the tests can see: HTML, CSS,
scripts, SVG and other text compressed with gzip when the browser accepts it (so a
response's Content-Length is what crosses the network), fonts and images as they are,
a folder's index.html for its address, and leave to cache for ten minutes. The browser
still reports a response taken from its cache, with the headers it was first sent with,
so a page's weight is the same whatever was loaded before; caching only spares the
browser compiling the site's scripts, and the test tools injected into pages, again for
every page.

Test tools from node_modules (axe-core, say) are served under NODE_MODULES_URL.
"""

from __future__ import annotations

import functools
import gzip
import http.server
import io
import os
import threading
from pathlib import Path
from urllib.parse import unquote, urlsplit

NODE_MODULES_URL = "/__node_modules__/"

# What GitHub Pages compresses; fonts (woff2 is compressed already) and images are not.
COMPRESSED_TYPES = {"text/html", "text/css", "text/javascript", "text/plain", "text/xml",
                    "application/json", "application/xml", "image/svg+xml"}


@functools.lru_cache(maxsize=512)
def _gzipped(path: str, mtime_ns: int) -> bytes:
    return gzip.compress(Path(path).read_bytes(), compresslevel=6, mtime=0)


class _Handler(http.server.SimpleHTTPRequestHandler):
    protocol_version = "HTTP/1.1"
    # Not left to the machine's /etc/mime.types.
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map,
                      ".html": "text/html", ".css": "text/css", ".js": "text/javascript",
                      ".mjs": "text/javascript", ".json": "application/json",
                      ".xml": "application/xml", ".txt": "text/plain", ".svg": "image/svg+xml",
                      ".png": "image/png", ".woff2": "font/woff2", ".woff": "font/woff",
                      ".ttf": "font/ttf", ".wasm": "application/wasm"}

    def __init__(self, *args, node_modules: Path, **kwargs):
        self.node_modules = node_modules
        super().__init__(*args, **kwargs)

    def translate_path(self, path):
        if not path.startswith(NODE_MODULES_URL):
            return super().translate_path(path)
        relative = unquote(urlsplit(path).path[len(NODE_MODULES_URL):])
        file = (self.node_modules / relative).resolve()
        return str(file) if file.is_relative_to(self.node_modules) else str(self.node_modules / "-")

    def send_head(self):
        path = self.translate_path(self.path)
        if os.path.isdir(path) and urlsplit(self.path).path.endswith("/"):
            path = os.path.join(path, "index.html")
        content_type = self.guess_type(path)
        accepts_gzip = "gzip" in self.headers.get("Accept-Encoding", "")
        if not (os.path.isfile(path) and accepts_gzip and content_type in COMPRESSED_TYPES):
            return super().send_head()
        body = _gzipped(path, os.stat(path).st_mtime_ns)
        self.send_response(200)
        self.send_header("Content-Type", content_type)
        self.send_header("Content-Encoding", "gzip")
        self.send_header("Vary", "Accept-Encoding")
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        return io.BytesIO(body)

    def list_directory(self, path):
        # Pages has no folder listings: a folder without index.html is not found.
        self.send_error(404, "File not found")
        return None

    def end_headers(self):
        self.send_header("Cache-Control", "max-age=600")
        super().end_headers()

    def handle_one_request(self):
        # A browser that moves on to the next page drops the connections it no longer needs.
        try:
            super().handle_one_request()
        except (BrokenPipeError, ConnectionResetError):
            self.close_connection = True

    def log_message(self, format, *args):  # noqa: A002 (the base class's name)
        pass


class SiteServer:
    """Serves `root` on 127.0.0.1 at a free port until `close()`."""

    def __init__(self, root: Path, node_modules: Path):
        handler = functools.partial(_Handler, directory=str(root),
                                    node_modules=node_modules.resolve())
        self._server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
        self._server.daemon_threads = True
        self.base_url = f"http://127.0.0.1:{self._server.server_port}/"
        threading.Thread(target=self._server.serve_forever, name="site-server", daemon=True).start()

    def close(self) -> None:
        self._server.shutdown()
        self._server.server_close()

#!/usr/bin/env python3
"""Serves a folder (web/dist/) on 127.0.0.1 with the cross-origin
isolation headers (Cross-Origin-Opener-Policy: same-origin,
Cross-Origin-Embedder-Policy: require-corp) unless --no-isolation, and
.wasm as application/wasm. `scripts/serve-web.sh` runs it;
`scripts/check_web_page.py` starts it itself."""

import argparse
import functools
import http.server

ISOLATION = {
    "Cross-Origin-Opener-Policy": "same-origin",
    "Cross-Origin-Embedder-Policy": "require-corp",
}


class Handler(http.server.SimpleHTTPRequestHandler):
    """Files with the isolation headers, and no caching of index.html (the
    other files' names change with their content)."""

    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map,
                      ".wasm": "application/wasm", ".js": "text/javascript"}
    isolation = True

    def end_headers(self):
        if self.isolation:
            for name, value in ISOLATION.items():
                self.send_header(name, value)
        self.send_header("Cache-Control", "no-cache")
        super().end_headers()

    def log_message(self, format, *args):
        pass


def server(directory, port, isolation):
    """An HTTP server on 127.0.0.1:port (0: any free port) for `directory`."""
    handler = functools.partial(
        type("Served", (Handler,), {"isolation": isolation}), directory=directory
    )
    return http.server.ThreadingHTTPServer(("127.0.0.1", port), handler)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--dir", required=True)
    parser.add_argument("--port", type=int, default=8049)
    parser.add_argument("--no-isolation", action="store_true")
    args = parser.parse_args()
    httpd = server(args.dir, args.port, not args.no_isolation)
    print(f"serving {args.dir} at http://127.0.0.1:{httpd.server_port}/", flush=True)
    httpd.serve_forever()


if __name__ == "__main__":
    main()

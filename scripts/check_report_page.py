#!/usr/bin/env python3
"""Opens a lab report (`workbench report`) in headless Chromium and checks
it as a reader's browser sees it: no console error or uncaught exception,
no request leaving the file (only file: and data: addresses), every image
decoded, the seven sections there. Talks to Chromium over the DevTools
protocol with the standard library alone (a minimal WebSocket client).

    scripts/check_report_page.py report.html [--chromium PATH]

Exits 0 when the page passes, 1 with the reasons when it does not, 2 when
Chromium cannot be started.
"""

import base64
import json
import os
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import time
import urllib.parse
import urllib.request

SECTIONS = 7
TIMEOUT = 60.0

CHROMIUM_FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--remote-debugging-port=0",
    "--remote-allow-origins=*",
]


class WebSocket:
    """A WebSocket client for one DevTools target: text frames, masked as
    a client must, fragmented replies joined, pings ignored."""

    def __init__(self, url):
        parts = urllib.parse.urlparse(url)
        self.sock = socket.create_connection((parts.hostname, parts.port), timeout=TIMEOUT)
        key = base64.b64encode(os.urandom(16)).decode()
        request = (
            f"GET {parts.path} HTTP/1.1\r\nHost: {parts.hostname}:{parts.port}\r\n"
            "Upgrade: websocket\r\nConnection: Upgrade\r\n"
            f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n"
        )
        self.sock.sendall(request.encode())
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = self.sock.recv(1)
            if not chunk:
                raise ConnectionError("DevTools closed the connection during the handshake")
            head += chunk
        if b" 101 " not in head.split(b"\r\n", 1)[0]:
            raise ConnectionError(f"DevTools refused the WebSocket: {head!r}")

    def _exactly(self, n):
        data = b""
        while len(data) < n:
            chunk = self.sock.recv(n - len(data))
            if not chunk:
                raise ConnectionError("DevTools closed the connection")
            data += chunk
        return data

    def send(self, text):
        payload = text.encode()
        header = bytearray([0x81])
        n = len(payload)
        if n < 126:
            header.append(0x80 | n)
        elif n < 1 << 16:
            header.append(0x80 | 126)
            header += struct.pack(">H", n)
        else:
            header.append(0x80 | 127)
            header += struct.pack(">Q", n)
        mask = os.urandom(4)
        masked = bytes(b ^ mask[i % 4] for i, b in enumerate(payload))
        self.sock.sendall(bytes(header) + mask + masked)

    def receive(self):
        message = b""
        while True:
            first, second = self._exactly(2)
            opcode = first & 0x0F
            n = second & 0x7F
            if n == 126:
                n = struct.unpack(">H", self._exactly(2))[0]
            elif n == 127:
                n = struct.unpack(">Q", self._exactly(8))[0]
            mask = self._exactly(4) if second & 0x80 else None
            payload = self._exactly(n)
            if mask:
                payload = bytes(b ^ mask[i % 4] for i, b in enumerate(payload))
            if opcode == 0x8:
                raise ConnectionError("DevTools closed the connection")
            if opcode in (0x9, 0xA):
                continue
            message += payload
            if first & 0x80:
                return message.decode()


class Page:
    """One page target: numbered commands, and the events seen meanwhile."""

    def __init__(self, ws):
        self.ws = ws
        self.next_id = 0
        self.events = []

    def command(self, method, **params):
        self.next_id += 1
        self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            message = json.loads(self.ws.receive())
            if message.get("id") == self.next_id:
                if "error" in message:
                    raise RuntimeError(f"{method}: {message['error']}")
                return message.get("result", {})
            self.events.append(message)

    def wait_for(self, method, deadline):
        for event in self.events:
            if event.get("method") == method:
                return
        while time.monotonic() < deadline:
            message = json.loads(self.ws.receive())
            self.events.append(message)
            if message.get("method") == method:
                return
        raise TimeoutError(f"no {method} within {TIMEOUT} s")


def start_chromium(chromium, profile):
    process = subprocess.Popen(
        [chromium, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", "about:blank"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    port_file = os.path.join(profile, "DevToolsActivePort")
    deadline = time.monotonic() + TIMEOUT
    while time.monotonic() < deadline:
        if process.poll() is not None:
            raise RuntimeError(f"{chromium} exited with status {process.returncode}")
        if os.path.exists(port_file):
            with open(port_file) as f:
                port = f.readline().strip()
            if port:
                return process, int(port)
        time.sleep(0.05)
    process.kill()
    raise RuntimeError(f"{chromium} did not open its DevTools port")


def page_target(port):
    deadline = time.monotonic() + TIMEOUT
    while time.monotonic() < deadline:
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=TIMEOUT) as r:
            targets = json.load(r)
        pages = [t for t in targets if t.get("type") == "page"]
        if pages:
            return pages[0]["webSocketDebuggerUrl"]
        time.sleep(0.05)
    raise RuntimeError("Chromium has no page to drive")


def problems_of(page, url):
    """Everything wrong with the loaded page, as sentences."""
    problems = []
    for event in page.events:
        method, params = event.get("method"), event.get("params", {})
        if method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
            args = " ".join(str(a.get("value", a.get("description", ""))) for a in params["args"])
            problems.append(f"console error: {args}")
        elif method == "Runtime.exceptionThrown":
            problems.append(f"uncaught exception: {params['exceptionDetails'].get('text')}")
        elif method == "Log.entryAdded" and params["entry"].get("level") == "error":
            problems.append(f"logged error: {params['entry'].get('text')} {params['entry'].get('url', '')}")
        elif method == "Network.requestWillBeSent":
            requested = params["request"]["url"]
            if not requested.startswith(("file:", "data:")):
                problems.append(f"request leaving the file: {requested}")
        elif method == "Network.loadingFailed":
            problems.append(f"failed to load: {params.get('errorText')}")
    counts = page.command(
        "Runtime.evaluate",
        expression="JSON.stringify({"
        "images: document.images.length,"
        "broken: Array.from(document.images).filter(i => !(i.complete && i.naturalWidth > 0)).length,"
        "sections: document.querySelectorAll('section').length,"
        "charts: document.querySelectorAll('svg').length})",
        returnByValue=True,
    )
    counts = json.loads(counts["result"]["value"])
    if counts["images"] == 0:
        problems.append("no image on the page")
    if counts["broken"]:
        problems.append(f"{counts['broken']} of {counts['images']} images did not load")
    if counts["sections"] != SECTIONS:
        problems.append(f"{counts['sections']} sections, not {SECTIONS}")
    if counts["charts"] == 0:
        problems.append("no chart on the page")
    return problems, counts


def main():
    args = sys.argv[1:]
    chromium = shutil.which("chromium") or "/usr/bin/chromium"
    if "--chromium" in args:
        i = args.index("--chromium")
        chromium = args[i + 1]
        del args[i : i + 2]
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    path = os.path.abspath(args[0])
    if not os.path.isfile(path):
        print(f"no report at {path}", file=sys.stderr)
        return 2
    url = "file://" + urllib.parse.quote(path)
    profile = tempfile.mkdtemp(prefix="report-check-")
    process = None
    try:
        try:
            process, port = start_chromium(chromium, profile)
            page = Page(WebSocket(page_target(port)))
        except (OSError, RuntimeError) as e:
            print(f"cannot start Chromium: {e}", file=sys.stderr)
            return 2
        for domain in ("Runtime", "Log", "Network", "Page"):
            page.command(f"{domain}.enable")
        page.command("Page.navigate", url=url)
        page.wait_for("Page.loadEventFired", time.monotonic() + TIMEOUT)
        problems, counts = problems_of(page, url)
    finally:
        if process is not None:
            process.kill()
            process.wait()
        shutil.rmtree(profile, ignore_errors=True)
    if problems:
        for p in problems:
            print(f"{path}: {p}", file=sys.stderr)
        return 1
    print(
        f"{path}: {counts['sections']} sections, {counts['images']} images loaded, "
        f"{counts['charts']} charts; no console error, no request leaving the file"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Opens the web build (web/dist/, from scripts/build-web.sh) in headless
Chromium, served as scripts/serve-web.sh serves it, and checks it: the
page cross-origin isolated with its workers up, side A's render of the
default scene finished, and no console error or uncaught exception on
the way. Prints the time from navigation to the first pass and to the
finished render (the page says how its render stands in <body data-…>).
Talks DevTools through check_report_page's standard-library client.

    scripts/check_web_page.py [--dist web/dist] [--screenshot page.png]
                              [--chromium PATH] [--timeout SECONDS]
                              [--query ?lesson=NAME --lesson NAME]
                              [--drop FILE [--error TEXT]]
                              [--save-png SCENE [--render-args ARGS]
                               [--workbench PATH]]
                              [--site-file FILE]... [--scene LABEL]

--save-png presses Save PNG (Ctrl+S) once the render is done and checks
the browser's download: named as the desktop's dialog offers (the
scene's name, .png) and equal, within the golden tests' tolerance
(scripts/png_match.py), to `workbench render SCENE` with the scene's
own settings (and --render-args, the flags a link's query gives the
page). --site-file puts a file on the served site at its path (a link's
?scene=URL or ?lesson=URL fetches it); --scene is the scene the page
must show at the end.

Exits 0 when the page passes, 1 with the reasons when it does not, 2 when
Chromium cannot be started.
"""

import argparse
import atexit
import base64
import json
import os
import shlex
import shutil
import subprocess
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_report_page as devtools  # noqa: E402
import png_match  # noqa: E402
import serve_web  # noqa: E402

# WebGL on the CPU: headless Chromium has no GPU here.
devtools.CHROMIUM_FLAGS[:] = [f for f in devtools.CHROMIUM_FLAGS if f != "--disable-gpu"] + [
    "--enable-unsafe-swiftshader",
    "--use-angle=swiftshader",
    "--window-size=1280,820",
]

STATUS = (
    "(() => { const data = document.body ? document.body.dataset : {};"
    " return JSON.stringify({isolated: self.crossOriginIsolated,"
    " render: data.render || '', passes: Number(data.passes || 0),"
    " workers: Number(data.workers || 0), lesson: data.lesson || '', scene: data.scene || '',"
    " now: performance.now()}); })()"
)


def problems_of(events):
    """Console errors and uncaught exceptions, as sentences."""
    problems = []
    for event in events:
        method, params = event.get("method"), event.get("params", {})
        if method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
            args = " ".join(str(a.get("value", a.get("description", ""))) for a in params["args"])
            problems.append(f"console error: {args}")
        elif method == "Runtime.exceptionThrown":
            details = params["exceptionDetails"]
            text = details.get("exception", {}).get("description") or details.get("text")
            problems.append(f"uncaught exception: {text}")
        elif method == "Log.entryAdded" and params["entry"].get("level") == "error":
            problems.append(f"logged error: {params['entry'].get('text')}")
    return problems


def status(page):
    result = page.command("Runtime.evaluate", expression=STATUS, returnByValue=True)
    return json.loads(result["result"]["value"])


def drop(page, path):
    """Drops the file `path` on the middle of the page, as a user would."""
    data = {"items": [], "files": [os.path.abspath(path)], "dragOperationsMask": 1}
    for kind in ("dragEnter", "dragOver", "drop"):
        page.command("Input.dispatchDragEvent", type=kind, x=640, y=400, data=data)


def press_save_png(page):
    """Ctrl+S on the page's canvas, as a user saves the render."""
    page.command("Runtime.evaluate", expression="document.querySelector('canvas').focus()")
    key = {"key": "s", "code": "KeyS", "windowsVirtualKeyCode": 83, "modifiers": 2}
    page.command("Input.dispatchKeyEvent", type="keyDown", **key)
    page.command("Input.dispatchKeyEvent", type="keyUp", **key)


def downloaded(folder, deadline):
    """The one file downloaded into `folder`, once complete, or None."""
    while time.monotonic() < deadline:
        names = [n for n in os.listdir(folder) if not n.endswith(".crdownload")]
        if names and not any(n.endswith(".crdownload") for n in os.listdir(folder)):
            return os.path.join(folder, sorted(names)[0])
        time.sleep(0.1)
    return None


def saved_png_problems(path, scene, workbench, render_args):
    """Why the page's download `path` is not the desktop's render of
    `scene` (named as its dialog offers, equal within the goldens'
    tolerance), as sentences."""
    if path is None:
        return ["Save PNG gave no download"]
    problems = []
    expected = os.path.splitext(os.path.basename(scene))[0] + ".png"
    if os.path.basename(path) != expected:
        problems.append(f"the download is named {os.path.basename(path)}, not {expected}")
    desktop = os.path.join(os.path.dirname(path), "desktop-render.png")
    run = subprocess.run(
        [workbench, "render", scene, "-o", desktop, *shlex.split(render_args)],
        capture_output=True,
        text=True,
    )
    if run.returncode != 0:
        return problems + [f"workbench render {scene} failed: {run.stderr.strip()}"]
    try:
        with open(path, "rb") as f, open(desktop, "rb") as g:
            page_png, desktop_png = png_match.read_png(f.read()), png_match.read_png(g.read())
    except (ValueError, OSError) as e:
        return problems + [f"the download is not a PNG the check reads: {e}"]
    print(f"saved PNG: {os.path.basename(path)}, {page_png[0]} x {page_png[1]}")
    why = png_match.mismatch(page_png, desktop_png)
    if why:
        problems.append(f"the page's PNG differs from `workbench render {scene}`: {why}")
    return problems


def check(url, timeout, screenshot, chromium, lesson, dropped=None, error=None, save=None,
          scene=None):
    profile = tempfile.mkdtemp(prefix="workbench-web-")
    downloads = os.path.join(profile, "downloads")
    os.mkdir(downloads)
    try:
        process, port = devtools.start_chromium(chromium, profile)
    except (OSError, RuntimeError) as e:
        shutil.rmtree(profile, ignore_errors=True)
        print(f"cannot start Chromium: {e}", file=sys.stderr)
        return 2
    try:
        page = devtools.Page(devtools.WebSocket(devtools.page_target(port)))
        for domain in ("Runtime", "Log", "Page"):
            page.command(f"{domain}.enable")
        page.command("Page.setDownloadBehavior", behavior="allow", downloadPath=downloads)
        start = status(page)["now"]
        page.command("Page.navigate", url=url)
        deadline = time.monotonic() + timeout
        first_pass = None
        while True:
            now = status(page)
            if now["passes"] >= 1 and first_pass is None:
                first_pass = now["now"]
                if dropped:
                    drop(page, dropped)
                    continue
            if now["render"] == "done" or now["render"].startswith(("failed", "error")):
                break
            if time.monotonic() > deadline:
                break
            time.sleep(0.05)
        save_problems = []
        if save and now["render"] == "done":
            press_save_png(page)
            path = downloaded(downloads, time.monotonic() + 60)
            save_problems = saved_png_problems(path, *save)
        problems = problems_of(page.events) + save_problems
        if not now["isolated"]:
            problems.append("the page is not cross-origin isolated")
        # web/index.html starts at least two (one per core, 2 to 8).
        if now["workers"] < 2:
            problems.append(f"the render ran on {now['workers']} worker(s), not at least 2")
        if error is not None:
            if not now["render"].startswith("error: ") or error not in now["render"]:
                problems.append(f"the page says {now['render']!r}, not an error with {error!r}")
        elif now["render"] != "done":
            problems.append(f"the render did not finish: {now['render'] or 'nothing said'}")
        elif dropped and now["scene"] != os.path.basename(dropped):
            problems.append(f"the page shows {now['scene'] or 'no scene'}, not the dropped file")
        if scene is not None and now["scene"] != scene:
            problems.append(f"the page shows {now['scene'] or 'no scene'}, not {scene}")
        if lesson is not None and now["lesson"] != lesson:
            problems.append(f"the Lessons panel shows {now['lesson'] or 'nothing'}, not {lesson}")
        if screenshot:
            shot = page.command("Page.captureScreenshot", format="png")
            with open(screenshot, "wb") as f:
                f.write(base64.b64decode(shot["data"]))
        print(f"workers: {now['workers']}, passes: {now['passes']}")
        if first_pass is not None:
            print(f"first pass: {(first_pass - start) / 1000:.2f} s after navigation started")
        print(f"render {now['render']}: {(now['now'] - start) / 1000:.2f} s after navigation started")
    finally:
        process.kill()
        process.wait()
        shutil.rmtree(profile, ignore_errors=True)
    for problem in problems:
        print(problem, file=sys.stderr)
    return 1 if problems else 0


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--dist", default=os.path.join(root, "web", "dist"))
    parser.add_argument("--screenshot")
    parser.add_argument("--chromium", default=shutil.which("chromium") or "chromium")
    parser.add_argument("--timeout", type=float, default=300.0)
    parser.add_argument("--query", default="", help="the page's query, as ?lesson=shadows")
    parser.add_argument("--lesson", help="the lesson the Lessons panel must show at the end")
    parser.add_argument("--drop", help="a file to drop on the page after its first pass")
    parser.add_argument("--error", help="text the page's error must hold at the end (no render)")
    parser.add_argument(
        "--save-png",
        metavar="SCENE",
        help="the scene file the page shows: save its render and compare with the desktop's",
    )
    parser.add_argument(
        "--render-args", default="", help="flags for `workbench render` with --save-png"
    )
    parser.add_argument(
        "--site-file",
        action="append",
        default=[],
        help="a file served on the site at its (relative) path, for a link to fetch",
    )
    parser.add_argument("--scene", help="the scene the page must show at the end")
    parser.add_argument(
        "--workbench",
        default=os.path.join(root, "target", "debug", "workbench"),
        help="the desktop binary that renders SCENE for --save-png",
    )
    args = parser.parse_args()
    site = args.dist
    if args.site_file:
        # The built site with the files beside it, in a folder of links.
        site = tempfile.mkdtemp(prefix="workbench-site-")
        atexit.register(shutil.rmtree, site, True)
        for name in os.listdir(args.dist):
            os.symlink(os.path.abspath(os.path.join(args.dist, name)), os.path.join(site, name))
        for path in args.site_file:
            os.makedirs(os.path.join(site, os.path.dirname(path)), exist_ok=True)
            os.symlink(os.path.abspath(path), os.path.join(site, path))
    httpd = serve_web.server(site, 0, True)
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    url = f"http://127.0.0.1:{httpd.server_port}/{args.query}"
    return check(
        url,
        args.timeout,
        args.screenshot,
        args.chromium,
        args.lesson,
        args.drop,
        args.error,
        (args.save_png, args.workbench, args.render_args) if args.save_png else None,
        args.scene,
    )


if __name__ == "__main__":
    sys.exit(main())

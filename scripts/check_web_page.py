#!/usr/bin/env python3
"""Opens the web build (web/dist/, from scripts/build-web.sh) in headless
Chromium (with --replay: its ?replay page, where every bundled lesson's
steps must pass; with --compare: its ?compare page, whose MSE, PSNR and
FLIP must equal `workbench compare`'s for the same scene and sides), served as scripts/serve-web.sh serves it, and checks it: the
page cross-origin isolated with its workers up, side A's render of the
default scene finished, and no console error or uncaught exception on
the way. Prints the time from navigation to the first pass and to the
finished render (the page says how its render stands in <body data-…>).
Talks DevTools through check_report_page's standard-library client.

    scripts/check_web_page.py [--dist web/dist] [--screenshot page.png]
                              [--chromium PATH] [--timeout SECONDS]
                              [--query ?lesson=NAME --lesson NAME]
                              [--drop FILE [--error TEXT]]
                              [--no-isolation] [--hide] [--replay]
                              [--compare SCENE --a FLAGS --b FLAGS
                               [--workbench PATH]]
                              [--save-png SCENE [--render-args ARGS]]
                              [--site-file FILE]... [--scene LABEL]
                              [--step N] [--missing PATH]
                              [--study SCENE [--param P --values V]]

--save-png presses Save PNG (Ctrl+S) once the render is done and checks
the browser's download: named as the desktop's dialog offers (the
scene's name, .png) and equal, within the golden tests' tolerance
(scripts/png_match.py), to `workbench render SCENE` with the scene's
own settings (and --render-args, the flags a link's query gives the
page). --site-file puts a file on the served site at its path (a link's
?scene=URL or ?lesson=URL fetches it); --scene is the scene the page
must show at the end, --step the lesson's step its Lessons panel must
show. --missing PATH: the query links to PATH, which the site lacks:
Chromium's own console error for that one 404 is expected, no other.
--study opens ?study=SCENE&param=P&values=V: a study run on a worker,
as the Studies window runs it, whose chart the page draws there and
downloads; the PNG must be a chart panel with its text drawn (ink in
the title's band and in the y axis's label).

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
import urllib.parse
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

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

STATUS = (
    "(() => { const data = document.body ? document.body.dataset : {};"
    " return JSON.stringify({isolated: self.crossOriginIsolated,"
    " render: data.render || '', passes: Number(data.passes || 0),"
    " workers: Number(data.workers || 0), lesson: data.lesson || '', step: data.step || '',"
    " scene: data.scene || '',"
    " renderedOn: data.renderedOn || '', tiles: data.tiles || '',"
    " rays: typeof self.workbench?.rays_traced === 'function' ? self.workbench.rays_traced() : -1,"
    " replay: data.replay || '', compare: data.compare || '', study: data.study || '',"
    " said: (document.getElementById('status') || {}).textContent || '',"
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


def without_expected_404(events, path):
    """`events` without Chromium's own log of the one 404 expected: of
    `path`, a link's missing file (the page says so itself, which the
    check reads). Any other error, or a second one, stays."""
    for i, event in enumerate(events):
        entry = event.get("params", {}).get("entry", {})
        if (event.get("method") == "Log.entryAdded" and entry.get("level") == "error"
                and "status of 404" in entry.get("text", "")
                and urllib.parse.urlsplit(entry.get("url", "")).path == "/" + path):
            return events[:i] + events[i + 1:]
    return events


def status(page):
    result = page.command("Runtime.evaluate", expression=STATUS, returnByValue=True)
    if "exceptionDetails" in result:
        raise RuntimeError(f"the page's status: {result['exceptionDetails']}")
    return json.loads(result["result"]["value"])


def drop(page, path):
    """Drops the file `path` on the middle of the page, as a user would."""
    data = {"items": [], "files": [os.path.abspath(path)], "dragOperationsMask": 1}
    for kind in ("dragEnter", "dragOver", "drop"):
        page.command("Input.dispatchDragEvent", type=kind, x=640, y=400, data=data)


HIDE = (
    "(() => { Object.defineProperty(document, 'hidden', {configurable: true, get: () => %s});"
    " document.dispatchEvent(new Event('visibilitychange')); })()"
)


def hidden_holds_the_render(page):
    """Hides the page as a hidden tab would (document.hidden and its
    event), and says what is wrong if the render goes on meanwhile (the
    rays the render itself counts: the page draws nothing while hidden);
    shows it again either way."""
    page.command("Runtime.evaluate", expression=HIDE % "true")
    try:
        # Tiles under way when it hid may still land.
        time.sleep(1.0)
        before = status(page)
        time.sleep(3.0)
        after = status(page)
    finally:
        page.command("Runtime.evaluate", expression=HIDE % "false")
    if after["rays"] != before["rays"] or after["render"] != "rendering":
        return [f"hidden, the render went on: {before['rays']} then {after['rays']} rays,"
                f" {after['render']}"]
    return []


# How far the page's metrics may be from the desktop's: the same renders
# and the same FLIP port, but the web's maths library. Measured on
# balls_medium, spp 1 against AA 4 x 4: the MSE equal to the last digit,
# the mean FLIP 1.1e-8 apart; B at AA 3 x 3 on the desktop moves them by
# 1.3 (MSE) and 3e-5 (FLIP).
FLIP_TOLERANCE = 1e-6
MSE_TOLERANCE = 1e-6


def desktop_metrics(workbench, scene, a, b):
    """`workbench compare`'s MSE, PSNR and FLIP of scenes/SCENE.p3f."""
    out_png = tempfile.mktemp(suffix=".png", prefix="compare-")
    try:
        out = subprocess.run(
            [workbench, "compare", os.path.join(ROOT, "scenes", f"{scene}.p3f"), "--a", a, "--b", b,
             "--format", "json", "-o", out_png],
            check=True, capture_output=True, text=True,
        ).stdout
    finally:
        if os.path.exists(out_png):
            os.remove(out_png)
    return json.loads(out)


def compare_problems(said, desktop):
    """What differs between the page's metrics (`said`, its JSON or an
    error) and the desktop's."""
    if not said:
        return ["the page's comparison did not finish"]
    if said.startswith("error"):
        return [f"the page's comparison failed: {said}"]
    page = json.loads(said)
    print(f"page    MSE {page['mse']:.9f}, FLIP {page['flip']:.9f}")
    print(f"desktop MSE {desktop['mse']:.9f}, FLIP {desktop['flip']:.9f}")
    problems = []
    if abs(page["flip"] - desktop["flip"]) > FLIP_TOLERANCE:
        problems.append(f"FLIP {page['flip']} on the page, {desktop['flip']} on the desktop")
    if abs(page["mse"] - desktop["mse"]) > MSE_TOLERANCE * max(1.0, desktop["mse"]):
        problems.append(f"MSE {page['mse']} on the page, {desktop['mse']} on the desktop")
    return problems


def render_problems(now, isolated, error, dropped):
    """What is wrong with the page's render as it stands in `now`."""
    problems = []
    if isolated:
        if not now["isolated"]:
            problems.append("the page is not cross-origin isolated")
        # web/index.html starts at least two (one per core, 2 to 8).
        if now["workers"] < 2:
            problems.append(f"the render ran on {now['workers']} worker(s), not at least 2")
        # A render of a few tiles (a lesson's 64 x 48: 4 in one pass) may
        # leave a worker idle; the showcase's thousands may not.
        tiles = [int(t) for t in now["tiles"].split(",") if t.strip()]
        enough = sum(tiles) >= 100
        if now["render"] == "done" and enough and (len(tiles) != now["workers"] or min(tiles) < 1):
            problems.append(f"not every worker rendered a tile: {now['tiles'] or 'none'}"
                            f" on {now['workers']} worker(s)")
    else:
        if now["isolated"]:
            problems.append("the page is cross-origin isolated, served without the headers")
        if now["workers"] != 0:
            problems.append(f"the page started {now['workers']} worker(s) without isolation")
        if "not cross-origin isolated" not in now["renderedOn"]:
            problems.append(f"the page says it renders on {now['renderedOn']!r}, not why")
    if error is not None:
        if not now["render"].startswith("error: ") or error not in now["render"]:
            problems.append(f"the page says {now['render']!r}, not an error with {error!r}")
    elif now["render"] != "done":
        problems.append(f"the render did not finish: {now['render'] or 'nothing said'}")
    elif dropped and now["scene"] != os.path.basename(dropped):
        problems.append(f"the page shows {now['scene'] or 'no scene'}, not the dropped file")
    return problems



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


def study_chart_problems(path, expected):
    """Why the page's download `path` is not a study's chart named
    `expected` with its text drawn, as sentences."""
    if path is None:
        return ["the study gave no chart download"]
    problems = []
    if os.path.basename(path) != expected:
        problems.append(f"the chart is named {os.path.basename(path)}, not {expected}")
    try:
        with open(path, "rb") as f:
            width, height, rows = png_match.read_png(f.read())
    except (ValueError, OSError) as e:
        return problems + [f"the chart is not a PNG the check reads: {e}"]
    # study_plot::PANEL; the title alone is in the top band, the y axis's
    # label (turned) alone in the left band.
    if (width, height) != (800, 500):
        problems.append(f"the chart is {width} x {height}, not one 800 x 500 panel")
    title, label = chart_ink(rows, range(0, 40), range(width)), chart_ink(rows, range(height), range(0, 28))
    print(f"study chart: {os.path.basename(path)}, {width} x {height}, "
          f"ink of its title {title} pixels, of its y axis's label {label}")
    if title < 200 or label < 200:
        problems.append("the chart's title or axis label is not drawn: its text is missing")
    return problems


def chart_ink(rows, ys, xs):
    """How many pixels in rows `ys`, columns `xs` are dark (text)."""
    return sum(
        1 for y in ys if y < len(rows) for x in xs
        if 3 * x + 2 < len(rows[y]) and max(rows[y][3 * x : 3 * x + 3]) < 128
    )


def check(url, timeout, screenshot, chromium, lesson, dropped=None, error=None, isolated=True,
          hide=False, replay=False, desktop=None, save=None, scene=None, step=None,
          missing=None, study=None):
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
        problems = []
        while True:
            now = status(page)
            if now["passes"] >= 1 and first_pass is None:
                first_pass = now["now"]
                if dropped:
                    drop(page, dropped)
                    continue
                if hide:
                    problems += hidden_holds_the_render(page)
                    continue
            if (replay and now["replay"]) or (desktop and now["compare"]) or (study and now["study"]):
                break
            # A worker that panics says so only on the console.
            if study and problems_of(page.events):
                break
            if now["render"] == "done" or now["render"].startswith(("failed", "error", "panic")):
                break
            if time.monotonic() > deadline:
                break
            time.sleep(0.05)
        save_problems = []
        if save and now["render"] == "done":
            press_save_png(page)
            path = downloaded(downloads, time.monotonic() + 60)
            save_problems = saved_png_problems(path, *save)
        events = without_expected_404(page.events, missing) if missing else page.events
        problems = problems_of(events) + problems + save_problems
        if study:
            print(now["said"])
            if not now["study"].startswith("drawn"):
                problems.append(f"the study's chart: {now['study'] or 'not drawn in time'}")
            else:
                path = downloaded(downloads, time.monotonic() + 60)
                problems += study_chart_problems(path, study)
        elif desktop:
            print(now["said"])
            problems += compare_problems(now["compare"], desktop)
        elif replay:
            print(now["said"])
            if now["replay"] != "passed":
                problems.append(f"the lessons' replay {now['replay'] or 'did not finish'}")
        else:
            problems += render_problems(now, isolated, error, dropped)
        if scene is not None and now["scene"] != scene:
            problems.append(f"the page shows {now['scene'] or 'no scene'}, not {scene}")
        if lesson is not None and now["lesson"] != lesson:
            problems.append(f"the Lessons panel shows {now['lesson'] or 'nothing'}, not {lesson}")
        if step is not None and now["step"] != str(step):
            problems.append(f"the Lessons panel shows step {now['step'] or 'none'}, not {step}")
        if screenshot:
            shot = page.command("Page.captureScreenshot", format="png")
            with open(screenshot, "wb") as f:
                f.write(base64.b64decode(shot["data"]))
        if replay or desktop or study:
            print(f"{'replay' if replay else 'study' if study else 'comparison'} done: {(now['now'] - start) / 1000:.2f} s after navigation started")
        else:
            print(f"workers: {now['workers']}, passes: {now['passes']}, on: {now['renderedOn']}")
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
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--dist", default=os.path.join(ROOT, "web", "dist"))
    parser.add_argument("--screenshot")
    parser.add_argument("--chromium", default=shutil.which("chromium") or "chromium")
    parser.add_argument("--timeout", type=float, default=300.0)
    parser.add_argument("--query", default="", help="the page's query, as ?lesson=shadows")
    parser.add_argument("--lesson", help="the lesson the Lessons panel must show at the end")
    parser.add_argument("--drop", help="a file to drop on the page after its first pass")
    parser.add_argument("--error", help="text the page's error must hold at the end (no render)")
    parser.add_argument("--no-isolation", action="store_true",
                        help="serve without the isolation headers: the page renders without workers")
    parser.add_argument("--replay", action="store_true",
                        help="open ?replay: every bundled lesson's steps must pass in the browser")
    parser.add_argument("--compare", metavar="SCENE",
                        help="open ?compare=SCENE: its metrics must equal workbench compare's")
    parser.add_argument("--a", default="", help="with --compare: side A's render flags")
    parser.add_argument("--b", default="", help="with --compare: side B's render flags")
    parser.add_argument("--workbench", default=os.path.join(ROOT, "target", "debug", "workbench"),
                        help="the desktop's binary, for --compare and --save-png")
    parser.add_argument("--hide", action="store_true",
                        help="after the first pass, hide the page for 4 s: the render must hold")
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
    parser.add_argument("--step", type=int,
                        help="the lesson's step (from 1) the Lessons panel must show at the end")
    parser.add_argument("--missing", metavar="PATH",
                        help="a file the site lacks, which the query links to: Chromium's"
                             " one console error for its 404 is expected (--error: the page's)")
    parser.add_argument("--study", metavar="SCENE",
                        help="open ?study=SCENE: a study's chart must be drawn and downloaded")
    parser.add_argument("--param", default="depth", help="with --study: the parameter studied")
    parser.add_argument("--values", default="1..3", help="with --study: its values")
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
            # build-web.sh already puts scenes/ beside the page.
            if not os.path.exists(os.path.join(site, path)):
                os.symlink(os.path.abspath(path), os.path.join(site, path))
    httpd = serve_web.server(site, 0, not args.no_isolation)
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    query = "?replay" if args.replay else args.query
    desktop = None
    if args.compare:
        quote = urllib.parse.quote
        query = f"?compare={quote(args.compare)}&a={quote(args.a)}&b={quote(args.b)}"
        desktop = desktop_metrics(args.workbench, args.compare, args.a, args.b)
    study = None
    if args.study:
        quote = urllib.parse.quote
        query = f"?study={quote(args.study)}&param={quote(args.param)}&values={quote(args.values)}"
        study = f"study-{args.param}-{args.study}.png"
    url = f"http://127.0.0.1:{httpd.server_port}/{query}"
    return check(
        url, args.timeout, args.screenshot, args.chromium, args.lesson, args.drop, args.error,
        not args.no_isolation, args.hide, args.replay, desktop,
        (args.save_png, args.workbench, args.render_args) if args.save_png else None,
        args.scene, args.step, args.missing, study,
    )


if __name__ == "__main__":
    sys.exit(main())

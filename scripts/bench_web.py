#!/usr/bin/env python3
"""The web page's speed against the desktop's: for each scene, rounds of
`workbench bench SCENE --structures bvh --threads 1 --format json` and the
page's `?bench=SCENE&workers=N` (the same frame: workbench bench's
settings, BVH) on 1 and on 2 workers, alternated, each page in a fresh
headless Chromium, and the desktop's on 2 threads too. Prints each
round's rays/s, then the medians of the pairs' ratios: web 1 worker /
desktop 1 thread, web 2 workers / web 1 worker, and desktop 2 threads /
1 thread: what the machine itself gives a second thread, the ceiling of
the web's. The page times its runs after untimed warm-up frames (its
`warmup`, default 10), as the browser's optimising compiler catches up.
Needs web/dist/ (scripts/build-web.sh) and the workbench binary.

    scripts/bench_web.py [--workbench target/release/workbench]
                         [--rounds 3] [--runs 15] SCENE...

A SCENE is a name in scenes/ (balls_medium, mount_high).
"""

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_web_page  # noqa: E402  (sets Chromium's WebGL flags)
import check_report_page as devtools  # noqa: E402
import serve_web  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BENCH = "(() => JSON.stringify({bench: document.body ? (document.body.dataset.bench || '') : '',"
BENCH += " render: document.body ? (document.body.dataset.render || '') : ''}))()"


def native(workbench, scene, runs, threads=1):
    """Rays per second of the desktop's frame on `threads` threads."""
    out = subprocess.run(
        [workbench, "bench", os.path.join(ROOT, "scenes", f"{scene}.p3f"), "--structures", "bvh",
         "--threads", str(threads), "--runs", str(runs), "--format", "json"],
        check=True, capture_output=True, text=True,
    ).stdout
    return json.loads(out)[0]["rays_per_second"]


def web(base, scene, runs, workers, chromium, timeout=600):
    """Rays per second of the page's frame on `workers` workers."""
    profile = tempfile.mkdtemp(prefix="workbench-bench-")
    process, port = devtools.start_chromium(chromium, profile)
    try:
        page = devtools.Page(devtools.WebSocket(devtools.page_target(port)))
        page.command("Runtime.enable")
        page.command("Page.navigate", url=f"{base}/?bench={scene}&workers={workers}&runs={runs}")
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            result = page.command("Runtime.evaluate", expression=BENCH, returnByValue=True)
            now = json.loads(result["result"]["value"])
            if now["render"].startswith("error"):
                raise RuntimeError(f"the page: {now['render']}")
            if now["bench"].startswith("error"):
                raise RuntimeError(f"the page's benchmark: {now['bench']}")
            if now["bench"]:
                return float(now["bench"])
            time.sleep(0.2)
        raise RuntimeError(f"no benchmark result in {timeout} s")
    finally:
        process.kill()
        process.wait()
        shutil.rmtree(profile, ignore_errors=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scenes", nargs="+")
    parser.add_argument("--workbench", default=os.path.join(ROOT, "target", "release", "workbench"))
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--runs", type=int, default=15)
    parser.add_argument("--dist", default=os.path.join(ROOT, "web", "dist"))
    parser.add_argument("--chromium", default=shutil.which("chromium") or "chromium")
    args = parser.parse_args()
    httpd = serve_web.server(args.dist, 0, True)
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    base = f"http://127.0.0.1:{httpd.server_port}"
    for scene in args.scenes:
        to_native, two_to_one, native_two = [], [], []
        for round_no in range(1, args.rounds + 1):
            desktop = native(args.workbench, scene, args.runs)
            one = web(base, scene, args.runs, 1, args.chromium)
            two = web(base, scene, args.runs, 2, args.chromium)
            desktop2 = native(args.workbench, scene, args.runs, threads=2)
            to_native.append(one / desktop)
            two_to_one.append(two / one)
            native_two.append(desktop2 / desktop)
            print(f"{scene} round {round_no}: desktop 1 thread {desktop / 1e6:.2f} M rays/s, "
                  f"web 1 worker {one / 1e6:.2f}, web 2 workers {two / 1e6:.2f}, "
                  f"desktop 2 threads {desktop2 / 1e6:.2f}", flush=True)
        print(f"{scene}: web 1 worker / desktop 1 thread, median {statistics.median(to_native):.2f} "
              f"({', '.join(f'{r:.2f}' for r in to_native)}); web 2 / 1 workers, median "
              f"{statistics.median(two_to_one):.2f} ({', '.join(f'{r:.2f}' for r in two_to_one)}); "
              f"desktop 2 / 1 threads, median {statistics.median(native_two):.2f} "
              f"({', '.join(f'{r:.2f}' for r in native_two)})")


if __name__ == "__main__":
    main()

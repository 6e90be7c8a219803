#!/usr/bin/env python3
# SPDX-FileCopyrightText: 2026 The xeno authors
# SPDX-License-Identifier: MIT
#
# Drives the browser page (examples/web/, built by scripts/web.sh) in headless Chromium through
# the DevTools protocol and checks what a visitor would see (docs/web.md, "Test"):
#   1. the page loads with no console error and no uncaught exception (checked again at the end);
#   2. the canvas is not blank (a share of its pixels differ from the background);
#   3. stepping moves the bodies (two captures of the rain, 30 steps apart, differ);
#   4. switching the scenario works (the picker's change event loads the column: 10 bodies);
#   5. picking moves the picked body (mouse events: a press at the canvas centre grabs a box of
#      the column, a drag of 120 px up and right pulls it at least 0.5 m, the release lets go);
#   6. float | double | both: "both" draws two worlds and reports their difference;
#   7. speed: the 210-box pyramid's ms/step in WebAssembly beside the native build of the same
#      code (--native), printed; within 2x of native is the goal, reported as met or missed.
# Writes a screenshot of the page (--screenshot). Exit status 0 when every check passes.
# Needs only Debian packages: chromium and python3-websocket (scripts/setup.sh web).
import argparse
import base64
import functools
import http.server
import json
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request

import websocket


class Page:
    """One Chromium tab over the DevTools protocol: commands, and the errors it reported."""

    def __init__(self, ws_url):
        self.ws = websocket.create_connection(ws_url, timeout=120, suppress_origin=True)
        self.next_id = 0
        self.errors = []

    def send(self, method, **params):
        self.next_id += 1
        self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            message = json.loads(self.ws.recv())
            if message.get("id") == self.next_id:
                if "error" in message:
                    raise RuntimeError(f"{method}: {message['error']}")
                return message.get("result", {})
            self.note(message)

    def note(self, event):
        method, params = event.get("method"), event.get("params", {})
        if method == "Runtime.exceptionThrown":
            self.errors.append("exception: " + params["exceptionDetails"].get("text", "") + " " +
                               json.dumps(params["exceptionDetails"].get("exception", {}).get("description", "")))
        elif method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
            self.errors.append("console.error: " + " ".join(str(a.get("value", a.get("description", ""))) for a in params["args"]))
        elif method == "Log.entryAdded" and params["entry"].get("level") == "error":
            self.errors.append("log: " + params["entry"].get("text", ""))

    def eval(self, expression):
        result = self.send("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in result:
            raise RuntimeError(f"{expression}: {result['exceptionDetails']}")
        return result["result"].get("value")

    def wait_for(self, expression, seconds):
        end = time.time() + seconds
        while time.time() < end:
            if self.eval(expression):
                return True
            time.sleep(0.2)
        return False


# Pixel captures of the WebGL canvas, kept in the page (preserveDrawingBuffer is on).
CAPTURE = """(name => { const c = document.getElementById('view'); const gl = c.getContext('webgl');
  const px = new Uint8Array(c.width * c.height * 4); gl.readPixels(0, 0, c.width, c.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
  window.__shots = window.__shots || {}; window.__shots[name] = px; return c.width * c.height; })"""
NOT_BACKGROUND = """(name => { const px = window.__shots[name]; let n = 0;
  for (let i = 0; i < px.length; i += 4)
    if (Math.abs(px[i] - 41) + Math.abs(px[i + 1] - 46) + Math.abs(px[i + 2] - 56) > 24) ++n;
  return n / (px.length / 4); })"""
DIFFERENT = """((a, b) => { const x = window.__shots[a], y = window.__shots[b]; let n = 0;
  for (let i = 0; i < x.length; i += 4)
    if (Math.abs(x[i] - y[i]) + Math.abs(x[i + 1] - y[i + 1]) + Math.abs(x[i + 2] - y[i + 2]) > 24) ++n;
  return n / (x.length / 4); })"""


def serve(directory):
    class Quiet(http.server.SimpleHTTPRequestHandler):
        extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map, ".wasm": "application/wasm"}

        def log_message(self, *args):
            pass

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=directory))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server


def launch_chromium(profile):
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if not browser:
        sys.exit("test_page: chromium not found (scripts/setup.sh web installs it)")
    args = [browser, "--headless=new", "--no-sandbox", "--no-first-run", "--no-default-browser-check",
            "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist",
            "--window-size=1280,860", "--remote-debugging-port=0", "--remote-allow-origins=*",
            f"--user-data-dir={profile}", "about:blank"]
    process = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    port_file = os.path.join(profile, "DevToolsActivePort")
    for _ in range(300):
        if os.path.exists(port_file) and open(port_file).read().strip():
            break
        time.sleep(0.1)
    else:
        process.kill()
        sys.exit("test_page: chromium did not open its DevTools port")
    port = open(port_file).read().split()[0]
    for _ in range(100):
        targets = json.load(urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list"))
        pages = [t for t in targets if t.get("type") == "page"]
        if pages:
            return process, pages[0]["webSocketDebuggerUrl"]
        time.sleep(0.1)
    process.kill()
    sys.exit("test_page: chromium opened no page")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--dir", required=True, help="the built page (index.html, page.js, xeno_web.js/.wasm)")
    parser.add_argument("--native", help="native_bench, for the speed comparison")
    parser.add_argument("--screenshot", help="where to write a PNG of the page")
    args = parser.parse_args()

    server = serve(args.dir)
    profile = tempfile.mkdtemp(prefix="xeno-chromium-")
    process, ws_url = launch_chromium(profile)
    failures = []

    def check(ok, what):
        print(("  ok    " if ok else "  FAIL  ") + what, flush=True)
        if not ok:
            failures.append(what)

    try:
        page = Page(ws_url)
        for domain in ("Runtime", "Log", "Page"):
            page.send(domain + ".enable")
        url = f"http://127.0.0.1:{server.server_address[1]}/index.html?scene=pyramid&paused"
        page.send("Page.navigate", url=url)
        loaded = page.wait_for("typeof xenoPage !== 'undefined' && xenoPage.ready", 120)
        check(loaded, "the page loads and the WebAssembly module starts")
        if not loaded:
            raise RuntimeError("the page did not start: " + "; ".join(page.errors))
        check(not page.errors, "no console errors or exceptions while loading" + (": " + "; ".join(page.errors) if page.errors else ""))
        check(page.eval("document.getElementById('scene').options.length") == page.eval("Module._xw_scene_count()"),
              "the picker lists every scenario")

        page.eval(f"({CAPTURE})('pyramid')")
        drawn = page.eval(f"({NOT_BACKGROUND})('pyramid')")
        check(drawn > 0.05, f"the canvas is not blank ({100 * drawn:.1f} % of its pixels drawn)")

        page.eval("xenoPage.load(xenoPage.sceneIndex('rain'), 1)")
        page.eval(f"({CAPTURE})('rain0')")
        page.eval("for (let i = 0; i < 30; ++i) xenoPage.stepOnce()")
        page.eval(f"({CAPTURE})('rain30')")
        moved = page.eval(f"({DIFFERENT})('rain0', 'rain30')")
        check(moved > 0.005, f"stepping moves the bodies ({100 * moved:.1f} % of the pixels changed in 30 steps)")

        page.eval("const s = document.getElementById('scene'); s.value = String(xenoPage.sceneIndex('column'));"
                  "s.dispatchEvent(new Event('change'))")
        column = page.eval("[xenoPage.state.scene === xenoPage.sceneIndex('column'), Module._xw_stat(1, 0)]")
        check(column == [True, 10], f"switching the scenario loads it (column: {column[1]} bodies)")

        # The mouse, as a visitor uses it: press on the column at the canvas centre, drag 120 px up
        # and right, hold while the world steps, let go.
        page.eval("for (let i = 0; i < 30; ++i) xenoPage.stepOnce()")
        x, y = page.eval("(() => { const r = document.getElementById('view').getBoundingClientRect();"
                         " return [r.left + r.width / 2, r.top + r.height / 2]; })()")
        mouse = functools.partial(page.send, "Input.dispatchMouseEvent", button="left")
        mouse(type="mousePressed", x=x, y=y, clickCount=1)
        body = page.eval("Module._xw_grabbed_body()")
        position = f"[0, 1, 2].map(k => Module._xw_body_position(1, {body}, k))"
        before = page.eval(position)
        mouse(type="mouseMoved", x=x + 120, y=y - 120, buttons=1)
        page.eval("for (let i = 0; i < 60; ++i) xenoPage.stepOnce()")
        mouse(type="mouseReleased", x=x + 120, y=y - 120, clickCount=1)
        after = page.eval(position)
        moved = sum((a - b) ** 2 for a, b in zip(after, before)) ** 0.5
        check(body >= 0 and moved > 0.5 and page.eval("Module._xw_grabbed_body()") == -1,
              f"picking with the mouse moves the picked body and lets go (body {body} moved {moved:.2f} m)")

        page.eval("xenoPage.load(xenoPage.sceneIndex('dominoes'), 2)")
        page.eval("for (let i = 0; i < 120; ++i) xenoPage.stepOnce()")
        both = page.eval("[Module._xw_stat(0, 0), Module._xw_stat(1, 0), Module._xw_max_difference()]")
        check(both[0] == both[1] == 24 and 0 <= both[2] < 1,
              f"both precisions side by side (24 dominoes each: {both[0]}, {both[1]}; largest difference {both[2]:.2e} m)")
        if args.screenshot:
            shot = page.send("Page.captureScreenshot", format="png")
            with open(args.screenshot, "wb") as f:
                f.write(base64.b64decode(shot["data"]))
            print(f"  screenshot: {args.screenshot}")

        web = page.eval("xenoPage.benchmark()")
        line = f"pyramid (210 boxes), 100 steps, best of 3: WebAssembly float {web['float']:.2f} / double {web['double']:.2f} ms/step"
        if args.native:
            native = subprocess.run([args.native], check=True, capture_output=True, text=True).stdout.split()
            nf, nd = float(native[1]), float(native[3])
            rf, rd = web["float"] / nf, web["double"] / nd
            line += f"; native float {nf:.2f} / double {nd:.2f} ms/step; {rf:.2f}x / {rd:.2f}x native"
            line += " (goal 2x: " + ("met" if max(rf, rd) <= 2 else "missed") + ")"
        print("  speed: " + line, flush=True)
        check(not page.errors, "no console errors or exceptions at the end" + (": " + "; ".join(page.errors) if page.errors else ""))
    finally:
        process.kill()
        process.wait()
        server.shutdown()
        shutil.rmtree(profile, ignore_errors=True)
    if failures:
        print(f"test_page: {len(failures)} check(s) failed", file=sys.stderr)
        return 1
    print("test_page: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Opens a mission's report.html in headless Chromium and checks it as a reviewer sees it.

Usage: browser_page_check.py --fognav BIN --scenario FILE.yaml --out DIR
       browser_page_check.py --out DIR          (a folder a run has written already)

Runs `fognav run FILE.yaml --out DIR --quiet` when given a scenario, opens DIR/report.html in
headless Chromium through its DevTools protocol (--remote-debugging-pipe) and fails if the page
logs a console error or an exception, if an image or video did not load (naturalWidth or
videoWidth 0), or if the outcome and failure on the page differ from report.json (a folder of
`fognav perceive`, without report.json, is checked for the rest). Saves the whole page as
DIR/report_screenshot.png and chromium's own log as DIR/chromium.log. Exits 77 (ctest's
SKIP_RETURN_CODE) with the reason when chromium is not installed. Only the standard library is
used.
"""
import argparse
import base64
import json
import os
import select
import shutil
import subprocess
import sys
import tempfile
import time

SKIP = 77
TIMEOUT_S = 120


class DevTools:
    """The Chrome DevTools protocol over the pipe pair fd 3 (to chromium) and 4 (from it)."""

    def __init__(self, to_browser, from_browser):
        self.to_browser = to_browser
        self.from_browser = from_browser
        self.buffer = b""
        self.next_id = 0
        self.events = []

    def _read_message(self, deadline):
        while b"\0" not in self.buffer:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError("chromium did not answer in time")
            ready, _, _ = select.select([self.from_browser], [], [], left)
            if ready:
                chunk = os.read(self.from_browser, 1 << 16)
                if not chunk:
                    raise RuntimeError("chromium closed its DevTools pipe")
                self.buffer += chunk
        message, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(message)

    def call(self, method, params=None, session=None):
        self.next_id += 1
        request = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            request["sessionId"] = session
        os.write(self.to_browser, json.dumps(request).encode() + b"\0")
        deadline = time.monotonic() + TIMEOUT_S
        while True:
            message = self._read_message(deadline)
            if message.get("id") == self.next_id:
                if "error" in message:
                    raise RuntimeError(f"{method}: {message['error']}")
                return message.get("result", {})
            self.events.append(message)

    def wait_for(self, method):
        for event in self.events:
            if event.get("method") == method:
                return event
        deadline = time.monotonic() + TIMEOUT_S
        while True:
            message = self._read_message(deadline)
            self.events.append(message)
            if message.get("method") == method:
                return message


def find_chromium():
    for name in (os.environ.get("FOGNAV_CHROMIUM", ""), "chromium", "chromium-browser"):
        if name and shutil.which(name):
            return shutil.which(name)
    return None


def errors_of(events):
    """The console errors, exceptions and failed loads among the protocol's events."""
    errors = []
    for event in events:
        method, params = event.get("method"), event.get("params", {})
        if method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
            errors.append("console: " + " ".join(str(a.get("value", a.get("description", "")))
                                                 for a in params.get("args", [])))
        elif method == "Runtime.exceptionThrown":
            details = params.get("exceptionDetails", {})
            errors.append("exception: " + details.get("exception", {}).get(
                "description", details.get("text", "")).splitlines()[0])
        elif method == "Log.entryAdded" and params.get("entry", {}).get("level") == "error":
            entry = params["entry"]
            errors.append(f"log ({entry.get('source')}): {entry.get('text')} "
                          f"{entry.get('url', '')}")
    return errors


# what the page shows, read in the page
PAGE_STATE = """JSON.stringify({
  outcome: (document.getElementById('outcome') || {}).textContent || null,
  failure: (document.getElementById('failure') || {}).textContent || null,
  images: Array.from(document.images).map(i => ({src: i.getAttribute('src'),
                                                  complete: i.complete, width: i.naturalWidth})),
  videos: Array.from(document.querySelectorAll('video')).map(v => ({
      src: v.getAttribute('src'), width: v.videoWidth, state: v.readyState}))
})"""


def check_page(chromium, page, screenshot):
    """Returns the list of problems the page has in chromium; writes the screenshot."""
    profile = tempfile.mkdtemp(prefix="fognav_chromium_")
    to_read, to_write = os.pipe()      # we write, chromium reads on fd 3
    from_read, from_write = os.pipe()  # chromium writes on fd 4, we read

    def child_fds():
        # move the pipe ends to fds 3 and 4 without clobbering one with the other
        high_in, high_out = os.dup(to_read), os.dup(from_write)
        os.dup2(high_in, 3)
        os.dup2(high_out, 4)

    # no sandbox: the page is fognav's own file, and root (CI) or a container without user
    # namespaces keeps chromium's sandbox from starting; /dev/shm is small in containers
    command = [chromium, "--headless=new", "--remote-debugging-pipe", "--no-sandbox",
               "--disable-dev-shm-usage", "--disable-gpu", "--no-first-run",
               "--no-default-browser-check", "--hide-scrollbars", "--mute-audio",
               f"--user-data-dir={profile}", "about:blank"]
    log = open(os.path.join(os.path.dirname(screenshot), "chromium.log"), "w")
    browser = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=log, stderr=log,
                               preexec_fn=child_fds, close_fds=False)
    os.close(to_read)
    os.close(from_write)
    problems = []
    try:
        tools = DevTools(to_write, from_read)
        target = tools.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = tools.call("Target.attachToTarget",
                             {"targetId": target, "flatten": True})["sessionId"]
        for domain in ("Page", "Runtime", "Log"):
            tools.call(domain + ".enable", session=session)
        tools.call("Emulation.setDeviceMetricsOverride",
                   {"width": 1200, "height": 900, "deviceScaleFactor": 1, "mobile": False},
                   session=session)
        tools.events.clear()
        tools.call("Page.navigate", {"url": "file://" + os.path.abspath(page)}, session=session)
        tools.wait_for("Page.loadEventFired")
        state = json.loads(tools.call("Runtime.evaluate", {"expression": PAGE_STATE},
                                      session=session)["result"]["value"])
        problems += errors_of(tools.events)
        for image in state["images"]:
            if not image["complete"] or image["width"] <= 0:
                problems.append(f"image {image['src']} did not load")
        for video in state["videos"]:
            if video["width"] <= 0:
                problems.append(f"video {video['src']} did not load (readyState {video['state']})")
        # the whole page in one picture
        size = tools.call("Page.getLayoutMetrics", session=session)["cssContentSize"]
        tools.call("Emulation.setDeviceMetricsOverride",
                   {"width": 1200, "height": int(size["height"]) + 1, "deviceScaleFactor": 1,
                    "mobile": False}, session=session)
        shot = tools.call("Page.captureScreenshot", {"format": "png"}, session=session)
        with open(screenshot, "wb") as f:
            f.write(base64.b64decode(shot["data"]))
        try:
            tools.call("Browser.close")
        except RuntimeError:
            pass
        return problems, state
    finally:
        try:
            browser.wait(timeout=20)
        except subprocess.TimeoutExpired:
            browser.kill()
            browser.wait()
        os.close(to_write)
        os.close(from_read)
        log.close()
        shutil.rmtree(profile, ignore_errors=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fognav")
    parser.add_argument("--scenario")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    chromium = find_chromium()
    if not chromium:
        print("SKIPPED: chromium is not installed (Debian: apt-get install chromium)")
        return SKIP

    if args.scenario:
        run = subprocess.run([args.fognav, "run", args.scenario, "--out", args.out, "--quiet"],
                             stderr=subprocess.PIPE, text=True)
        if run.returncode not in (0, 1):
            print(f"FAIL: fognav run exited {run.returncode}: {run.stderr.strip()}")
            return 1
    page = os.path.join(args.out, "report.html")
    screenshot = os.path.join(args.out, "report_screenshot.png")
    problems, state = check_page(chromium, page, screenshot)

    # a mission's page names its outcome as report.json does (a perceive page has none)
    report_path = os.path.join(args.out, "report.json")
    if os.path.exists(report_path) or args.scenario:
        with open(report_path) as f:
            report = json.load(f)
        expected_outcome = "success" if report["success"] else "failed"
        if state["outcome"] != expected_outcome:
            problems.append(f"the page says {state['outcome']!r}, report.json "
                            f"{expected_outcome!r}")
        expected_failure = report.get("failure") or "none"
        if state["failure"] != expected_failure:
            problems.append(f"the page's failure is {state['failure']!r}, report.json's "
                            f"{expected_failure!r}")
    if not state["images"]:
        problems.append("the page shows no image")
    for problem in problems:
        print("FAIL: " + problem)
    print(f"{page}: outcome {state['outcome']}, failure {state['failure']}, "
          f"{len(state['images'])} images, {len(state['videos'])} videos; screenshot {screenshot}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

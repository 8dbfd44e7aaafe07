"""The live page in a real browser: headless Chromium (Debian's `chromium`) on a running dam break.

  test_live_browser.py DAMBREAK WORK_FOLDER [SCREENSHOT]

While the job runs, the page is loaded and left to poll; its DOM then must show a picture whose
SHA-256 (which the page computes from the bytes it shows) is that of the job's own PNG frame of
the step it claims, a step no older than the job's latest when the browser started, and the
chart drawn. After the last step (the job keeps the page up: live.linger_seconds) the page must
say that the job ended and show the last step's picture (the job runs until the test has seen
the page during the run, then is stopped). The job's page is interactive: first a
drag on the picture and a click on its reset button (through the DevTools protocol on a pipe)
must reach the job, which logs both changes. SCREENSHOT: where the screenshot of the page during
the run goes (default WORK_FOLDER/live_page.png). Exits 77 (skipped) without Chromium.
"""
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from live_job import SKIP, Checks, LiveJob  # noqa: E402

check = Checks()


def chromium():
    for name in ["chromium", "chromium-browser", "google-chrome"]:
        if shutil.which(name):
            return shutil.which(name)
    return None


def browser_args(browser, profile):
    return [browser, "--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run",
            "--disable-extensions", f"--user-data-dir={profile}", "--window-size=1120,820",
            "--hide-scrollbars"]


def browse(browser, url, profile, screenshot=None, budget_ms=6000):
    """The page's DOM after `budget_ms` of the page's own time (and a screenshot)."""
    args = browser_args(browser, profile) + [f"--virtual-time-budget={budget_ms}"]
    if screenshot:
        subprocess.run(args + [f"--screenshot={screenshot}", url], check=True, timeout=120,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    dom = subprocess.run(args + ["--dump-dom", url], check=True, timeout=120,
                         capture_output=True, text=True).stdout
    return dom


class DevTools:
    """Chromium driven through the DevTools protocol on a pipe (--remote-debugging-pipe: it
    reads commands on fd 3 and answers on fd 4, each message JSON ended by a NUL byte)."""

    def __init__(self, browser, profile):
        to_browser, self._commands = os.pipe()
        self._answers, from_browser = os.pipe()

        def pipes():  # in the child: its ends at 3 and 4, whatever numbers they had
            ends = [os.dup(to_browser), os.dup(from_browser)]
            for fd, end in zip([3, 4], ends):
                os.dup2(end, fd)
                os.set_inheritable(fd, True)

        self.process = subprocess.Popen(
            browser_args(browser, profile) + ["--remote-debugging-pipe", "about:blank"],
            preexec_fn=pipes, close_fds=False, stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL)
        os.close(to_browser)
        os.close(from_browser)
        self._next, self._buffer, self.session = 0, b"", None

    def send(self, method, **params):
        self._next += 1
        message = {"id": self._next, "method": method, "params": params}
        if self.session:
            message["sessionId"] = self.session
        os.write(self._commands, json.dumps(message).encode() + b"\0")
        while True:
            while b"\0" not in self._buffer:
                chunk = os.read(self._answers, 65536)
                if not chunk:
                    raise RuntimeError("chromium closed its DevTools pipe")
                self._buffer += chunk
            raw, self._buffer = self._buffer.split(b"\0", 1)
            answer = json.loads(raw)
            if answer.get("id") == self._next:
                if "error" in answer:
                    raise RuntimeError(f"{method}: {answer['error']}")
                return answer.get("result", {})

    def open(self, url):
        target = self.send("Target.createTarget", url=url)["targetId"]
        attached = self.send("Target.attachToTarget", targetId=target, flatten=True)
        self.session = attached["sessionId"]

    def value(self, expression):
        return self.send("Runtime.evaluate", expression=expression,
                         returnByValue=True)["result"].get("value")

    def wait(self, expression, timeout=60):
        end = time.time() + timeout
        while time.time() < end:
            if self.value(expression):
                return True
            time.sleep(0.2)
        return False

    def mouse(self, kind, x, y, buttons):
        self.send("Input.dispatchMouseEvent", type=kind, x=x, y=y, button="left",
                  buttons=buttons, clickCount=1)

    def close(self):
        self.process.kill()
        self.process.wait()


def turned(job):
    return [line for line in job.log if "camera turned from the live page" in line]


def drag_and_reset(browser, job, url, profile):
    """A drag across the picture and a click on reset, as a user makes them."""
    tools = DevTools(browser, profile)
    try:
        tools.open(url)
        ready = tools.wait("!!document.querySelector('figure.interactive img[data-step]')")
        check("interactive: the page shows the camera controls", ready and tools.value(
            "document.querySelectorAll('figure.interactive button').length") == 3)
        box = tools.value("(() => { const r = document.querySelector('figure.interactive img')"
                          ".getBoundingClientRect(); return [r.x + r.width / 2, r.y + "
                          "r.height / 2, r.width]; })()")
        x, y, width = box
        tools.mouse("mousePressed", x, y, 1)
        for i in range(1, 11):
            tools.mouse("mouseMoved", x + 0.03 * width * i, y + 2 * i, 1)
            time.sleep(0.03)
        tools.mouse("mouseReleased", x + 0.3 * width, y + 20, 0)
        accepted = tools.wait("Number(document.body.dataset.camera) >= 1")
        end = time.time() + 60
        while not turned(job) and time.time() < end:
            time.sleep(0.2)
        check("... a drag on the picture: accepted and logged by the job", accepted and turned(job),
              turned(job)[0] if turned(job) else "nothing logged")
        # The drag's last requests may reach the job a step after its first: lines logged from
        # here on may still be the drag's, and the reset is the first that says so.
        before = len(turned(job))
        tools.value("document.querySelector('figure.interactive button[data-action=reset]')"
                    ".click()")

        def resets():
            return [line for line in turned(job)[before:] if "reset" in line]
        end = time.time() + 60
        while not resets() and time.time() < end:
            time.sleep(0.2)
        check("... the reset button: logged by the job as a reset", resets(),
              resets()[0] if resets() else "; ".join(turned(job)[before:]) or "nothing logged")
    finally:
        tools.close()


def attribute(dom, element_pattern, name):
    m = re.search(element_pattern, dom)
    if not m:
        return None
    a = re.search(rf'\b{name}="([^"]*)"', m.group(0))
    return a.group(1) if a else None


def shown_picture(dom):
    img = r'<img[^>]*data-view="main"[^>]*>'
    step = attribute(dom, img, "data-step")
    return (int(step) if step else None), attribute(dom, img, "data-sha256")


def main():
    browser = chromium()
    if browser is None:
        print("SKIPPED: no chromium on PATH (Debian: apt-get install chromium; "
              "tools/scripts/setup.sh installs it)")
        return SKIP
    dambreak, work = sys.argv[1], sys.argv[2]
    screenshot = sys.argv[3] if len(sys.argv) > 3 else os.path.join(work, "live_page.png")
    shutil.rmtree(work, ignore_errors=True)
    job = LiveJob(dambreak, os.path.join(work, "job"),
                  {"enabled": "true", "port": 0, "linger_seconds": 40, "interactive": "true"},
                  steps=None, particles=6000, every=10, size=(480, 270))
    url = job.wait_url()
    print("live page:", url, flush=True)
    job.wait_state(lambda s: s["render_steps"] >= 2)
    drag_and_reset(browser, job, url, os.path.join(work, "profile-drag"))
    latest = job.wait_state(lambda s: s["render_steps"] >= 20)["step"]

    dom = browse(browser, url, os.path.join(work, "profile"), screenshot)
    step, sha = shown_picture(dom)
    rows = attribute(dom, r"<svg[^>]*id=\"chart\"[^>]*>", "data-rows")
    check("during the run: the page shows a picture and the chart",
          step is not None and sha and rows and int(rows) >= 1,
          f"step {step}, chart of {rows} steps")
    check("... of a step no older than the job's latest when the browser started",
          step is not None and step >= latest, f"step {step}, latest {latest}")
    check("... with the bytes of the job's own frame of that step",
          step is not None and sha == hashlib.sha256(job.png("main", step)).hexdigest())
    check("... and the progress", re.search(r'id="particles">[0-9,]+<', dom) is not None)
    check("... and says the job runs", 'data-ended="false"' in dom)

    job.stop()
    final = job.wait_state(lambda s: not s["running"], timeout=300)
    # One browser start, not two (no screenshot): the page is up only for the linger.
    dom = browse(browser, url, os.path.join(work, "profile"))
    step, sha = shown_picture(dom)
    check("after the last step: the page says the job ended",
          'data-ended="true"' in dom and "the job has ended" in dom)
    check("... and shows the last step's picture, byte for byte",
          step == final["step"] and sha == hashlib.sha256(job.png("main", step)).hexdigest(),
          f"step {step}, last {final['step']}")
    job.finish()
    print("screenshot:", screenshot)
    return check.verdict()


if __name__ == "__main__":
    sys.exit(main())

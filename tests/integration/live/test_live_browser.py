"""The live page in a real browser: headless Chromium (Debian's `chromium`) on a running dam break.

  test_live_browser.py DAMBREAK WORK_FOLDER [SCREENSHOT]

While the job runs, the page is loaded and left to poll; its DOM then must show a picture whose
SHA-256 (which the page computes from the bytes it shows) is that of the job's own PNG frame of
the step it claims, a step no older than the job's latest when the browser started, and the
chart drawn. After the last step (the job keeps the page up: live.linger_seconds) the page must
say that the job ended and show the last step's picture. SCREENSHOT: where the screenshot of the
page during the run goes (default WORK_FOLDER/live_page.png). Exits 77 (skipped) without
Chromium.
"""
import hashlib
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from live_job import SKIP, LiveJob  # noqa: E402

failures = []


def check(what, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + what + (f": {detail}" if detail else ""), flush=True)
    if not ok:
        failures.append(what)


def chromium():
    for name in ["chromium", "chromium-browser", "google-chrome"]:
        if shutil.which(name):
            return shutil.which(name)
    return None


def browse(browser, url, profile, screenshot=None, budget_ms=6000):
    """The page's DOM after `budget_ms` of the page's own time (and a screenshot)."""
    args = [browser, "--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run",
            "--disable-extensions", f"--user-data-dir={profile}", "--window-size=1120,820",
            f"--virtual-time-budget={budget_ms}", "--hide-scrollbars"]
    if screenshot:
        subprocess.run(args + [f"--screenshot={screenshot}", url], check=True, timeout=120,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    dom = subprocess.run(args + ["--dump-dom", url], check=True, timeout=120,
                         capture_output=True, text=True).stdout
    return dom


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
                  {"enabled": "true", "port": 0, "linger_seconds": 25}, steps=1000,
                  particles=6000, every=10, size=(480, 270))
    url = job.wait_url()
    print("live page:", url, flush=True)
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

    final = job.wait_state(lambda s: not s["running"], timeout=300)
    dom = browse(browser, url, os.path.join(work, "profile"),
                 os.path.join(work, "live_page_ended.png"))
    step, sha = shown_picture(dom)
    check("after the last step: the page says the job ended",
          'data-ended="true"' in dom and "the job has ended" in dom)
    check("... and shows the last step's picture, byte for byte",
          step == final["step"] and sha == hashlib.sha256(job.png("main", step)).hexdigest(),
          f"step {step}, last {final['step']}")
    job.finish()
    print("screenshot:", screenshot)
    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

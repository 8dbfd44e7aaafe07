"""The live page's camera controls over HTTP (`live.interactive`), on a running dam break.

  test_live_interactive.py DAMBREAK WORK_FOLDER

Runs the dam break twice at once with the same config: without the live page (the reference)
and with it, interactive. POST /camera must be refused without the token or with a wrong one,
in the query, with another method, with bodies that are not one valid request (each with its
status and a message that says why); then an orbit, a pan and a zoom, and a reset, each logged
by the job at its next render step. The pictures must be the reference's, byte for byte,
before the first change and after the reset, and differ between; the solver's steps (step,
time, particles, the cells they fill) must be the reference's on every step: the page turns the
camera, never the solver. Both jobs run until stopped (the solver's --stop-file).
"""
import os
import re
import shutil
import socket
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from live_job import Checks, LiveJob  # noqa: E402

PARTICLES, EVERY = 4000, 5
FORM = "application/x-www-form-urlencoded"
check = Checks()


def post(job, body, token=None, path="/camera", content_type=FORM, method="POST"):
    headers = {"Content-Type": content_type} if content_type else {}
    if token is not False:
        headers["Authorization"] = "Bearer " + (token or job.token)
    status, headers, answer = job.request(path, headers, method=method, body=body)
    return status, headers, answer.decode()


def refusals(job):
    orbit = "view=main&action=orbit&d_phi=10&d_theta=0"
    status, headers, _ = post(job, orbit, token=False)
    check("no token -> 401", status == 401 and headers.get("WWW-Authenticate") == "Bearer",
          str(status))
    status, _, _ = post(job, orbit, token="0" * len(job.token))
    check("a wrong token of the same length -> 401", status == 401, str(status))
    status, _, _ = post(job, orbit, token=False, path="/camera?token=" + job.token)
    check("the token in the query -> 401", status == 401, str(status))
    status, headers, _ = job.request("/camera", {"Authorization": "Bearer " + job.token})
    check("GET /camera -> 405, Allow: POST", status == 405 and headers.get("Allow") == "POST",
          str(status))
    for what, body, expected, says in [
            ("an unknown view", "view=top&action=reset", 400, 'no view "top" (the views: main)'),
            ("an unknown action", "view=main&action=spin", 400, "action must be orbit, pan"),
            ("a missing number", "view=main&action=orbit&d_phi=10", 400, "d_theta is missing"),
            ("a field of another action", "view=main&action=zoom&factor=2&dx=1", 400,
             "unknown field dx for zoom"),
            ("NaN", "view=main&action=zoom&factor=nan", 400, "factor must be a finite number"),
            ("infinity", "view=main&action=orbit&d_phi=-inf&d_theta=0", 400,
             "d_phi must be a finite number"),
            ("out of range", "view=main&action=zoom&factor=1000", 400,
             "factor = 1000 is outside [0.1, 10]"),
            ("a field twice", "view=main&view=main&action=reset", 400, "field view given twice"),
            ("a body over 1 KiB", "view=main&action=reset&" + "x" * 2000, 413, "at most 1024"),
            ("another content type", '{"view":"main","action":"reset"}', 415,
             "expected application/x-www-form-urlencoded")]:
        content_type = "application/json" if body.startswith("{") else FORM
        status, _, answer = post(job, body, content_type=content_type)
        check(f"{what} -> {expected}", status == expected and says in answer,
              f"{status} {answer.strip()}")
    s = socket.create_connection((job.host, job.port), timeout=10)
    s.sendall(f"POST /camera HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer {job.token}\r\n"
              f"Content-Type: {FORM}\r\nTransfer-Encoding: chunked\r\n\r\n"
              "16\r\nview=main&action=reset\r\n0\r\n\r\n".encode())
    reply = s.recv(4096)
    s.close()
    check("a body of no stated length -> 411", reply.split(b" ")[1:2] == [b"411"],
          reply.split(b"\r\n")[0].decode())


def applied(job, count, timeout=60):
    """The job's count-th log line of a camera change, once it is there."""
    end = time.time() + timeout
    while time.time() < end:
        lines = [l for l in job.log if "camera turned from the live page" in l]
        if len(lines) >= count:
            return lines[count - 1]
        time.sleep(0.1)
    return None


def turns(job):
    check("the state says the page is interactive", job.state().get("interactive") is True)
    for count, bodies in enumerate([
            ["view=main&action=orbit&d_phi=60&d_theta=25"],
            ["view=main&action=pan&dx=0.1&dy=-0.05", "view=main&action=zoom&factor=1.5"],
            ["view=main&action=reset"]], start=1):
        statuses = [post(job, b)[0] for b in bodies]
        line = applied(job, count)
        check(f"{' + '.join(b.split('action=')[1].split('&')[0] for b in bodies)}: 202, then "
              "logged at the next render step", statuses == [202] * len(bodies) and line,
              f"{statuses} {line}")
        # Two render steps at least between changes, so that each shows in the pictures.
        step = job.state()["step"]
        job.wait_state(lambda s, step=step: s["step"] >= step + 2 * EVERY)


def solver_steps(job):
    keys = ["particles", "owned", "boundary", "cells", "cells_inner_empty", "cells_inner_full"]
    return [(r["step"], r["time"], *[r["counters"][k] for k in keys]) for r in job.stats()]


def frames(job):
    folder = os.path.join(job.folder, "frames")
    return {int(re.search(r"(\d+)\.png$", f).group(1)): os.path.join(folder, f)
            for f in os.listdir(folder)}


def pictures(job, reference):
    mine, theirs = frames(job), frames(reference)
    same = []
    for step in sorted(set(mine) & set(theirs)):
        with open(mine[step], "rb") as a, open(theirs[step], "rb") as b:
            same.append((step, a.read() == b.read()))
    # same before, different while turned, same again after the reset
    runs = [same[0]]
    for s in same[1:]:
        if s[1] != runs[-1][1]:
            runs.append(s)
    check("the pictures: the reference's before the first change, turned, the reference's "
          "again after the reset", [r[1] for r in runs] == [True, False, True],
          "from step " + ", ".join(f"{r[0]}: {'same' if r[1] else 'turned'}" for r in runs))


def main():
    dambreak, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    # Both run until stopped: the job once the changes are made, the reference once it has
    # passed the job's last step.
    reference = LiveJob(dambreak, os.path.join(work, "reference"), None, None, PARTICLES, EVERY)
    job = LiveJob(dambreak, os.path.join(work, "interactive"),
                  {"enabled": "true", "port": 0, "interactive": "true"}, None, PARTICLES, EVERY)
    print("live page:", job.wait_url(), flush=True)
    job.wait_state(lambda s: s["views"][0]["step"] >= 2 * EVERY)
    refusals(job)
    check("no camera change logged by the refused requests", applied(job, 1, timeout=1) is None)
    turns(job)
    check("the job still running after the reset", job.process.poll() is None)
    job.stop()
    job.finish()
    last = job.stats()[-1]["step"]
    end = time.time() + 300
    while max([r["step"] for r in reference.stats()], default=0) < last and time.time() < end:
        time.sleep(0.2)
    reference.stop()
    reference.finish()
    print("\n".join(l for l in job.log if "camera turned" in l))
    pictures(job, reference)
    # Every render step of the job up to its last (stopped: at a step the reference need not
    # render) the reference's.
    mine = [s for s in solver_steps(job) if s[0] < last]
    theirs = [s for s in solver_steps(reference) if s[0] < last]
    check("the solver's steps: the reference's, every one", mine == theirs and len(mine) > 10,
          f"{len(mine)} steps, {len(theirs)} in the reference, up to step {last}")
    return check.verdict()


if __name__ == "__main__":
    sys.exit(main())

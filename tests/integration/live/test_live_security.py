"""The live page over HTTP, as a hostile client sees it (insitu/live/live_server.h).

  test_live_security.py DAMBREAK WORK_FOLDER [--runs N] [--same]

Runs the dam break twice at once with the same config: without the live page (the reference)
and with it, while this script sends to the latter, one after another: no token, wrong tokens,
the token in the wrong place, path traversals, other methods, a camera request (the page is not
interactive), oversized requests, 300 requests at once (over the rate limit), 200 simultaneous
connections, a client that sends a byte a second and one that reads a byte a second. Each must
be refused or bounded with its status, and the job's in-situ time per render step (the 20th
percentile over the run, from its stats lines) at most TOLERANCE (VOXSPAN_LIVE_TOLERANCE, default
0.25; the goal, 0.05, is printed) above the reference's. Both jobs run side by side so that the
machine's other work weighs on both alike. Each run prints the CPU time the page's threads (those
at LiveFeed::kThreadNice) used over the attacks: the most the page could take from the solver.

The benchmark of that goal (docs/benchmarks.md, "The live page"): `--runs N` repeats the pair N
times, the job with the page started first on every other run, and checks the median change;
`--same` runs both without the page for as long as the attacks take (nothing attacked): what two
identical jobs differ by on this machine.
"""
import os
import re
import shutil
import socket
import statistics
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from live_job import Checks, LiveJob  # noqa: E402

# The goal is 5 %, but two identical jobs without the page, side by side on the shared 2-core
# machine where this was written, differed by -16.6 to +12.4 % in eight runs (`--same`); with the
# page, attacked, by -25.0 to +49.9 % (medians of eight: -3.7 to +5.8 %); on CI once -28.9 %.
# So the test fails only where the job with the page is over 25 % slower (a page that held the
# solver up would show far more); the page's own CPU time, printed, is what bounds it.
GOAL = 0.05
TOLERANCE = float(os.environ.get("VOXSPAN_LIVE_TOLERANCE", "0.25"))
PARTICLES, EVERY = 4000, 5
FORM = "application/x-www-form-urlencoded"
check = Checks()


def raw(job, data, timeout=15):
    """Sends `data` on a fresh connection; (status or None, seconds until the server closed)."""
    start = time.time()
    s = socket.create_connection((job.host, job.port), timeout=timeout)
    try:
        s.sendall(data)
    except OSError:
        pass
    reply = b""
    try:
        while True:
            chunk = s.recv(65536)
            if not chunk:
                break
            reply += chunk
    except OSError:
        pass
    s.close()
    status = int(reply.split(b" ")[1]) if reply.startswith(b"HTTP/") else None
    return status, time.time() - start


def token_rules(job):
    t = job.token
    right = {"Authorization": "Bearer " + t}
    check("the page with the token in its URL", job.request("/?token=" + t)[0] == 200)
    check("the state with the token in the header", job.request("/state.json", right)[0] == 200)
    status, headers, body = job.request("/view/main.png", right)
    check("a picture with the token", status == 200 and body[:8] == b"\x89PNG\r\n\x1a\n")
    check("no-store, nosniff, no framing", headers.get("Cache-Control") == "no-store" and
          headers.get("X-Content-Type-Options") == "nosniff" and
          headers.get("X-Frame-Options") == "DENY")
    wrong = "0" * len(t)
    for what, path, headers in [
            ("no token: the page", "/", {}),
            ("no token: the state", "/state.json", {}),
            ("no token: a picture", "/view/main.png", {}),
            ("a wrong token of the same length", "/state.json", {"Authorization": "Bearer " + wrong}),
            ("a wrong token in the page's URL", "/?token=" + wrong, {}),
            ("the token's first half", "/state.json", {"Authorization": "Bearer " + t[:len(t) // 2]}),
            ("the token with more after it", "/state.json", {"Authorization": "Bearer " + t + "0"}),
            ("the token in the query of the state", "/state.json?token=" + t, {}),
            ("the token in the query of a picture", "/view/main.png?token=" + t, {}),
            ("the token in the path", f"/{t}/state.json", {}),
            ("the token in a cookie", "/state.json", {"Cookie": "token=" + t}),
            ("the token without `Bearer`", "/state.json", {"Authorization": t}),
            ("the token in another header", "/state.json", {"X-Token": t})]:
        status, headers, _ = job.request(path, headers)
        check(what + " -> 401", status == 401 and headers.get("WWW-Authenticate") == "Bearer",
              str(status))


def fixed_paths(job):
    right = {"Authorization": "Bearer " + job.token}
    for path in ["/../../../../etc/passwd", "/view/../../../../etc/passwd",
                 "/view/..%2f..%2f..%2fetc%2fpasswd", "/%2e%2e/%2e%2e/etc/passwd",
                 "/view/main.png/../../state.json", "//etc/passwd", "/view/", "/view/main",
                 "/state.json/", "/index.html", "/live_page.html", "/view/..%00.png"]:
        status, _, body = job.request(path, right)
        check(f"{path} -> 404 (or 400)", status in (400, 404) and b"root:" not in body, str(status))
    for method in ["POST", "PUT", "DELETE", "PATCH", "OPTIONS"]:
        status, headers, _ = job.request("/state.json", right, method=method)
        check(f"{method} -> 405", status == 405 and headers.get("Allow") == "GET, HEAD", str(status))
    status, _, body = job.request("/camera", dict(right, **{"Content-Type": FORM}), method="POST",
                                  body="view=main&action=reset")
    check("POST /camera, the page not interactive -> 403", status == 403 and
          b"live.interactive is off" in body, str(status))


def oversized(job):
    auth = f"Authorization: Bearer {job.token}\r\n".encode()
    cases = [
        ("a 20000-character path", b"GET /" + b"a" * 20000 + b" HTTP/1.1\r\nHost: x\r\n" + auth +
         b"\r\n", (400, 413, 414)),
        ("a 20000-byte header", b"GET /state.json HTTP/1.1\r\nHost: x\r\nX-Big: " + b"b" * 20000 +
         b"\r\n" + auth + b"\r\n", (400, 413, 431)),
        ("100 headers", b"GET /state.json HTTP/1.1\r\nHost: x\r\n" + auth +
         b"".join(b"X-H%d: 1\r\n" % i for i in range(100)) + b"\r\n", (431,)),
        ("a body on a GET", b"GET /state.json HTTP/1.1\r\nHost: x\r\nContent-Length: 1000000\r\n" +
         auth + b"\r\n" + b"c" * 1000, (400, 413)),
    ]
    for what, data, expected in cases:
        status, seconds = raw(job, data)
        # Closed at the latest when civetweb stops reading what it drops (two timeouts).
        check(f"{what} -> {'/'.join(map(str, expected))}", status in expected and seconds < 12,
              f"{status}, closed after {seconds:.2f} s")


def server_limit(name, header="live_server.h"):
    """A limit of insitu/live/live_server.h (`static constexpr ... name = value;`), or of another
    header there, read from the header so that the test follows the server."""
    header = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                          "insitu", "live", header)
    with open(header) as f:
        match = re.search(r"\b" + name + r"\s*=\s*([0-9.]+)\s*;", f.read())
    if not match:
        raise SystemExit(f"{header}: no {name}")
    return float(match.group(1))


# kBurst requests at once per address, kRequestsPerSecond after.
BURST, PER_SECOND = server_limit("kBurst"), server_limit("kRequestsPerSecond")
# What a request held up behind a slow client would wait: that client's write timeout.
REQUEST_TIMEOUT = server_limit("kRequestTimeoutMs") / 1000
# The page's threads, the feed's and civetweb's, and only they, run at this niceness.
PAGE_NICE = int(server_limit("kThreadNice", "live_feed.h"))


def rate_limit(job):
    """300 requests from one address, from 10 threads so that they come faster than the limit
    refills even on a loaded machine (one at a time, each took over 13 ms there: 300 within the
    bucket's refill): some refused, and no more served than the limit allows in the time taken."""
    time.sleep(2.5)  # the bucket full again
    statuses = []
    lock = threading.Lock()

    def some(n):
        for _ in range(n):
            status = job.get("/state.json")[0]
            with lock:
                statuses.append(status)

    start = time.time()
    threads = [threading.Thread(target=some, args=(30,)) for _ in range(10)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    seconds = time.time() - start
    limited, served = statuses.count(429), statuses.count(200)
    most = BURST + PER_SECOND * seconds
    check("300 requests from one address: 429 past the rate limit, no more served than it allows",
          limited > 0 and served <= most + 1 and set(statuses) <= {200, 429},
          f"{limited} of 300 refused in {seconds:.2f} s, {served} served (at most {most:.0f})")
    time.sleep(2.5)


def simultaneous(job, count=200):
    before = job.threads()
    results, most_threads = [None] * count, [before]
    start = threading.Barrier(count + 1)

    def one(i):
        start.wait()
        t0 = time.time()
        try:
            status, _ = raw(job, f"GET /state.json HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer "
                                 f"{job.token}\r\n\r\n".encode(), timeout=60)
        except OSError as e:
            status = type(e).__name__
        results[i] = (status, time.time() - t0)

    threads = [threading.Thread(target=one, args=(i,)) for i in range(count)]
    for t in threads:
        t.start()
    start.wait()
    while any(t.is_alive() for t in threads):
        most_threads.append(job.threads())
        time.sleep(0.05)
    for t in threads:
        t.join()
    statuses = [r[0] for r in results]
    slowest = max(r[1] for r in results)
    summary = {s: statuses.count(s) for s in set(statuses)}
    check(f"{count} simultaneous connections: each answered 200 or 429, none held",
          set(statuses) <= {200, 429} and slowest < 30, f"{summary}, slowest {slowest:.2f} s")
    check("... on the job's threads as before (a fixed pool)", max(most_threads) <= before,
          f"{before} threads before, at most {max(most_threads)} during")
    time.sleep(2.5)


def slow_sender(job):
    s = socket.create_connection((job.host, job.port), timeout=30)
    head = b"GET /state.json HTTP/1.1\r\nHost: x\r\nX-Slow: " + b"s" * 60
    start, closed = time.time(), None
    for b in head:
        try:
            s.sendall(bytes([b]))
            s.settimeout(1.0)
            if s.recv(1) == b"":
                closed = time.time() - start
                break
        except socket.timeout:
            continue
        except OSError:
            closed = time.time() - start
            break
        if time.time() - start > 20:
            break
    s.close()
    check("a client sending a byte a second is cut off after the request timeout (5 s)",
          closed is not None and closed < 9, f"after {closed and round(closed, 1)} s")


def slow_reader(job):
    s = socket.socket()
    s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 2048)
    s.settimeout(5)
    s.connect((job.host, job.port))
    s.sendall(f"GET /view/main.png HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer {job.token}"
              f"\r\n\r\n".encode())
    latencies, stop = [], threading.Event()

    def others():
        while not stop.is_set():
            t0 = time.time()
            status = job.get("/state.json")[0]
            latencies.append((status, time.time() - t0))
            time.sleep(0.5)

    other = threading.Thread(target=others)
    other.start()
    read = 0
    for _ in range(10):
        try:
            read += len(s.recv(1))
        except OSError:
            break
        time.sleep(1)
    stop.set()
    other.join()
    s.close()
    # A request held up behind it would wait out its write timeout; served beside it, each takes
    # what the load allows (51 ms alone, 1.1 s beside two busy loops under the sanitizers).
    worst = max(t for _, t in latencies)
    check("a client reading a byte a second holds no one up: others served meanwhile",
          all(st == 200 for st, _ in latencies) and worst < REQUEST_TIMEOUT / 2,
          f"{len(latencies)} requests, slowest {worst * 1000:.0f} ms; it read {read} bytes")


def in_situ_ms(job):
    """The 20th percentile of the in-situ time per render step (the first left out): the cost of
    a step when the machine's other work leaves it alone, which the median is not on a shared
    machine."""
    rows = [r for r in job.stats() if r.get("timings_ms", {}).get("in_situ") is not None]
    times = sorted(r["timings_ms"]["in_situ"] for r in rows[1:])
    return statistics.quantiles(times, n=5)[0], len(rows)


ATTACKS = [token_rules, fixed_paths, oversized, rate_limit, simultaneous, slow_sender, slow_reader]
ATTACKS_TAKE_S = 35  # what they took on the machine where this was written (34.6-36.4 s)


def one_run(dambreak, work, page_first, same):
    """One pair side by side, the attacks on the second job (`same`: no page, a wait as long as
    the attacks): the second's in-situ time per render step's change over the reference's."""
    shutil.rmtree(work, ignore_errors=True)
    live = None if same else {"enabled": "true", "port": 0}

    # Both run until the attacks are over (stop()).
    def reference():
        return LiveJob(dambreak, os.path.join(work, "without"), None, None, PARTICLES, EVERY)

    def second():
        return LiveJob(dambreak, os.path.join(work, "with"), live, None, PARTICLES, EVERY)

    if page_first:
        job, ref = second(), reference()
    else:
        ref, job = reference(), second()
    if same:
        time.sleep(ATTACKS_TAKE_S)
    else:
        print("live page:", job.wait_url(), flush=True)
        job.wait_state(lambda s: s["views"][0]["step"] >= 0)
        # What the page could take from the solver at most, were every one of its cycles on the
        # solver's core: its threads' CPU time over the attacks' wall time, the server's
        # (answering the clients) and the feed's (encoding every render step's pictures).
        def cpu():
            return (time.time(), job.cpu_seconds(), job.cpu_seconds(PAGE_NICE),
                    job.cpu_seconds(PAGE_NICE, "civetweb"))

        before = cpu()
        for part in ATTACKS:
            if job.process.poll() is not None:
                check(f"{part.__name__}: the job still running", False, "it ended on its own")
                break
            part(job)
        seconds, every, page, server = (b - a for a, b in zip(before, cpu()))
        print(f"the page's threads used {page:.2f} s of CPU over the attacks' {seconds:.1f} s "
              f"({page / seconds:.1%} of one core): the server's {server:.2f} s, the feed's "
              f"{page - server:.2f} s; the job's other threads {every - page:.1f} s", flush=True)
    job.stop()
    ref.stop()
    job.finish()
    ref.finish()
    ref_ms, ref_steps = in_situ_ms(ref)
    live_ms, live_steps = in_situ_ms(job)
    change = live_ms / ref_ms - 1
    print(f"{'the second job' if same else 'the job with the page'}, started "
          f"{'first' if page_first else 'second'}: 20th percentile {live_ms:.3f} ms over "
          f"{live_steps} steps, without {ref_ms:.3f} ms over {ref_steps}: {change:+.1%}",
          flush=True)
    return change


def main():
    dambreak, work = sys.argv[1], sys.argv[2]
    runs = int(sys.argv[sys.argv.index("--runs") + 1]) if "--runs" in sys.argv else 1
    same = "--same" in sys.argv
    changes = [one_run(dambreak, work, run % 2 == 1, same) for run in range(runs)]
    change = statistics.median(changes)
    goal = "within" if abs(change) <= GOAL else "NOT within"
    check(f"in-situ time per render step at most {TOLERANCE:.0%} over the run without the page "
          f"({goal} the {GOAL:.0%} goal)", change <= TOLERANCE,
          f"{change:+.1%}" + (f", the median of {runs} runs" if runs > 1 else ""))
    return check.verdict()


if __name__ == "__main__":
    sys.exit(main())

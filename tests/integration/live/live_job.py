"""A dam break job with the live page (insitu/live/), for the live page's tests.

Starts examples/dambreak with a config that renders one view every few steps, writes its PNG
frames and stats lines, and serves the live page on a free port; reads the URL the job prints.
Standard library only.
"""
import glob
import http.client
import json
import os
import re
import subprocess
import threading
import time
import urllib.parse

SKIP = 77  # ctest's SKIP_RETURN_CODE for these tests


class Checks:
    """A test script's checks: each printed as it is made, the failed ones kept for the end."""

    def __init__(self):
        self.failures = []

    def __call__(self, what, ok, detail=""):
        print(("ok   " if ok else "FAIL ") + what + (f": {detail}" if detail else ""), flush=True)
        if not ok:
            self.failures.append(what)

    def verdict(self):
        """Prints the tally; the script's exit status."""
        print(f"{len(self.failures)} failed" if self.failures else "all passed")
        return 1 if self.failures else 0


def config_text(folder, live, every=5, width=320, height=180):
    lines = [
        f"output_folder: {folder}",
        f"trigger: {{every_steps: {every}, first: true, last: true}}",
        f"views: [{{name: main, width: {width}, height: {height}}}]",
        "outputs:",
        "  png: {enabled: true}",
        "  stats: {enabled: true}",
    ]
    if live is not None:
        lines.append("live: {" + ", ".join(f"{k}: {v}" for k, v in live.items()) + "}")
    return "\n".join(lines) + "\n"


class LiveJob:
    """The job, its live page's address and token, and what it wrote. `steps` None: it runs
    until stop() (the solver's --stop-file), so that a test takes the time its checks take on
    any machine, the sanitizers' builds included, not a step count's."""

    def __init__(self, dambreak, folder, live, steps, particles=4000, every=5, size=(320, 180)):
        os.makedirs(folder, exist_ok=True)
        self.folder = folder
        path = os.path.join(folder, "run.yaml")
        with open(path, "w") as f:
            f.write(config_text(folder, live, every, *size))
        self.log = []
        self.url = None
        self._found = threading.Event()
        self.stop_file = os.path.join(folder, "STOP")
        ends = ["--steps", str(steps)] if steps is not None else \
            ["--steps", str(10**9), "--stop-file", self.stop_file]
        self.process = subprocess.Popen(
            [dambreak, "--config", path, "--particles", str(particles), *ends,
             "--progress-every", "0"],
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        threading.Thread(target=self._read_log, daemon=True).start()

    def _read_log(self):
        for line in self.process.stderr:
            self.log.append(line.rstrip("\n"))
            m = re.search(r"live page: (http://\S+)", line)
            if m and self.url is None:
                self.url = m.group(1)
                self._found.set()
        self._found.set()

    def wait_url(self, timeout=120):
        self._found.wait(timeout)
        if self.url is None:
            raise RuntimeError("the job printed no live page URL:\n" + "\n".join(self.log))
        u = urllib.parse.urlsplit(self.url)
        self.host, self.port = u.hostname, u.port
        self.token = urllib.parse.parse_qs(u.query)["token"][0]
        return self.url

    def request(self, path, headers=None, method="GET", timeout=10, body=None):
        """(status, headers, body) of one request with the given headers (no token added)."""
        c = http.client.HTTPConnection(self.host, self.port, timeout=timeout)
        c.request(method, path, body=body, headers=headers or {})
        r = c.getresponse()
        body = r.read()
        c.close()
        return r.status, dict(r.getheaders()), body

    def get(self, path):
        return self.request(path, {"Authorization": "Bearer " + self.token})

    def state(self):
        status, _, body = self.get("/state.json")
        assert status == 200, status
        return json.loads(body)

    def wait_state(self, holds, timeout=120):
        end = time.time() + timeout
        while time.time() < end:
            s = self.state()
            if holds(s):
                return s
            time.sleep(0.2)
        raise RuntimeError("the live page's state never got there")

    def stop(self):
        """Asks a job started without `steps` to end: its next step is its last."""
        open(self.stop_file, "w").close()

    def finish(self, timeout=300):
        rc = self.process.wait(timeout)
        if rc != 0:
            raise RuntimeError(f"the job failed ({rc}):\n" + "\n".join(self.log))

    def threads(self):
        with open(f"/proc/{self.process.pid}/status") as f:
            return int(re.search(r"Threads:\s+(\d+)", f.read()).group(1))

    def cpu_seconds(self, nice=None, named=""):
        """CPU time its threads have used so far: those at niceness `nice` only, if given, and
        whose names start with `named`."""
        total = 0
        for tid in os.listdir(f"/proc/{self.process.pid}/task"):
            try:
                with open(f"/proc/{self.process.pid}/task/{tid}/stat") as f:
                    name, fields = f.read().split("(", 1)[1].rsplit(")", 1)
            except OSError:  # the thread ended meanwhile
                continue
            fields = fields.split()
            if (nice is None or int(fields[16]) == nice) and name.startswith(named):
                total += int(fields[11]) + int(fields[12])  # utime, stime
        return total / os.sysconf("SC_CLK_TCK")

    def stats(self):
        lines = []
        for path in glob.glob(os.path.join(self.folder, "**", "*.jsonl"), recursive=True):
            with open(path) as f:
                lines += [json.loads(line) for line in f if line.strip()]
        return sorted(lines, key=lambda r: r["step"])

    def png(self, view, step, timeout=60):
        """The bytes of the job's PNG frame of `view` at `step`. The job's writer thread writes
        frames after the step that rendered them, and the page may show a step first: waits."""
        start = time.time()
        while True:
            paths = glob.glob(os.path.join(self.folder, "**", f"{view}_*{step}.png"),
                              recursive=True)
            paths = [p for p in paths if re.search(rf"{view}_0*{step}\.png$", p)]
            if paths:
                if time.time() > start + 0.1:
                    print(f"(the PNG of step {step} came {time.time() - start:.1f} s after the "
                          "page showed it)", flush=True)
                with open(paths[0], "rb") as f:
                    return f.read()
            if time.time() > start + timeout:
                raise RuntimeError(f"no PNG of view {view} at step {step} in {self.folder}")
            time.sleep(0.2)

"""A real Debian InfluxDB (influxd 1.x) for the tests: on free loopback ports, with its
configuration, data and logs in a folder of the test's scratch, stopped when the test ends."""
import atexit
import json
import os
import shutil
import socket
import subprocess
import time
import urllib.error
import urllib.parse
import urllib.request

GUARD_S = 20


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class InfluxServer:
    """influxd on 127.0.0.1: the HTTP API on one free port, its RPC service on another; no
    usage reporting, no self-monitoring, nothing outside `folder`."""

    def __init__(self, scratch, name):
        self.folder = os.path.join(scratch, name + ".influxdb")
        shutil.rmtree(self.folder, ignore_errors=True)
        os.makedirs(self.folder)
        self.port = free_port()
        self.conf = os.path.join(self.folder, "influxdb.conf")
        with open(self.conf, "w") as f:
            f.write("\n".join([
                "reporting-disabled = true",
                f'bind-address = "127.0.0.1:{free_port()}"',
                "[meta]", f'  dir = "{self.folder}/meta"',
                "[data]", f'  dir = "{self.folder}/data"', f'  wal-dir = "{self.folder}/wal"',
                "  query-log-enabled = false",
                "[retention]", "  enabled = false",
                "[shard-precreation]", "  enabled = false",
                "[monitor]", "  store-enabled = false",
                "[continuous_queries]", "  enabled = false",
                "[http]", f'  bind-address = "127.0.0.1:{self.port}"', "  log-enabled = false",
                "  max-row-limit = 0", ""]))
        self.log = open(os.path.join(self.folder, "influxd.log"), "w")
        self.proc = subprocess.Popen(["influxd", "run", "-config", self.conf],
                                     stdout=self.log, stderr=self.log)
        atexit.register(self.stop)  # also when a check fails with an exception
        deadline = time.monotonic() + GUARD_S
        while self.request("GET", "/ping")[0] != 204:
            if self.proc.poll() is not None:
                raise RuntimeError(f"influxd exited {self.proc.returncode}; see {self.log.name}")
            if time.monotonic() > deadline:
                raise RuntimeError(f"influxd did not answer /ping; see {self.log.name}")
            time.sleep(0.05)

    def request(self, method, path, params=None, body=None):
        """(HTTP status, body text); status 0 when nothing listens yet."""
        url = f"http://127.0.0.1:{self.port}{path}"
        if params:
            url += "?" + urllib.parse.urlencode(params)
        req = urllib.request.Request(url, data=body, method=method)
        try:
            with urllib.request.urlopen(req, timeout=GUARD_S) as r:
                return r.status, r.read().decode()
        except urllib.error.HTTPError as e:
            return e.code, e.read().decode()
        except (ConnectionError, urllib.error.URLError):
            return 0, ""

    def query(self, db, q):
        """The results of one InfluxQL statement, times in nanoseconds."""
        status, text = self.request("POST", "/query", {"db": db, "q": q, "epoch": "ns"})
        if status != 200:
            raise RuntimeError(f"{q}: HTTP {status}: {text}")
        result = json.loads(text)["results"][0]
        if "error" in result:
            raise RuntimeError(f"{q}: {result['error']}")
        return result.get("series", [])

    def stop(self):
        if self.proc.poll() is None:
            self.proc.terminate()
            self.proc.wait(GUARD_S)
        self.log.close()

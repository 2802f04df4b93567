"""A real Debian mosquitto broker for the tests: on a free loopback port, with a password
file, optionally with TLS (certificates made here with openssl), and a paho subscriber that
records everything it receives."""
import atexit
import os
import pwd
import queue
import socket
import subprocess
import threading
import time

import paho.mqtt.client as paho

# The longest one program this test runs may take: a guard, not a timing check. On expiry
# subprocess raises TimeoutExpired, which names the command that was waited for.
RUN_GUARD_S = 120

USER, PASSWORD = "pvtap", "s3cret-pw"
ADMIN, ADMIN_PASSWORD = "watcher", "watcher-pw"
GUARD_S = 20


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def make_ca(folder, name):
    """A CA and a server certificate it signed for 127.0.0.1 and localhost (EC keys: fast)."""
    run = lambda *a: subprocess.run(["openssl", *a], check=True, capture_output=True,
                                    timeout=RUN_GUARD_S)
    ca_key, ca_crt = (os.path.join(folder, f"{name}-ca.{e}") for e in ("key", "crt"))
    key, csr, crt = (os.path.join(folder, f"{name}-server.{e}") for e in ("key", "csr", "crt"))
    ext = os.path.join(folder, f"{name}.ext")
    with open(ext, "w") as f:
        f.write("subjectAltName=IP:127.0.0.1,DNS:localhost\n")
    ec = ["-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes"]
    run("req", "-x509", *ec, "-keyout", ca_key, "-out", ca_crt, "-days", "2",
        "-subj", f"/CN=pvtap test CA {name}")
    run("req", *ec, "-keyout", key, "-out", csr, "-subj", "/CN=localhost")
    run("x509", "-req", "-in", csr, "-CA", ca_crt, "-CAkey", ca_key, "-CAcreateserial",
        "-out", crt, "-days", "2", "-extfile", ext)
    for path in (ca_key, key):
        os.chmod(path, 0o644)  # mosquitto may run as another user
    return {"ca": ca_crt, "cert": crt, "key": key}


class Broker:
    """mosquitto on 127.0.0.1:port; stop() and start() keep the port and, with
    persistence, the subscribers' sessions and retained messages."""

    def __init__(self, scratch, name, tls=None):
        self.folder = os.path.join(scratch, name + ".broker")
        os.makedirs(self.folder, exist_ok=True)
        self.port = free_port()
        self.tls = tls
        self.proc = None
        passwd = os.path.join(self.folder, "passwd")
        if os.path.exists(passwd):
            os.remove(passwd)
        for user, pw in ((USER, PASSWORD), (ADMIN, ADMIN_PASSWORD)):
            subprocess.run(["mosquitto_passwd", "-b", *(["-c"] if user == USER else []), passwd,
                            user, pw], check=True, capture_output=True, timeout=RUN_GUARD_S)
        os.chmod(passwd, 0o644)
        self.password_file = os.path.join(self.folder, "pvtap.pw")
        with open(self.password_file, "w") as f:
            f.write(PASSWORD + "\n")
        lines = [f"listener {self.port} 127.0.0.1", "allow_anonymous false",
                 f"password_file {passwd}", "persistence true",
                 # No limit on a subscriber's queue: the tests' Python subscriber is slower
                 # than pvtap, and a broker that drops for it would hide what pvtap sent.
                 "max_queued_messages 0",
                 f"persistence_location {self.folder}/",
                 f"user {pwd.getpwuid(os.getuid()).pw_name}"]
        if tls:
            lines += [f"cafile {tls['ca']}", f"certfile {tls['cert']}", f"keyfile {tls['key']}"]
        self.conf = os.path.join(self.folder, "mosquitto.conf")
        with open(self.conf, "w") as f:
            f.write("\n".join(lines) + "\n")
        db = os.path.join(self.folder, "mosquitto.db")
        if os.path.exists(db):
            os.remove(db)
        atexit.register(self.stop)  # also when a check fails with an exception
        self.start()

    def url(self):
        return f"{'mqtts' if self.tls else 'mqtt'}://127.0.0.1:{self.port}"

    def start(self):
        log = open(os.path.join(self.folder, "broker.log"), "a")
        self.proc = subprocess.Popen(["mosquitto", "-c", self.conf], stdout=log, stderr=log)
        deadline = time.monotonic() + GUARD_S
        while time.monotonic() < deadline:
            if self.proc.poll() is not None:
                raise RuntimeError(f"mosquitto exited {self.proc.returncode}; see {log.name}")
            try:
                socket.create_connection(("127.0.0.1", self.port), 0.2).close()
                return
            except OSError:
                time.sleep(0.02)
        raise RuntimeError("mosquitto did not listen")

    def stop(self):
        if self.proc and self.proc.poll() is None:
            self.proc.terminate()
            self.proc.wait(GUARD_S)


class Subscriber:
    """Everything published under `topics` (QoS 1, a persistent session, so that what was
    published while broker or subscriber were away still arrives), as (topic, payload, retain)
    in arrival order."""

    def __init__(self, broker, topics=("#",), client_id="pvtap-test-watcher"):
        self.messages = []
        self._lock = threading.Lock()
        self._subscribed = queue.Queue()
        self.client = paho.Client(client_id=client_id, clean_session=False)
        self.client.username_pw_set(ADMIN, ADMIN_PASSWORD)
        if broker.tls:
            self.client.tls_set(ca_certs=broker.tls["ca"])
        self.client.reconnect_delay_set(min_delay=1, max_delay=1)
        self.client.on_connect = lambda c, u, f, rc: c.subscribe([(t, 1) for t in topics])
        self.client.on_subscribe = lambda *a: self._subscribed.put(True)
        self.client.on_message = self._on_message
        self.client.connect("127.0.0.1", broker.port)
        self.client.loop_start()
        self._subscribed.get(timeout=GUARD_S)

    def _on_message(self, client, userdata, m):
        with self._lock:
            self.messages.append((m.topic, m.payload.decode("utf-8", "replace"), bool(m.retain)))

    def snapshot(self):
        with self._lock:
            return list(self.messages)

    def wait_for(self, predicate, timeout=GUARD_S):
        """Waits until predicate(messages) holds; returns whether it did."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if predicate(self.snapshot()):
                return True
            time.sleep(0.05)
        return predicate(self.snapshot())

    def latest(self, prefix=""):
        """The last payload of every topic under `prefix`."""
        out = {}
        for topic, payload, _ in self.snapshot():
            if topic.startswith(prefix):
                out[topic] = payload
        return out

    def close(self):
        self.client.loop_stop()
        self.client.disconnect()

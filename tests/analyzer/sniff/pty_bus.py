"""A simulated RS485 bus played onto the master side of real pseudo-terminals, for the
`pvtap sniff` tests and benchmark. A pty ignores baud rate, so this writer paces the bytes
itself: each burst of bytes (or each byte) is written when a UART at the bus's baud would
have finished sending it.
"""
import json
import os
import subprocess
import termios
import time
import tty

# The longest one program this test runs may take: a guard, not a timing check. On expiry
# subprocess raises TimeoutExpired, which names the command that was waited for.
RUN_GUARD_S = 120


def simulate(sim, scratch, name, args):
    """Runs pvtap-sim with `args`, returns its ground truth (a dict)."""
    truth_path = os.path.join(scratch, name + ".truth.json")
    subprocess.run([sim, *args, "--truth", truth_path], check=True, timeout=RUN_GUARD_S)
    with open(truth_path, encoding="utf-8") as f:
        return json.load(f)


class Pty:
    """One pseudo-terminal: the test writes to `master`, pvtap opens `path` (the slave)."""

    def __init__(self):
        self.master, self._slave = os.openpty()
        self.path = os.ttyname(self._slave)
        # Raw from the start, so that nothing written before pvtap sets its own termios is
        # echoed or held for a line end.
        tty.setraw(self._slave)
        attrs = termios.tcgetattr(self._slave)
        attrs[3] &= ~termios.ECHO
        termios.tcsetattr(self._slave, termios.TCSANOW, attrs)
        os.set_blocking(self.master, False)

    def drain_master(self):
        """Bytes that arrived on the master side: what someone wrote to the slave."""
        got = b""
        while True:
            try:
                chunk = os.read(self.master, 4096)
            except (BlockingIOError, OSError):
                return got
            if not chunk:
                return got
            got += chunk

    def unplug(self):
        """Closes both sides: readers of the slave see a hang-up, as when an adapter is
        pulled."""
        os.close(self._slave)
        os.close(self.master)

    def close(self):
        for fd in (self._slave, self.master):
            try:
                os.close(fd)
            except OSError:
                pass


def byte_schedule(events, baud, bits_per_char=10, bursts=True):
    """(due offset in seconds from the first event, byte) for every byte of the events.

    Byte by byte (bursts=False), each byte is due when a UART would have sent it. But a pty
    hands written bytes to the reader through a kernel worker, which a loaded machine can
    delay by a scheduler tick, longer than t3.5 at 9600 baud: a silence inside a frame that
    was never on the bus. So by default each burst of bytes (a frame, or frames and noise
    with no silence between them) is due at once, when its last byte would have been sent,
    as a USB adapter delivers it; the silences between bursts stay as on the bus."""
    char_s = bits_per_char / baud
    first = events[0]["ts"]
    out = []
    for event in events:
        data = bytes.fromhex(event["hex"])
        for i, b in enumerate(data):
            out.append((event["ts"] - first + (i + 1) * char_s, b))
    if not bursts:
        return out
    # From the end: a byte joins the burst of the next one unless a silence lies between.
    burst_end = None
    for k in range(len(out) - 1, -1, -1):
        due, b = out[k]
        if burst_end is None or out[k + 1][0] - due > 1.5 * char_s:
            burst_end = due
        out[k] = (burst_end, b)
    return out


def keep_time():
    """A UART is clocked by hardware; a writer that the scheduler delays inside a frame puts
    a real silence on the bus, which splits the frame. As root, the writing thread takes a
    real-time priority so that builds on the same machine cannot delay it."""
    try:
        os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(10))
    except (PermissionError, OSError):
        pass


# The longest the reader may leave the pty full before play() gives up: a guard against a
# reader that stopped (a pty holds a few KiB; a reading pvtap empties it in milliseconds).
STALL_S = 30


def write_all(master, chunk):
    """Writes `chunk` to the non-blocking master side; raises when the reader takes nothing
    for STALL_S seconds, naming how much was left, instead of waiting forever."""
    stalled_since = None
    while chunk:
        try:
            chunk = chunk[os.write(master, chunk):]
            stalled_since = None
        except BlockingIOError:
            now = time.monotonic()
            stalled_since = stalled_since or now
            if now - stalled_since > STALL_S:
                raise RuntimeError("the pty's reader took none of the last %d bytes for %g s: "
                                   "it stopped reading" % (len(chunk), STALL_S)) from None
            time.sleep(0.001)


def play(master, schedule, start, writes=None):
    """Writes each byte at start + its due offset; bytes that are due together go in one
    write, as a USB adapter batches them. Returns the most any write was late (seconds).
    With a `writes` list, appends (bytes written so far, time.monotonic()) after each write."""
    keep_time()
    i = 0
    worst = 0.0
    while i < len(schedule):
        due = start + schedule[i][0]
        wait = due - time.monotonic()
        if wait > 0:
            time.sleep(wait)
        now = time.monotonic()
        worst = max(worst, now - due)
        j = i
        while j < len(schedule) and start + schedule[j][0] <= now:
            j += 1
        write_all(master, bytes(b for _, b in schedule[i:j]))
        i = j
        if writes is not None:
            writes.append((i, time.monotonic()))
    return worst


def play_duplex(masters, events, baud, start):
    """A 4-wire bus: the requests' bytes onto masters[0], the replies' and the noise onto
    masters[1], each burst when its last byte would have been sent, on one clock."""
    keep_time()
    first = events[0]["ts"]
    merged = []
    for side, master in enumerate(masters):
        mine = [e for e in events if (e.get("role") == "request") == (side == 0)]
        if not mine:
            continue
        offset = mine[0]["ts"] - first
        merged += [(due + offset, side, b) for due, b in byte_schedule(mine, baud)]
    merged.sort(key=lambda item: item[0])
    i = 0
    while i < len(merged):
        due, side, _ = merged[i]
        wait = start + due - time.monotonic()
        if wait > 0:
            time.sleep(wait)
        j = i
        while j < len(merged) and merged[j][1] == side and merged[j][0] == due:
            j += 1
        write_all(masters[side], bytes(b for _, _, b in merged[i:j]))
        i = j

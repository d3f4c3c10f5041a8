"""The FC link over a pseudo-terminal paced at 115 200 baud (issue 14): `motiontool drive --listen fc:pty,baud=115200`
in its own process answers as the line would carry request and answer (11-bit characters), FcLink is the master.
Prints
- fc_param_round_trips: parameter reads per second (goal >= 250; the line allows ~327 for two 16-byte telegrams),
- fc_upload_262_parameters: seconds to read all 262 parameters (goal < 2 s),
- fc_write_verified: verified parameter writes per second,
- fc_polled_scope_samples: samples per second of a polling scope with 4 curves (one read_signals per poll, through
  the extension), and fc_polled_scope_polls,
- fc_download_5kB: seconds to download a 5 kB program image (extension, chunked),
- fc_wire_limit_round_trips: what the line alone allows for a parameter round trip,
- fc_param_round_trip_cpu: CPU time (master + drive process) per parameter round trip — on a shared, loaded
  machine the rates above include waiting for a core; wire time + this CPU time is what an idle machine reaches,
- fc_repeats: telegrams sent again (timeouts under load show here),
- fc_flood_round_trips_alone / _flooded / _flooded_share: parameter reads per second of a well-behaved master on
  `fc:socket://…,baud=115200` alone and while a second connection floods the drive with garbage bytes as fast as
  it can (issue 24 goal: >= 80 %),
- fc_zlib_bomb_peak_rss: the drive's peak RSS (VmHWM) after a request whose zlib body inflates to 1 GiB (issue 24
  item 5; goal <= 150 MB),
- load_average: the machine's 1-minute load average at the end (other work shares the cores).
`--seconds N` (default 3) sets each rate measurement's duration; `--part line|flood|rss` runs one part only."""

import argparse
import os
import select
import subprocess
import sys
import time
import zlib

from motiontool.aposs.driver import compile_source
from motiontool.comms.fc.telegram import wire_time
from motiontool.comms.links import open_link
from motiontool.paramdb import database
from motiontool.scope.acquisition import Polling, new_curve
from motiontool.scope.curves import Scope

BAUD = 115200


def start_drive(baud: int | None = BAUD, listen: str = "fc:pty"):
    """`motiontool drive` on a pty (or `listen`) paced at `baud` (None: not paced), in its own process (ended with
    this one): (process, URL)."""
    paced = f",baud={baud}" if baud else ""
    proc = subprocess.Popen([sys.executable, "-m", "motiontool", "drive", "--listen", listen + paced,
                             "--stop-with-parent"], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    if not select.select([proc.stdout], [], [], 60)[0]:
        proc.kill()
        raise SystemExit("the drive did not start")
    return proc, proc.stdout.readline().split(" ", 2)[2].strip()


def cpu_seconds(pid: int) -> float:
    """User + system CPU time of a process (Linux /proc)."""
    import os

    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def peak_rss_mb(pid: int) -> float:
    """VmHWM of a process (Linux /proc): its peak resident set."""
    with open(f"/proc/{pid}/status", encoding="ascii") as status:
        for line in status:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024
    return float("nan")


FLOODER = """
import socket, sys, threading
sock = socket.create_connection((sys.argv[1], int(sys.argv[2])))
payload = bytes.fromhex(sys.argv[3]) * int(sys.argv[4])
sock.sendall(bytes.fromhex(sys.argv[5]))
def drain():
    while sock.recv(65536):
        pass
threading.Thread(target=drain, daemon=True).start()
sent = 0
try:
    while True:
        sent += sock.send(payload)
except (OSError, KeyboardInterrupt):
    pass
finally:
    print(sent, flush=True)
"""


class Flood:
    """A second connection to a TCP listener, from a process of its own (its CPU is not this one's), sending
    `first` once, then `payload` as fast as it can, reading whatever the drive answers, until stopped; `sent` bytes."""

    def __init__(self, host: str, port: int, payload: bytes, repeat: int = 256, first: bytes = b""):
        self.proc = subprocess.Popen([sys.executable, "-c", FLOODER, host, str(port), payload.hex(), str(repeat),
                                      first.hex()],
                                     stdout=subprocess.PIPE, text=True)
        self.sent = 0

    def stop(self) -> None:
        import signal

        self.proc.send_signal(signal.SIGINT)
        out, _ = self.proc.communicate(timeout=20)
        self.sent = int(out.split()[-1]) if out.split() else 0


def flooded_round_trips(url: str, read, seconds: float, payload: bytes, prefix: str, first: bytes = b"",
                        pid: int | None = None) -> None:
    """`read()` per second alone and while a Flood of `payload` (x 256 per send) runs against the listener at
    `url`'s host:port."""
    host, port = url.split("//", 1)[1].split(",", 1)[0].split("#", 1)[0].rsplit(":", 1)
    cpu = cpu_seconds(pid) if pid else 0.0
    alone = rate(read, seconds)
    cpu_alone = cpu_seconds(pid) - cpu if pid else 0.0
    flood = Flood(host, int(port), payload, first=first)
    try:
        time.sleep(0.2)
        cpu = cpu_seconds(pid) if pid else 0.0
        flooded = rate(read, seconds)
        cpu_flooded = cpu_seconds(pid) - cpu if pid else 0.0
    finally:
        flood.stop()
    if pid:
        print(f"{prefix}_flood_drive_cpu: {100 * cpu_alone / seconds:.0f} % alone, {100 * cpu_flooded / seconds:.0f} %"
              " flooded")
    print(f"{prefix}_flood_round_trips_alone: {alone:.0f} /s")
    print(f"{prefix}_flood_round_trips_flooded: {flooded:.0f} /s (the flood sent {flood.sent / 1e6:.0f} MB)")
    print(f"{prefix}_flood_round_trips_flooded_share: {100 * flooded / alone:.0f} %")


def zlib_bomb(inflated: int) -> bytes:
    """A link-protocol request whose zlib body inflates to `inflated` zero bytes (tests/comms/test_drive_limits.py)."""
    from motiontool.comms.wire import FLAG_ZLIB, HEADER, REQUEST, VERSION

    packer = zlib.compressobj(9)
    block = bytes(1 << 20)
    body = b"".join(packer.compress(block) for _ in range(inflated >> 20)) + packer.flush()
    return HEADER.pack(VERSION, REQUEST, FLAG_ZLIB, 0, zlib.crc32(body)) + body


def flood_part(seconds: float) -> None:
    proc, url = start_drive(BAUD, "fc:socket://127.0.0.1:0")
    try:
        link = open_link(f"{url}#1")
        link.read_parameter("KPROP")
        garbage = bytes(range(256))        # every byte value: start bytes, lengths, junk
        flooded_round_trips(url, lambda: link.read_parameter("KPROP"), seconds, garbage, "fc", pid=proc.pid)
        link.close()
    finally:
        proc.terminate()
        proc.wait(timeout=20)


def rss_part() -> None:
    proc, url = start_drive(None, "fc:socket://127.0.0.1:0")       # unpaced: the bomb is 1 MB on the wire
    try:
        link = open_link(f"{url}#1")
        started = time.perf_counter()
        try:
            link._exchange(zlib_bomb(1 << 30))
        except Exception as exc:      # a refusal is the expected answer; its form does not matter here
            print(f"fc_zlib_bomb_answer: {type(exc).__name__}")
        print(f"fc_zlib_bomb_seconds: {time.perf_counter() - started:.1f} s")
        print(f"fc_zlib_bomb_peak_rss: {peak_rss_mb(proc.pid):.0f} MB")
        link.close()
    finally:
        proc.terminate()
        proc.wait(timeout=20)


def rate(action, seconds: float) -> float:
    count, start = 0, time.perf_counter()
    while time.perf_counter() - start < seconds:
        action()
        count += 1
    return count / (time.perf_counter() - start)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--part", choices=("all", "line", "flood", "rss"), default="all")
    args = parser.parse_args()
    if args.part in ("all", "line"):
        line_part(args)
    if args.part in ("all", "flood"):
        flood_part(args.seconds)
    if args.part in ("all", "rss"):
        rss_part()
    print(f"load_average: {os.getloadavg()[0]:.1f}")


def line_part(args) -> None:
    proc, url = start_drive()
    try:
        link = open_link(f"{url}#1,baud={BAUD}")
        link.read_parameter("KPROP")
        idle = cpu_seconds(proc.pid)           # the drive's clock thread ticks whatever the link does
        time.sleep(1.0)
        idle = cpu_seconds(proc.pid) - idle
        cpu, wall = time.process_time() + cpu_seconds(proc.pid), time.perf_counter()
        trips = rate(lambda: link.read_parameter('KPROP'), args.seconds)
        cpu = time.process_time() + cpu_seconds(proc.pid) - cpu - idle * (time.perf_counter() - wall)
        count = trips * (time.perf_counter() - wall)
        print(f"fc_param_round_trips: {trips:.0f} /s")
        params = list(database())
        start = time.perf_counter()
        for p in params:
            link.read_parameter(p.number)
        print(f"fc_upload_{len(params)}_parameters: {time.perf_counter() - start:.2f} s")
        values = iter(range(10**9))
        print(f"fc_write_verified: {rate(lambda: link.write_parameter('19-00', next(values)), args.seconds):.0f} /s")
        scope = Scope()
        for signal in ("APOS", "CPOS", "TRACKERR", "AVEL"):
            new_curve(scope, signal, "poll", "polled")
        polling = Polling(scope, link)
        polling.start()
        polls = rate(polling.poll, args.seconds)
        print(f"fc_polled_scope_samples: {polls * 4:.0f} /s")
        print(f"fc_polled_scope_polls: {polls:.0f} /s")
        image = b""
        lines = 50
        while len(image) < 5000:   # a program image of about 5 kB
            lines += 50
            source = "\n".join(f"v{i % 50} = {i} * 3 + v{(i + 1) % 50}" for i in range(lines)) + "\n"
            image = compile_source(source, "big.m").image.to_bytes()
        start = time.perf_counter()
        link.download(image, name="big")
        print(f"fc_download_{len(image) / 1000:.1f}kB: {time.perf_counter() - start:.2f} s")
        print(f"fc_wire_limit_round_trips: {1 / (2 * wire_time(16, BAUD)):.0f} /s")
        print(f"fc_param_round_trip_cpu: {1000 * cpu / count:.2f} ms")
        stats = link.bus.stats
        print(f"fc_repeats: {stats.repeats} telegrams")
        link.close()
    finally:
        proc.terminate()
        proc.wait(timeout=20)


if __name__ == "__main__":
    main()

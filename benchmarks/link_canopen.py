"""The CANopen link through the slcan loopback (issue 15): `motiontool drive --listen canopen:slcan:socket://…` as
its own process, paced at real time, and a CanopenLink in this one. Prints
- canopen_sdo_round_trips: expedited SDO reads of a parameter per second,
- canopen_upload_all_parameters: the time to read all 262 parameters,
- canopen_download_program: the time to download a 37 kB program image (block transfer),
- canopen_pdo_drops: values lost in a Free Run of 4 TxPDOs at 1 kHz (goal 0) over `--seconds` (default 60),
- canopen_pdo_rows: rows received (4 signals each) and canopen_pdo_expected: the controller's milliseconds,
- canopen_display_latency_p95 / _max: how far the newest sample in the oscilloscope's curve buffers is behind the
  controller clock, looked at 20 times a second (goal p95 < 100 ms). The controller clock "now" is estimated from
  SDO reads of sys_clock with the smallest round trip, every 5 s (the drive process may drift from real time);
- canopen_link_cpu / canopen_drive_cpu: CPU time of the two processes per second of the run,
- load_average: the machine's 1-minute load average at the end (other work shares the cores).

`--part clients` compares python-can's own slcan interface (`,client=python-can`) with motiontool's SlcanSocketBus
(decision N13) side by side on one drive: canopen_<client>_sdo_round_trips (/s), canopen_<client>_bulk_upload
(kB/s: the 92 kB EDS of 0x1021 by block upload), canopen_<client>_frames (/s received of 20 000 numbered 1-byte
frames four other connections send as fast as the drive takes them, and how many were lost between them).
`--part flood`: SDO round
trips of a well-behaved master alone and while another connection floods the slcan server with garbage bytes, then
with frames (goal >= 80 %). `--part rss`: the drive's peak RSS (VmHWM) after 25 MiB of slcan line without CR and
after a zlib bomb (a link message inflating to 1 GiB) written to 0x5F00 (issue 24 item 5; goal <= 150 MB).
`--part pdo` is the rest above (`--client python-can` runs it on python-can's reader); `all` (the default) runs
every part.
"""

import argparse
import functools
import os
import select
import signal
import subprocess
import sys
import time

import numpy as np

from link_fc import Flood, cpu_seconds, flooded_round_trips, peak_rss_mb, rate, zlib_bomb  # scripts in benchmarks/
from motiontool.aposs.driver import compile_source
from motiontool.comms.links import open_link
from motiontool.paramdb import database
from motiontool.scope.acquisition import FreeRun, new_curve
from motiontool.scope.curves import Group, Scope

FRAME = b"t7E580011223344556677\r"    # a frame for no node (0x7E5: LSS, which the drive does not serve)
SENDERS = 4


def numbered(can_id: int) -> bytes:
    """256 one-byte frames numbered 0-255: a gap is a loss (modulo 256)."""
    return b"".join(b"t%03X1%02X\r" % (can_id, i) for i in range(256))


SIGNALS = ("APOS", "CPOS", "TRACKERR", "AVEL")
PROGRAM = "VEL 50\nACC 50\nDEC 50\nWHILE 1 DO\nPOSA 200000\nPOSA 0\nENDWHILE\n"


def clients_part(seconds: float) -> None:
    from motiontool.comms.canopen import objects
    from motiontool.comms.canopen.link import open_bus

    drive, url = start_drive()
    channel = url.removeprefix("canopen:slcan:")
    host, port = channel.removeprefix("socket://").rsplit(":", 1)
    try:
        for client in ("fast", "python-can"):
            name = "motiontool" if client == "fast" else "python_can"
            link = open_link(f"{url}#1,client={client}")
            trips = rate(functools.partial(link.read_parameter, "KPROP"), seconds)
            print(f"canopen_{name}_sdo_round_trips: {trips:.0f} /s")
            began = time.perf_counter()
            size = len(link._sdo(functools.partial(link._read_domain, index=objects.STORE_EDS)))
            print(f"canopen_{name}_bulk_upload: {size / 1024 / (time.perf_counter() - began):.0f} kB/s "
                  f"({size // 1024} kB)")
            link.close()
            bus = open_bus("slcan", channel, client=client)
            burst = 20_000
            received, lost, previous, first, last = 0, 0, {}, None, None
            # senders of their own: the drive reads each no faster than a 1 Mbit/s bus (decision N53)
            senders = [Flood(host, int(port), numbered(0x7E0 + k), 1, first=b"O\r") for k in range(SENDERS)]
            try:
                while (msg := bus.recv(1.0)) is not None:
                    if 0x7E0 <= msg.arbitration_id < 0x7E0 + SENDERS:
                        received += 1
                        if msg.arbitration_id in previous:      # a gap in the numbers is a loss
                            lost += (msg.data[0] - previous[msg.arbitration_id] - 1) % 256
                        previous[msg.arbitration_id] = msg.data[0]
                        first = first or time.perf_counter()
                        last = time.perf_counter()
                        if received >= burst:
                            break
            finally:
                for sender in senders:
                    sender.stop()
                bus.shutdown()
            span = (last - first) if first and last and last > first else float("nan")
            offered = sum(sender.sent for sender in senders) // len(numbered(0x7E0)) * 256
            print(f"canopen_{name}_frames: {received / span:.0f} /s ({received} received in {span:.2f} s, at least "
                  f"{lost} lost between them; {SENDERS} senders offered {offered} in all)")
    finally:
        drive.send_signal(signal.SIGTERM)
        drive.wait(timeout=20)


def flood_part(seconds: float) -> None:
    drive, url = start_drive()
    try:
        link = open_link(url + "#1")
        link.read_parameter("KPROP")
        read = lambda: link.read_parameter("KPROP")   # noqa: E731
        flooded_round_trips(url, read, seconds, bytes(range(256)), "canopen_garbage", pid=drive.pid)
        flooded_round_trips(url, read, seconds, FRAME, "canopen_frames", first=b"O\r", pid=drive.pid)
        link.close()
    finally:
        drive.send_signal(signal.SIGTERM)
        drive.wait(timeout=20)


def rss_part() -> None:
    import socket

    drive, url = start_drive()
    try:
        host, port = url.removeprefix("canopen:slcan:socket://").rsplit(":", 1)
        with socket.create_connection((host, int(port))) as flood:
            for _ in range(400):                     # 25 MiB without a CR
                flood.sendall(b"x" * 65536)
            time.sleep(0.5)
        print(f"canopen_line_without_cr_peak_rss: {peak_rss_mb(drive.pid):.0f} MB")
        link = open_link(url + "#1")
        began = time.perf_counter()
        try:
            link._exchange(zlib_bomb(1 << 30))
        except Exception as exc:      # a refusal is the expected answer; its form does not matter here
            print(f"canopen_zlib_bomb_answer: {type(exc).__name__}")
        print(f"canopen_zlib_bomb_seconds: {time.perf_counter() - began:.1f} s")
        print(f"canopen_zlib_bomb_peak_rss: {peak_rss_mb(drive.pid):.0f} MB")
        link.close()
    finally:
        drive.send_signal(signal.SIGTERM)
        drive.wait(timeout=20)


def start_drive() -> tuple[subprocess.Popen, str]:
    proc = subprocess.Popen([sys.executable, "-m", "motiontool", "drive", "--listen",
                             "canopen:slcan:socket://127.0.0.1:0", "--node", "1", "--stop-with-parent"],
                            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    if not select.select([proc.stdout], [], [], 60)[0]:
        proc.kill()
        raise SystemExit("the drive did not start")
    return proc, proc.stdout.readline().split(" ", 2)[2].strip()


def clock_offset(link) -> float:
    """Controller ms minus this machine's monotonic ms, from the sys_clock read with the smallest round trip."""
    best = None
    for _ in range(5):
        before = time.monotonic()
        clock = link.read_object(0x2500, 23)
        after = time.monotonic()
        if best is None or after - before < best[0]:
            best = (after - before, clock - (before + after) / 2 * 1000)
    return best[1]


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--rate-seconds", type=float, default=3.0, help="each rate of the clients and flood parts")
    parser.add_argument("--part", choices=("all", "clients", "flood", "rss", "pdo"), default="all")
    parser.add_argument("--client", choices=("fast", "python-can"), default="fast", help="the pdo part's reader")
    args = parser.parse_args()
    if args.part in ("all", "clients"):
        clients_part(args.rate_seconds)
    if args.part in ("all", "flood"):
        flood_part(args.rate_seconds)
    if args.part in ("all", "rss"):
        rss_part()
    if args.part in ("all", "pdo"):
        pdo_part(args)
    print(f"load_average: {os.getloadavg()[0]:.1f}")


def pdo_part(args) -> None:
    drive, url = start_drive()
    try:
        link = open_link(f"{url}#1,client={args.client}")
        n = 500
        began = time.perf_counter()
        for _ in range(n):
            link.read_parameter("KPROP")
        print(f"canopen_sdo_round_trips: {n / (time.perf_counter() - began):.0f} /s")
        began = time.perf_counter()
        for p in database():
            link.read_parameter(p.number)
        print(f"canopen_upload_all_parameters: {time.perf_counter() - began:.2f} s")
        source = "\n".join(f'x{i} = {i}\nPRINT "line {i} ", x{i}' for i in range(1500)) + "\n"
        image = compile_source(source, "big.m").image.to_bytes()
        began = time.perf_counter()
        link.download(image)
        print(f"canopen_download_program: {time.perf_counter() - began:.2f} s ({len(image) // 1024} kB)")
        link.download(compile_source(PROGRAM, "move.m").image.to_bytes())
        link.start()

        scope = Scope("free_run")
        scope.settings.default_samples = 20_000
        group = scope.add_group(Group("PDO", controller=1))
        for s in SIGNALS:
            new_curve(scope, s, group.name, "free_run")
        run = FreeRun(scope, link, group.name, subscribe=True)
        seen = []   # (first, last) controller time of every packet
        link.subscribe(lambda e: seen.append((e.data["time_ms"][0], e.data["time_ms"][-1]))
                       if e.kind == "samples" else None)
        offset = clock_offset(link)
        cpu_link0, cpu_drive0 = time.process_time(), cpu_seconds(drive.pid)
        run.start()
        started = last_offset = time.monotonic()
        latencies = []
        apos = scope.members(group.name)[0].buffer
        while (now := time.monotonic()) - started < args.seconds:
            time.sleep(0.05)
            if now - last_offset > 5:
                offset, last_offset = clock_offset(link), now
            newest = apos.arrays()[0]
            if newest.size:
                latencies.append(time.monotonic() * 1000 + offset - newest[-1])
        elapsed = time.monotonic() - started
        cpu_link, cpu_drive = time.process_time() - cpu_link0, cpu_seconds(drive.pid) - cpu_drive0
        rows = link.stream.published_rows
        run.stop()
        stream = link.stream
        print(f"canopen_pdo_drops: {stream.dropped + stream.rows_dropped} values")
        print(f"canopen_pdo_rows: {rows} rows")
        span = seen[-1][1] - seen[0][0] + 1 if seen else 0
        print(f"canopen_pdo_expected: {span} rows (the controller's ms from the first row to the last)")
        lat = np.array(latencies[20:] or [0.0])
        print(f"canopen_display_latency_p95: {np.percentile(lat, 95):.0f} ms")
        print(f"canopen_display_latency_max: {lat.max():.0f} ms")
        print(f"canopen_link_cpu: {100 * cpu_link / elapsed:.0f} %")
        print(f"canopen_drive_cpu: {100 * cpu_drive / elapsed:.0f} %")
        link.close()
    finally:
        drive.send_signal(signal.SIGTERM)
        drive.wait(timeout=20)


if __name__ == "__main__":
    main()

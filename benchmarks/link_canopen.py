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
"""

import argparse
import os
import select
import signal
import subprocess
import sys
import time

import numpy as np

from link_fc import cpu_seconds  # the benchmarks are scripts run from benchmarks/
from motiontool.aposs.driver import compile_source
from motiontool.comms.links import open_link
from motiontool.paramdb import database
from motiontool.scope.acquisition import FreeRun, new_curve
from motiontool.scope.curves import Group, Scope

SIGNALS = ("APOS", "CPOS", "TRACKERR", "AVEL")
PROGRAM = "VEL 50\nACC 50\nDEC 50\nWHILE 1 DO\nPOSA 200000\nPOSA 0\nENDWHILE\n"


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
    args = parser.parse_args()
    drive, url = start_drive()
    try:
        link = open_link(url + "#1")
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
    print(f"load_average: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()

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
- fc_repeats: telegrams sent again (timeouts under load show here).
`--seconds N` (default 3) sets each rate measurement's duration."""

import argparse
import select
import subprocess
import sys
import time

from motiontool.aposs.driver import compile_source
from motiontool.comms.fc.telegram import wire_time
from motiontool.comms.links import open_link
from motiontool.paramdb import database
from motiontool.scope.acquisition import Polling, new_curve
from motiontool.scope.curves import Scope

BAUD = 115200


def start_drive(baud: int = BAUD):
    """`motiontool drive` on a pty paced at `baud`, in its own process (ended with this one): (process, URL)."""
    proc = subprocess.Popen([sys.executable, "-m", "motiontool", "drive", "--listen", f"fc:pty,baud={baud}",
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


def rate(action, seconds: float) -> float:
    count, start = 0, time.perf_counter()
    while time.perf_counter() - start < seconds:
        action()
        count += 1
    return count / (time.perf_counter() - start)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seconds", type=float, default=3.0)
    args = parser.parse_args()
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

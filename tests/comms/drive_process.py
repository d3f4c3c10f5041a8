"""`motiontool drive` as a separate process for end-to-end tests: started, its `listening on URL` line read, and
stopped with SIGTERM (which must end it cleanly, exit status 0)."""

from __future__ import annotations

import select
import signal
import subprocess
import sys
import time
from contextlib import contextmanager


class DriveProcess:
    def __init__(self, *args: str, listen: str = "fc:socket://127.0.0.1:0"):
        import weakref

        # --stop-with-parent: the drive ends with its stdin pipe, so it never outlives a killed test run
        self.args = ["drive", "--listen", listen, "--stop-with-parent", *args]
        self.proc = subprocess.Popen([sys.executable, "-m", "motiontool", *self.args], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        weakref.finalize(self, _terminate, self.proc)
        self._url: str | None = None

    @property
    def url(self) -> str:
        if self._url is None:
            deadline = time.monotonic() + 60
            while time.monotonic() < deadline:
                if select.select([self.proc.stdout], [], [], 0.5)[0]:
                    line = self.proc.stdout.readline()
                    assert line.startswith("listening on "), (line, self.proc.stderr.read())
                    self._url = line.split(" ", 2)[2].strip()
                    break
                assert self.proc.poll() is None, self.proc.stderr.read()
            else:
                raise AssertionError("the drive did not say where it listens within 60 s")
        return self._url

    def stop(self) -> tuple[int, str, str]:
        if self.proc.stdin is not None and self.proc.stdin.closed:
            self.proc.stdin = None          # closed by the test already (communicate would flush it)
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
        try:
            out, err = self.proc.communicate(timeout=20)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            out, err = self.proc.communicate()
        return self.proc.returncode, out, err


def _terminate(proc: subprocess.Popen) -> None:
    if proc.poll() is None:
        proc.terminate()


@contextmanager
def drive_process(*args: str, listen: str = "fc:socket://127.0.0.1:0"):
    drive = DriveProcess(*args, listen=listen)
    try:
        assert drive.url
        yield drive
    finally:
        code, _, err = drive.stop()
        assert code == 0, f"the drive ended with {code}: {err}"


class DrivePool:
    """Fresh drives, one started ahead while the previous one is in use (a drive takes a second to start)."""

    def __init__(self, *args: str, listen: str = "fc:socket://127.0.0.1:0"):
        self.args = args
        self.listen = listen
        self.spare: DriveProcess | None = None

    def take(self) -> DriveProcess:
        drive = self.spare or DriveProcess(*self.args, listen=self.listen)
        self.spare = DriveProcess(*self.args, listen=self.listen)
        return drive

    def close(self) -> None:
        if self.spare is not None:
            self.spare.stop()


class PausableProxy:
    """A TCP relay on 127.0.0.1 between a master and a drive whose line can be cut and restored (a pulled cable):
    while paused, bytes in both directions are thrown away."""

    def __init__(self, target_port: int):
        import socket
        import threading

        self.target_port = target_port
        self.paused = threading.Event()
        self.server = socket.create_server(("127.0.0.1", 0))
        self.port = self.server.getsockname()[1]
        self._stop = threading.Event()
        threading.Thread(target=self._accept, daemon=True).start()

    def _accept(self):
        import socket
        import threading

        self.server.settimeout(0.1)
        while not self._stop.is_set():
            try:
                client, _ = self.server.accept()
            except TimeoutError:
                continue
            except OSError:
                return
            upstream = socket.create_connection(("127.0.0.1", self.target_port))
            for a, b in ((client, upstream), (upstream, client)):
                threading.Thread(target=self._pump, args=(a, b), daemon=True).start()

    def _pump(self, source, sink):
        source.settimeout(0.1)
        while not self._stop.is_set():
            try:
                data = source.recv(4096)
            except TimeoutError:
                continue
            except OSError:
                return
            if not data:
                return
            if not self.paused.is_set():
                try:
                    sink.sendall(data)
                except OSError:
                    return

    def close(self):
        self._stop.set()
        self.server.close()

"""`sweep --executor dask:tcp://HOST:PORT` (issue 30 item 3): the same 4 x 4 sweep through a local Dask cluster on
loopback gives the CSV of the local processes byte for byte."""

from __future__ import annotations

import pytest

from motiontool import cli

pytestmark = [pytest.mark.wire, pytest.mark.slow]


def test_a_dask_cluster_gives_the_same_csv(tmp_path, capsys):
    distributed = pytest.importorskip("distributed")
    p = tmp_path / "p.m"
    p.write_text("POSA 204800\n", encoding="utf-8")
    grid = ["sweep", str(p), "--vary", "32-60=20:80:20", "--vary", "32-61=0:300:100", "--seconds", "3",
            "--measure", "max(abs(TRACKERR))", "--measure", "settle_time(APOS, 204800, 10)"]
    assert cli.main([*grid, "--jobs", "2", "-o", str(tmp_path / "local.csv")]) == 0
    with distributed.LocalCluster(processes=True, n_workers=2, threads_per_worker=1, host="127.0.0.1",
                                  dashboard_address=None) as cluster:
        code = cli.main([*grid, "--executor", f"dask:{cluster.scheduler_address}", "-o", str(tmp_path / "dask.csv")])
    err = capsys.readouterr().err
    assert code == 0, err
    assert (tmp_path / "dask.csv").read_bytes() == (tmp_path / "local.csv").read_bytes()
    assert "16 of 16 points" in err


def test_no_scheduler_is_one_line(tmp_path, capsys):
    pytest.importorskip("distributed")
    import socket

    with socket.socket() as s:  # a port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    p = tmp_path / "p.m"
    p.write_text("POSA 204800\n", encoding="utf-8")
    code = cli.main(["sweep", str(p), "--vary", "KPROP=20:40:20", "--measure", "max(APOS)", "--executor",
                     f"dask:tcp://127.0.0.1:{port}", "-o", str(tmp_path / "s.csv")])
    err = capsys.readouterr().err
    assert code == 1 and f"--executor dask:tcp://127.0.0.1:{port}: no Dask scheduler answers there" in err
    assert not (tmp_path / "s.csv").exists()

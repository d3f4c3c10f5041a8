"""Several controllers on one master signal (kernel/simulation.py, issue 5).

DG 254: "Virtual master is an encoder simulation which serves as a common master signal for synchronization of
up-to 32 axes."
DG 796: "… or it can be a multi-axis system where multiple slaves are following the velocity or position of a
common master signal."
DG 8520-8521: "- One encoder is connected to multiple MCO 305" / "- The virtual master output of one MCO 305 is
connected to multiple MCO 305."
DG 2395: "You can execute different programs on different controllers all at the same time …"
"""

from __future__ import annotations

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.kernel.controller import Controller
from motiontool.kernel.master import MasterConfig
from motiontool.kernel.simulation import MAX_NODES, Simulation

LOOP = "WAITI 8 ON\n"  # the program waits (an input that never comes): the VM does not busy-loop
MASTER = "PULSACC 20000\nPULSVEL 10000\n" + LOOP        # 40 qc/ms after 0.5 s (4 qc per pulse, CR 3574-3611)
GEAR = {"SYNCFACTS": 55, "SYNCFACTM": 32, "FFVEL": 1000}  # DG 9318-9324: slave qc per master qc


def load(ctl: Controller, source: str, settings: dict | None = None) -> Controller:
    result = compile_source(source, "node.m")
    assert result.ok, "\n".join(d.format() for d in result.diagnostics)
    for key, value in (settings or {}).items():
        ctl.params.set(key, value, source="link")
    ctl.load(result.image)
    ctl.start()
    return ctl


def prints(ctl: Controller) -> list[str]:
    return [e.text for e in ctl.events if e.kind == "print"]


def errors(sim: Simulation) -> list:
    return [(n, e.text) for n in sim for e in sim[n].events if e.kind == "error"]


def test_two_controllers_share_node_1_virtual_master_and_syncv_follows_with_the_gear():
    """DG 8521: the virtual master output of node 1 is the master input of node 2; SYNCV: slave velocity =
    master velocity · SYNCFACTS / SYNCFACTM (DG 9318-9324)."""
    sim = Simulation([1, 2], master_node=1)
    load(sim[1], MASTER)
    load(sim[2], "VEL 100\nACC 100\nSYNCV\n" + LOOP, GEAR)
    for _ in range(40):
        sim.run_for(50)
        assert sim[2].master.mapos == sim[1].master.mapos            # the same MAPOS on both nodes
        assert sim[2].params.get(3459) == sim[1].params.get(3459)           # 34-59 MAVEL
        assert sim[1].time_ms == sim[2].time_ms == sim.time_ms       # lockstep
    assert sim[1].master.mavel == 40_000 and sim[1].master.mapos > 60_000
    assert sim[2].axis.mode == "sync"
    assert sim[2].axis.profile.velocity == pytest.approx(40.0 * 55 / 32)
    assert sim[1].axis.mode == "idle" and sim[1].axis.apos == 0      # node 1 only produces the master
    assert not errors(sim)


def test_syncp_slave_on_node_2_is_the_same_as_one_controller_running_both_programs():
    """SYNCP (DG 944-1140): CPOS = MAPOS · gear + offset once locked. A slave fed by node 1's PULSVEL moves exactly
    like a single controller whose own virtual master runs the same PULSVEL (CR 3564-3565: the virtual master is
    evaluated "as master input … as they would in an external master")."""
    slave = "VEL 100\nACC 100\nDEC 100\nSYNCP\n" + LOOP
    settings = {**GEAR, "SYNCPOSOFFS": 1000}
    sim = Simulation({1: None, 2: None}, master_node=1)
    load(sim[1], MASTER)
    load(sim[2], slave, settings)
    alone = load(Controller(), "PULSACC 20000\nPULSVEL 10000\n" + slave, settings)
    for _ in range(3000):
        sim.tick()
        alone.tick()
        assert sim[2].axis.cpos == alone.axis.cpos and sim[2].axis.apos == alone.axis.apos
    ctl = sim[2]
    assert ctl.axis.sync.locked
    assert ctl.uu(ctl.axis.cpos) == (sim[1].master.mapos + 1000) * 55 // 32
    assert not errors(sim)


def test_32_controllers_on_one_virtual_master_each_with_its_own_gear():
    """DG 254: a common master signal for up to 32 axes; every slave has its own SYNCFACTS (parameters per node)."""
    sim = Simulation(range(1, MAX_NODES + 1), master_node=1)
    assert len(sim) == 32 and sim.nodes == list(range(1, 33))
    load(sim[1], MASTER)
    for n in range(2, 33):
        load(sim[n], "VEL 100\nACC 100\nDEC 100\nSYNCP\n" + LOOP, {"SYNCFACTS": n, "SYNCFACTM": 32, "FFVEL": 1000})
    sim.run_for(2500)
    mapos = sim[1].master.mapos
    assert mapos > 60_000
    for n in range(2, 33):
        ctl = sim[n]
        assert ctl.master.mapos == mapos
        assert ctl.axis.sync.locked, n
        assert ctl.uu(ctl.axis.cpos) == mapos * n // 32
    assert not errors(sim)


def test_parameters_programs_and_arrays_are_per_node():
    """Each controller keeps its own parameters, program and arrays (DG 2395: different programs on different
    controllers at the same time)."""
    sim = Simulation([3, 7, 12], master_node=7)
    sim[3].params.set("KPROP", 77, source="link")
    load(sim[3], "DIM a[3]\nSET POSFACT_Z 2\na[1] = 5\nPRINT GET KPROP, \" \", GET POSFACT_Z\n" + LOOP)
    load(sim[7], "PRINT GET KPROP, \" \", GET POSFACT_Z\n")
    load(sim[12], "DIM a[2]\na[2] = 9\nPRINT \"twelve\"\n")
    sim.run_for(100)
    assert prints(sim[3]) == ["77 2"]
    assert prints(sim[7]) == [f"{sim[7].params['KPROP']} 1"] and sim[7].params["KPROP"] != 77
    assert prints(sim[12]) == ["twelve"]
    assert sim[3].program_state == "running" and sim[7].program_state == sim[12].program_state == "ended"
    assert sim[3].arrays.arrays[0].data[:] == [5, 0, 0]
    assert sim[12].arrays.arrays[0].data[:] == [0, 9]
    assert sim[7].arrays.arrays == [] or not any(a.data for a in sim[7].arrays.arrays)


def test_a_shared_external_encoder_counts_the_same_on_every_node():
    """DG 8520: "One encoder is connected to multiple MCO 305": without a master node the simulated external
    master encoder drives every node's master input; each node counts like a single controller with it."""
    config = MasterConfig(velocity=2.5, jitter=0.5, seed=3, start_position_qc=100)
    sim = Simulation([1, 2, 5], master=config)
    alone = Controller(master=config)
    sim.run_for(1000)
    alone.run_for(1000)
    assert [sim[n].master.mapos for n in sim] == [alone.master.mapos] * 3
    assert [sim[n].master.mavel for n in sim] == [alone.master.mavel] * 3
    assert Simulation([4]).encoder is not None and Simulation([4])[4].master.mapos == 0  # default: standing still


def test_master_origin_and_own_pulsvel_stay_per_node():
    """DEFMORIGIN / SETMORIGIN (CR 849-859, 3969-3983) set one node's master zero; a node that runs PULSVEL feeds
    its own virtual master back to its own input (CR 3564-3565) and ignores the wire until PULSACC 0 + PULSVEL."""
    sim = Simulation([1, 2, 3], master_node=1)
    load(sim[1], "PULSVEL 10000\n" + LOOP)                          # 40 qc/ms
    load(sim[2], "DELAY 500\nDEFMORIGIN\n" + LOOP)
    load(sim[3], "DELAY 500\nPULSVEL 2500\nDELAY 500\nPULSACC 0\nPULSVEL 0\n" + LOOP)
    sim.run_for(1000)
    assert sim[1].master.mapos == 39_960  # PULSVEL runs in the program slice of tick 1: counting from tick 2
    assert sim[2].master.raw == 39_960 and sim[2].master.mapos == pytest.approx(20_000, abs=80)
    assert sim[3].master.mavel == 10_000                              # its own 2500 Hz, not node 1's
    sim.run_for(1000)
    assert sim[3].master.mavel == 40_000                              # back on the wire from node 1
    assert sim[2].master.raw == sim[1].master.raw == 79_960


def test_esc_on_the_master_node_stops_the_common_master():
    """DG 10782: [Esc] stops the master simulation — every slave on its signal sees the master stand still."""
    sim = Simulation([1, 2], master_node=1)
    load(sim[1], MASTER)
    load(sim[2], "VEL 100\nACC 100\nDEC 100\nSYNCV\n" + LOOP, GEAR)
    sim.run_for(1000)
    sim[1].break_program()
    sim.run_for(3000)
    assert sim[1].master.velocity == sim[2].master.velocity == 0.0
    assert sim[2].master.mapos == sim[1].master.mapos
    assert abs(sim[2].axis.profile.velocity) < 1e-9


@pytest.mark.parametrize(("nodes", "kwargs", "message"), [
    ([0, 1], {}, "node id 0 is outside 1..32"),
    ([1, 33], {}, "node id 33 is outside 1..32"),
    ([-4], {}, "node id -4 is outside 1..32"),
    ([1, 2, 2], {}, "node id 2 is given twice"),
    (["2"], {}, "node id '2' is not a whole number"),
    ([True], {}, "node id True is not a whole number"),
    ([], {}, "at least one node id"),
    ([1, 2], {"master_node": 3}, "master node id 3 is not one of the nodes"),
    ([1, 2], {"master_node": 40}, "node id 40 is outside 1..32"),
    (list(range(1, 34)), {}, "node id 33 is outside 1..32"),
])
def test_node_id_errors_name_the_id(nodes, kwargs, message):
    with pytest.raises(ValueError, match=message):
        Simulation(nodes, **kwargs)


def test_an_unknown_node_is_a_value_error_naming_it():
    sim = Simulation([1, 2])
    with pytest.raises(ValueError, match="node id 9 is not in this simulation"):
        sim[9]
    with pytest.raises(ValueError, match="node id 5"):
        sim.set_ticker(5, lambda: None)


# --- the comms side: EmbeddedBus (one Link per node, one clock) and `motiontool run --node` ------------------------
def test_embedded_bus_gives_every_node_a_link_on_one_clock():
    """DG 2404: controllers "that all share the same network connection, (e.g. in a field bus)"; every node has its
    own link with the ordinary requests; advancing any node's link advances all nodes together."""
    from motiontool.comms.protocol import LinkError
    from motiontool.controller.bus import EmbeddedBus

    bus = EmbeddedBus([1, 4], master_node=1)
    seen = {1: [], 4: []}
    for n in bus.nodes:
        bus.link(n).subscribe(lambda e, n=n: e.kind == "print" and seen[n].append(e.text))
    bus.link(4).write_parameter("SYNCFACTS", 3)
    for n, source in ((1, "PULSVEL 2500\nDELAY 500\nPRINT MAPOS\n"), (4, "SYNCV\nDELAY 500\nPRINT MAPOS\n")):
        result = compile_source(source, f"n{n}.m")
        bus.link(n).download(result.image.to_bytes())
        bus.link(n).start()
    bus.link(4).advance(600)
    assert bus.link(1).status().time_ms == bus.link(4).status().time_ms == 600
    assert seen[1] == seen[4] and seen[1] and int(seen[1][0]) > 0
    assert bus.link(4).read_parameter("SYNCFACTS") == 3 and bus.link(1).read_parameter("SYNCFACTS") == 1
    with pytest.raises(ValueError, match="node id 2 is not in this simulation"):
        bus.link(2)
    bus.close()
    with pytest.raises(LinkError):
        bus.link(1).status()


def test_cli_run_with_several_nodes(tmp_path):
    """`motiontool run master.m --node 2:slave.m`: node 1's PULSVEL is node 2's master; output lines carry the id."""
    import subprocess
    import sys

    (tmp_path / "m.m").write_text("PULSVEL 2500\nDELAY 1000\nPRINT \"master \", MAPOS\n")
    (tmp_path / "s.m").write_text("DELAY 1000\nPRINT \"slave \", MAPOS, \" \", GET SYNCFACTS\n")

    def run(*args):
        return subprocess.run([sys.executable, "-m", "motiontool", "run", *args], capture_output=True, text=True,
                              timeout=120, cwd=tmp_path)

    proc = run("m.m", "--node", "2:s.m", "--set", "2:SYNCFACTS=7", "--seconds", "3")
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert sorted(lines) == ["1: master 10000", "2: slave 10000 7"]  # 10 qc/ms, ticks 2..1001 (PRINT in 1001)
    proc = run("m.m", "--node", "33:s.m")
    assert proc.returncode == 1 and "node id 33 is outside 1..32" in proc.stderr
    proc = run("m.m", "--node", "1:s.m")
    assert proc.returncode == 1 and "node id 1 is given twice" in proc.stderr


# --- the markers fast path (benchmarks/kernel_rtf.py) -------------------------------------------------------------
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_markers_fast_path_latches_the_same_index_pulses_as_the_full_check(seed, monkeypatch):
    """The fast path of Markers.tick (no sensor, index-pulse markers 0/1, no marker sync) must not change what is
    latched: MIPOS / IPOS (CR 1767-1815, 2263-2310) every tick equal a controller that always runs the full check,
    with a jittering master going both ways and a slave positioning back and forth over several index pulses."""
    master = MasterConfig(table=((0, 30.0), (400, -25.0), (900, 3.0), (1400, 41.0)), jitter=5.0, seed=seed)
    program = ("VEL 100\nACC 100\nDEC 100\nmain:\nPOSA 9000\nPOSA -3000\nPOSA 4100\nGOTO main\n")
    settings = {"SYNCMTYPM": seed % 2, "SYNCMTYPS": (seed + 1) % 2, "ENCODER": 256}
    fast = load(Controller(master=master), program, settings)
    full = load(Controller(master=master), program, settings)
    monkeypatch.setattr(full.markers, "_quiet", lambda key: False)
    checks = []  # ticks on which the fast controller ran the full check
    channel_tick = fast.markers.master.tick
    monkeypatch.setattr(fast.markers.master, "tick", lambda *a: checks.append(1) or channel_tick(*a))
    for _ in range(3000):
        fast.tick()
        full.tick()
        assert (fast.markers.mipos(), fast.markers.ipos_qc()) == (full.markers.mipos(), full.markers.ipos_qc())
        assert fast.master.raw == full.master.raw and fast.axis.apos == full.axis.apos
    assert full.markers.master.latched_raw is not None and full.markers.slave.latched_raw is not None
    assert len(checks) < 1000  # the fast path took most ticks

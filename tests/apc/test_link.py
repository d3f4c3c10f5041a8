"""The APC answers the same Link requests as the MCO 305 (issue 19 item 9, docs/link-protocol.md)."""

import pytest

from motiontool.apc import ApcDrive, CTSyncLine
from motiontool.comms.protocol import LinkError
from motiontool.controller.apc_service import ApcService, embedded_apc_link


def test_identify_names_the_kind():
    link = embedded_apc_link()
    info = link.call("identify")
    assert info["kind"] == "APC" and info["pos_period_us"] == 1000 and info["protocol"] >= 1


def test_read_parameters_signals_and_drive_parameters_over_the_link():
    """The scope and watch read APC read parameters by number or alias ([48], APC_FB_POS, L7701-7875) and drive
    parameters by menu.parameter (#18.11, L4840)."""
    drive = ApcDrive()
    link = embedded_apc_link(drive)
    link.write_parameter("18.11", 25)
    assert link.read_parameter("#18.11") == 25 and drive.params[(18, 11)] == 25
    drive.APCSetRunMode(2)
    drive.APCSetPositionSetPoint(65536)
    drive.APCSelectReference(1)
    samples = []
    link.subscribe(lambda e: samples.append(e) if e.kind == "samples" else None)
    link.call("stream", signals=["APC_PROF_OUT_POS", "[48]", "1.11"], interval_ms=5)
    link.advance(600)
    assert link.read_parameter("APC_PROF_OUT_POS") == 65536 == link.read_parameter(117)
    assert link.call("read_signals", signals=["APC_POS_SETPOINT", 4]) == [65536, 1]
    values = [row for e in samples for row in e.data["values"]]
    assert values[-1][0] == 65536 and values[-1][2] == 1 and len(values) >= 100
    status = link.status()
    assert status.time_ms == 600 and status.cpos == 65536 and status.axend == 1
    with pytest.raises(LinkError, match="only through the APC calls"):
        link.write_parameter("48", 0)
    with pytest.raises(LinkError, match="no APC read parameter"):
        link.read_parameter("APC_NO_SUCH")


def test_program_ops_need_a_dpl_runtime():
    link = embedded_apc_link()
    with pytest.raises(LinkError, match="runs DPL programs"):
        link.start()


def test_arrays_of_the_program_host_for_the_array_editor():
    service = ApcService()
    service.arrays.append(("InArray%", [1, 2, 3]))
    link = embedded_apc_link()
    link.service = service
    assert link.call("list_arrays") == [{"index": 0, "name": "InArray%", "size": 3}]
    link.write_array(0, [7, 8])
    assert link.read_array(0) == [7, 8, 3]


def test_apc_errors_reach_the_link_as_events():
    """Table 4-11 codes as error events with 90.49's number (L2316-2324)."""
    drive = ApcDrive()
    link = embedded_apc_link(drive)
    events = []
    link.subscribe(events.append)
    drive.APCSetRunMode(2)
    drive.APCSelectReference(3)                   # size 0
    link.advance(3)
    assert [e.number for e in events if e.kind == "error"][:1] == [3]
    assert link.call("error_history")[0]["number"] == 3
    link.call("clear_error")
    assert drive.trip == "" and link.status().error == 0


def test_a_ctsync_node_service_advances_the_whole_line():
    drives = [ApcDrive(), ApcDrive()]
    line = CTSyncLine(drives)
    service = ApcService(drives[1], advance=line.tick)
    service.op_advance(10)
    assert drives[0].samples == drives[1].samples == 10


def test_a_ctsync_line_gives_every_node_a_link_on_one_clock():
    """§4.10 (L2058-2101): the nodes run in lockstep; advance on any node's link moves the whole line."""
    from motiontool.controller.apc_bus import ApcLineBus

    bus = ApcLineBus([ApcDrive(), ApcDrive(), ApcDrive()])
    bus.link(2).advance(25)
    assert [bus.link(n).status().time_ms for n in bus.nodes] == [25, 25, 25]
    assert all(d.samples == 25 for d in bus.line.drives)
    assert bus.link(3).call("identify")["kind"] == "APC"
    with pytest.raises(ValueError, match="not on the line"):
        bus.link(9)


def test_program_host_slices_before_each_pos_sample_and_publishes():
    """The DPL host runs Initial/Background between POS samples (docs/apc.md "Link") and reports through the
    service's publish."""
    from motiontool.comms.protocol import LinkEvent

    order = []

    class Host:
        publish = None

        def slice(self):
            order.append(("slice", drive.samples))

        def op_start(self, number=None, step=False):
            self.publish(LinkEvent("program", 0, "started"))

    drive = ApcDrive(pos_rate=2)                   # 0.5 ms: two samples per link millisecond
    link = embedded_apc_link(drive)
    link.service.attach_program(Host())
    events = []
    link.subscribe(events.append)
    link.start()
    link.advance(2)
    assert order == [("slice", 0), ("slice", 1), ("slice", 2), ("slice", 3)]
    assert [e.text for e in events] == ["started"]


def test_the_freeze_input_over_the_link():
    """L629-643 DIGIN0 (T10) is the SM-Applications freeze input: set_input 0 freezes now, schedule_input later;
    L1076 "Parameter 81.42 … must be set to 1 to enable the freeze hardware" (default 0, L8212)."""
    drive = ApcDrive()
    drive.APCEnableReferenceFreeze()
    drive.APCEnableFeedbackFreeze()
    drive.APCSetRunMode(1)
    link = embedded_apc_link(drive)
    link.advance(5)
    link.set_input(0, 1)
    link.advance(1)
    assert link.read_parameter("APC_RFSRC_FRZFLG") == 0 and link.read_parameter(42) == 0
    link.set_input(0, 0)
    link.write_parameter("81.42", 1)
    link.set_input(0, 1)
    link.advance(1)
    assert link.read_parameter("APC_RFSRC_FRZFLG") == 1 and link.read_parameter(42) == 1
    with pytest.raises(LinkError, match="DIGIN0"):
        link.set_input(3, 1)


def test_threaded_link_paces_the_apc_in_real_time():
    """The IDE's link runs the controller on its own thread at real time × factor (decision K10)."""
    import time

    drive = ApcDrive()
    link = embedded_apc_link(drive, realtime_factor=20.0)
    try:
        deadline = time.monotonic() + 10
        while link.status().time_ms < 200 and time.monotonic() < deadline:
            time.sleep(0.01)
        assert link.status().time_ms >= 200 and drive.samples >= 200
        assert link.call("identify")["kind"] == "APC"
    finally:
        link.close()


def test_polled_curves_are_time_stamped_with_the_apcs_clock():
    """Decision A76. The scope polls its curves with SYSVAR sys_clock (4119) for the time stamp; the APC refused it
    ("no APC read parameter [4119]"), so no polled curve ran on the APC."""
    link = embedded_apc_link()
    link.write_parameter("18.11", 50)
    link.advance(7)
    assert link.call("read_signals", signals=["18.11", "APC_FB_POS", "4119"]) == [50, 0, 7]

"""CTSync: drives in lockstep, the master's references one sample late on every node (seed 004 §4.10, §7.5-7.6)."""

import pytest

from motiontool.apc import ApcDrive, CTSyncLine
from motiontool.apc.intmath import UnsignedBottomWord, UnsignedTopWord


def make_line(nodes: int = 4):
    drives = [ApcDrive() for _ in range(nodes)]
    drives[0].params["81.06"] = 25            # master (L2063-2066)
    for d in drives[1:]:
        d.params["81.06"] = 26
    log = {i: [] for i in range(nodes)}
    state = {"counter": 0}

    def node_pos0(i, d):
        def pos0():
            ref1, _, aux, status = d.CTSyncGetSlaveReferences()
            log[i].append((ref1, aux, status))
            d.APCSetReferencePosition(UnsignedTopWord(ref1), UnsignedBottomWord(ref1), 0)
            if i == 0:                           # §7.5: the master also builds the virtual master and sends it
                state["counter"] += 700
                d.CTSyncSetMasterReferences(state["counter"], 0, 1)
        return pos0

    for i, d in enumerate(drives):
        d.APCSetReferenceSource(4)
        d.APCSetRunMode(1)
        d.pos0 = node_pos0(i, d)
    return CTSyncLine(drives), drives, log, state


def test_every_node_applies_the_same_one_sample_old_master_data():
    """L2080-2094 "The reference data is retrieved by the Slave(s), including the Master (if relevant), using the
    CTSyncGetSlaveReferences function block"; §7.5 "the master's references reaching every node one cycle late"."""
    line, drives, log, _ = make_line()
    line.run_ms(50)
    for i in range(4):
        assert log[i][0][2] == 0                      # nothing received yet in the first sample
        assert [r for r, _, _ in log[i][1:]] == [700 * k for k in range(1, 50)]
        assert all(status == 1 for _, _, status in log[i][1:])
    assert len({d.read(20) for d in drives}) == 1 and drives[0].read(20) == 700 * 49
    assert drives[2].params["91.17"] == 49


def test_injected_checksum_error_gives_status_minus_2_and_counts():
    """L3276-3281 status "-2 Checksum error in received data"; 91.18 counts invalid messages (L7925-7932)."""
    line, drives, log, _ = make_line(3)
    line.inject(10, "checksum")
    line.inject(20, "missing")
    line.run_ms(30)
    assert log[1][9][2] == -2 and log[1][9][0] == log[1][8][0]      # the old data stays
    assert log[1][19][2] == 0
    assert drives[1].params["91.18"] == 1 and drives[1].params["91.19"] == 1
    assert log[1][10][2] == 1


def test_nodes_must_share_the_pos_rate():
    """L2071 "All CTSync Master and Slave POS tasks must be set to the same update time (parameter #81.12)"."""
    with pytest.raises(ValueError, match="same POS rate"):
        CTSyncLine([ApcDrive(pos_rate=3), ApcDrive(pos_rate=4)])
    with pytest.raises(ValueError, match="8 on a 2-wire"):
        CTSyncLine([ApcDrive() for _ in range(9)])


def test_only_the_master_broadcasts():
    """L3262 "It may only be used on the Master" (USR_NOT_MASTER −2, L8028-8036)."""
    d = ApcDrive()
    assert d.CTSyncSetMasterReferences(1, 2, 3) == -2
    d.params["81.06"] = 25
    assert d.CTSyncSetMasterReferences(1, 2, 3) == 1


def test_a_four_wire_line_takes_16_nodes():
    """L2078 "8 nodes maximum for 2-wire and 16 nodes maximum for 4-wire before line repeaters are required"."""
    line = CTSyncLine([ApcDrive() for _ in range(16)], four_wire=True)
    line.run_ms(3)
    assert line.samples == 3
    with pytest.raises(ValueError, match="17 nodes: CTSync allows 16 on a 4-wire line without repeaters"):
        CTSyncLine([ApcDrive() for _ in range(17)], four_wire=True)
    with pytest.raises(ValueError, match=r"9 nodes: CTSync allows 8 on a 2-wire line without repeaters \(16 on a "
                                         r"4-wire line\)"):
        CTSyncLine([ApcDrive() for _ in range(9)])


def test_a_slave_that_changes_its_pos_rate_is_an_error_naming_it():
    """L2077 "All CTSync Master and Slave POS tasks must be set to the same update time (parameter #81.12)": a
    slave's REINIT to 2 ms on a 1 ms line stops the line with words naming the slave and both rates."""
    from motiontool.apc.ctsync import CTSyncRateError

    slave, master = ApcDrive(), ApcDrive()
    master.params["81.06"] = 25
    line = CTSyncLine([slave, master])
    line.run_ms(5)
    slave.params["81.12"] = 4
    slave.reinit()
    with pytest.raises(CTSyncRateError) as caught:
        line.run_ms(5)
    assert str(caught.value) == ("CTSync: node 1 runs its POS task every 2 ms (#81.12 = 4), the line every 1 ms "
                                 "(#81.12 = 3 on node 2, the master): all CTSync master and slave POS tasks must "
                                 "be set to the same update time")
    named = caught.value.describe([5, 8])                      # the command line's node ids
    assert named.startswith("CTSync: node 5 runs its POS task every 2 ms") and "on node 8, the master" in named

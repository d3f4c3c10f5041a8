"""The controller's object dictionary (kernel/objdict.py, docs/protocols/canopen.md)."""

from __future__ import annotations

import pytest

from motiontool.aposs.driver import compile_source
from motiontool.kernel import objdict
from motiontool.kernel.controller import Controller


def controller_with_arrays() -> Controller:
    c = Controller()
    result = compile_source("DIM a[3], b[300]\na[2] = -7\nb[300] = 9\n", "t.m")
    assert result.ok
    c.load(result.image)
    c.start()
    c.run_for(5)
    return c


def test_arrays_and_user_parameters_by_object():
    """CR 2042-2044: "SDO 0x2100 / 5 (= SDO with the first element of the first application array)"; decision N2:
    array k + 1 at 0x2100 + k, sub 1 its size, elements up to 250; 0x23FF the whole array (CR 2806); N3: 0x2201 sub 1
    is 19-00 (CR 1986)."""
    c = controller_with_arrays()
    assert objdict.read(c, 0x2100, 1) == 3 and objdict.read(c, 0x2100, 6) == -7
    assert objdict.read(c, 0x2101, 1) == 300 and objdict.read(c, 0x2101, 254) == 0     # element 250
    objdict.write(c, 0x2100, 7, 11)
    assert c.arrays.arrays[0].data == [0, -7, 11]
    with pytest.raises(objdict.ObjectError) as info:
        objdict.read(c, 0x2100, 8)                       # element 4 of a 3-element array
    assert info.value.code == objdict.ABORT_NO_DATA
    with pytest.raises(objdict.ObjectError) as info:
        objdict.read(c, 0x2102, 5)                       # there is no third array
    assert info.value.code == objdict.ABORT_NO_DATA
    with pytest.raises(objdict.ObjectError) as info:
        objdict.write(c, 0x2100, 1, 10)                  # the size is read-only
    assert info.value.code == objdict.ABORT_READ_ONLY
    whole = objdict.read(c, 0x23FF, 2)
    assert len(whole) == 1200 and whole[-4:] == (9).to_bytes(4, "little")
    objdict.write(c, 0x23FF, 1, (5).to_bytes(4, "little", signed=True) * 2)
    assert c.arrays.arrays[0].data == [5, 5, 11]
    objdict.write(c, 0x2201, 1, 1234)
    assert c.params.get(1900) == 1234 and objdict.read(c, 0x2000 + 1900, 0) == 1234


def test_parameters_keep_their_type_and_refuse_what_the_link_refuses():
    """Decision N1: parameter xx-yy at 0x2000 + xxyy with its own type; a read-only parameter aborts 0x06010002, a
    value outside the parameter's range 0x06090030 (as a link write, DG 7782-7795)."""
    c = Controller()
    assert objdict.find(0x2CBC, 0).datatype == "UNSIGNED32" and objdict.read(c, 0x2CBC, 0) == 30   # KPROP
    objdict.write(c, 0x2CBC, 0, 150)
    assert c.params.get("KPROP") == 150
    for index, value, code in ((0x2000 + 3450, 1, objdict.ABORT_READ_ONLY),      # 34-50 APOS
                               (0x2CBC, -1, objdict.ABORT_VALUE),                # KPROP is unsigned
                               (0x2CBC, 100_001, objdict.ABORT_VALUE)):          # above KPROP's maximum
        with pytest.raises(objdict.ObjectError) as info:
            objdict.write(c, index, 0, value)
        assert info.value.code == code
    assert objdict.encode(objdict.read(c, 0x2000 + 3450, 0), "INTEGER32") == bytes(4)
    with pytest.raises(objdict.ObjectError) as info:
        objdict.read(c, 0x2000 + 3299, 0)                # 32-99 does not exist
    assert info.value.code == objdict.ABORT_NO_OBJECT


def test_link_signals_and_process_data_by_object():
    """Decision N6: 0x2510 carries the link's signals in user units; N5: 0x2500 sub n is SYSVAR 4096 + n."""
    c = Controller()
    c.params.set("POSFACT_Z", 2, source="link")
    c.axis.apos = 1000
    assert objdict.read(c, 0x2510, objdict.SIGNAL_SUB["APOS"]) == c.uu(1000) == 500
    assert objdict.read(c, 0x2500, 1) == 1000 == objdict.read_sysvar(c, 0x01250001)
    c.run_for(70000)
    assert objdict.read(c, 0x2500, objdict.TIME_STAMP_SUB) == 70000 & 0xFFFF


def test_store_and_restore_parameters():
    """CiA 301 0x1010/0x1011 (decision N10): "save" keeps the values past a program end, "load" restores the
    defaults."""
    c = Controller()
    c.params.set("KPROP", 99)                                  # a program's SET: reverts at the program end
    objdict.write(c, 0x1010, 1, 0x65766173)
    c.params.restore()
    assert c.params.get("KPROP") == 99
    with pytest.raises(objdict.ObjectError):
        objdict.write(c, 0x1011, 1, 1)
    objdict.write(c, 0x1011, 1, 0x64616F6C)
    assert c.params.get("KPROP") == 30


def test_codec_round_trips_every_integer_type():
    for name, (_, size, signed) in objdict.DATATYPES.items():
        if not size:
            continue
        low, high = (-(1 << (8 * size - 1)), (1 << (8 * size - 1)) - 1) if signed else (0, (1 << (8 * size)) - 1)
        for value in (low, high, 0):
            assert objdict.decode(objdict.encode(value, name), name) == value
    assert objdict.decode((200).to_bytes(4, "little"), "UNSIGNED8") == 200   # an MCO's 4-byte SDOWRITE
    with pytest.raises(objdict.ObjectError):
        objdict.decode((300).to_bytes(4, "little"), "UNSIGNED8")

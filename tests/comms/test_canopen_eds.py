"""The shipped EDS (resources/eds/mco305.eds) is the controller's dictionary, readable by python-canopen."""

from __future__ import annotations

import canopen

from motiontool.comms.canopen.objects import eds_path
from motiontool.controller.canopen import eds
from motiontool.kernel import objdict


def test_the_shipped_eds_is_the_dictionary_and_python_canopen_reads_it():
    """Issue 15 item 1: the dictionary "shipped as an EDS in resources/ that third-party CANopen tools load";
    decisions N1 (parameters at 0x2000 + number) and N8 (identity)."""
    shipped = eds_path().read_text()
    assert shipped == eds.eds_text(), \
        "regenerate: python -m motiontool.controller.canopen.eds > resources/eds/mco305.eds"
    od = canopen.import_od(str(eds_path()), 3)
    assert set(eds.dictionary()) == {obj.index for obj in od.values()}
    kprop = od[0x2000 + 3260]
    assert kprop.name == "32-60 KPROP" and kprop.data_type == canopen.objectdictionary.UNSIGNED32
    assert kprop.default == 30 and kprop.writable and od[0x2000 + 3450].access_type == "ro"
    assert od[0x1800][1].default == 0x183 and od[0x1801][1].default == 0x80000283
    assert od[0x1018][2].default == 305 and od[0x1018][4].default == 3
    assert od[0x2100][5].data_type == canopen.objectdictionary.INTEGER32           # CompactSubObj: element 1
    assert od[0x2500][1].name == "REG_ACTPOS" and od[0x5F00].data_type == canopen.objectdictionary.DOMAIN
    mappable = [(o.index, o.subindex) for o in (od[0x2500][6], od[0x2510][1], od[0x2CBC])]
    assert all(od[i] if not s else od[i][s] for i, s in mappable)
    assert all(objdict.find(i, s).mappable for i, s in mappable)

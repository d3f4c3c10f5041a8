"""The simulators are link schemes the composition root registers (decision N56, issue 27 item 3): the IDE's side
(comms/) does not know them by itself and never imports the controller's side."""

from __future__ import annotations

import subprocess
import sys

import pytest

from motiontool.comms.links import open_link, parse_link_spec, scheme_help
from motiontool.comms.protocol import LinkError

PROBE = """
import sys
from motiontool.comms.links import open_link
from motiontool.comms.protocol import LinkError
try:
    open_link("sim")
except LinkError as exc:
    print("refused:", exc)
print(sorted(m for m in sys.modules if m.startswith(("motiontool.controller", "motiontool.kernel"))))
from motiontool.controller import schemes
schemes.register()
link = open_link("sim")
print("opened:", link.identify().product)
"""


def test_comms_alone_knows_no_simulator_and_imports_no_controller():
    out = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True, timeout=60, check=True).stdout
    lines = out.splitlines()
    assert lines[0] == ("refused: link 'sim': the simulators are not registered in this program; call "
                        "motiontool.controller.schemes.register() first, as the motiontool command does")
    # the FC 300 parameter table is the one pure-data module of the kernel package the FC master reads
    assert lines[1] == "['motiontool.kernel', 'motiontool.kernel.fc300_table']"
    assert lines[2] == "opened: MCO 305 (simulated)"


@pytest.mark.parametrize(("spec", "kind"), [("sim,realtime=50", "MCO"), ("apcsim,realtime=50", "APC")])
def test_the_registered_simulators_open_paced(spec: str, kind: str):
    link = open_link(spec)
    try:
        assert link.identify().kind == kind
        assert link.realtime_factor == 50.0   # paced (the IDE's simulators), not virtual time
    finally:
        link.close()


def test_the_help_names_the_simulators_once():
    text = scheme_help()
    assert text.count("sim (the embedded simulated controller") == 1
    assert text.count("apcsim[,realtime=F]") == 1


def test_an_unknown_scheme_is_named_with_the_known_ones():
    with pytest.raises(LinkError, match=r"^link 'simx': unknown scheme 'simx' \(known: apcsim, canopen, fc, sim"):
        open_link(parse_link_spec("simx"))

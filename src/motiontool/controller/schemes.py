"""The simulators as link schemes: `sim` (a simulated MCO 305 in this process) and `apcsim` (a simulated APC with
its DPL host), opened with `open_link` exactly as drives are (issue 27 item 3).

The IDE's side (comms/, the UI) knows only `open_link`; the composition root (the `motiontool` command, a headless
run, a sweep's worker, a test session) calls `register()` once, so the client side never imports the controller's.
"""

from __future__ import annotations

from motiontool.comms.link import Link
from motiontool.comms.links import MAX_REALTIME, LinkSpec, LinkSpecError, register_link_scheme
from motiontool.comms.protocol import LinkError


def _open_sim(spec: LinkSpec) -> Link:
    """`sim[,realtime=F]`: a simulated controller in this process (embedded.py); virtual time without realtime."""
    from motiontool.controller.embedded import EmbeddedLink

    spec.check_options({"realtime"})
    if spec.target:
        raise LinkSpecError(f"link '{spec.text}': sim takes no target")
    realtime = spec.option("realtime", 0.0, float, 0, MAX_REALTIME)
    return EmbeddedLink(realtime_factor=realtime or None)


def _open_apcsim(spec: LinkSpec) -> Link:
    """`apcsim[#1][,realtime=F]`: the embedded simulated APC with its DPL host (one controller, number 1)."""
    from motiontool.controller.dpl_program import dpl_link

    spec.check_options({"realtime"})
    if spec.target or spec.node not in (None, 1):
        raise LinkError(f"link '{spec.text}': the APC simulator is one controller (apcsim or apcsim#1)")
    return dpl_link(realtime_factor=spec.option("realtime", None, float, 0, MAX_REALTIME) or None)  # 0: virtual


def register() -> None:
    """Make `sim` and `apcsim` links open simulators (again: registering twice changes nothing)."""
    register_link_scheme("sim", _open_sim, "sim", "the embedded simulated controller, the default")
    register_link_scheme("apcsim", _open_apcsim, "apcsim[,realtime=F]",
                         "the embedded simulated APC that runs DPL programs",
                         scan=lambda spec, ids: [n for n in ids if n == 1])

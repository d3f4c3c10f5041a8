"""The controller's side of the link protocol (issue 27 item 3): what answers the IDE's requests.

The services that run requests on a simulated MCO 305 (`service.py`) or APC (`apc_service.py`, `dpl_program.py`),
the embedded host that puts a service behind a Link in this process (`embedded.py`, `bus.py`, `apc_bus.py`), and
the virtual drive: simulated controllers in their own process (`drive/`) behind the FC protocol (`fc/server.py`)
and CANopen (`canopen/`). The IDE's side (`comms/`, the UI, the scope and editors) never imports this package: it
opens a simulator as it opens a drive, with `open_link("sim")`, once the composition root (the `motiontool`
command, a test session) has called `schemes.register()`.
"""

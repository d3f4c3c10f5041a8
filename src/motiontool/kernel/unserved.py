"""Commands whose device the simulation does not have, answered as the manual says a controller answers when the
device does not reply (aposs/simulated.py lists them; `check` warns about them).

ENCTGWRITE/ENCTGREAD (and the master encoder's MENCTG…) talk to a Hiperface encoder on the RS485 line (CR
1232-1302): the telegram is "sent" (0), a second one within 300 ms is BUSY (-3), the answer is ACTIVE (0) until
300 ms have passed and then TIMEOUT (-1). ENCPOSOFFS/MENCPOSOFFS wait those 300 ms for the same encoder and
return TIMEOUT.
"""

from __future__ import annotations

from motiontool.kernel.command_base import COMMANDS, Until

TELEGRAM_TIMEOUT_MS = 300   # "No answer has been received within 300ms" (CR 1239)
ACTIVE, TIMEOUT, BUSY = 0, -1, -3


def _telegram_commands(prefix: str) -> None:
    def sent_at(ctl) -> dict:
        return vars(ctl.program_data).setdefault("encoder_telegrams", {})   # forgotten at the next start

    def write(ctl, vm, args):
        sent = sent_at(ctl)
        last = sent.get(prefix)
        if last is not None and ctl.time_ms - last < TELEGRAM_TIMEOUT_MS:
            return BUSY
        sent[prefix] = ctl.time_ms
        return 0

    def read(ctl, vm, args):
        last = sent_at(ctl).get(prefix)
        if last is not None and ctl.time_ms - last < TELEGRAM_TIMEOUT_MS:
            return ACTIVE
        return TIMEOUT

    COMMANDS[f"{prefix}TGWRITE"] = write
    COMMANDS[f"{prefix}TGREAD"] = read


_telegram_commands("ENC")
_telegram_commands("MENC")


def _position_offset(ctl, vm, args):
    """ENCPOSOFFS/MENCPOSOFFS (CR 1178-1231, 2197-2217) ask the Hiperface encoder for its absolute position: with
    no encoder on the line nothing answers, so after 300 ms the result is TIMEOUT (-1) and `offset` is left as it
    was (K123)."""
    end = ctl.time_ms + TELEGRAM_TIMEOUT_MS
    return Until(lambda: ctl.time_ms >= end, value=TIMEOUT)


COMMANDS["ENCPOSOFFS"] = COMMANDS["MENCPOSOFFS"] = _position_offset

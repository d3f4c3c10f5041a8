"""The simulated FC 300's own parameters as GETVLT/SETVLT(SUB) reach them (CR 1387-1428, 4009-4053): number,
name, range, default and conversion index. docs/fc300.md is the readable copy of this table with its sources.

A value crosses as an integer scaled by 10^-conversion index: 16-13 "50.0 Hz" (index -1) reads 500 (CR 1394-1396),
3-03 = 60 Hz is written as 60000 (index -3, CR 4025-4027). Index 67 marks RPM and 100 °C; both scale by 1.

Sources (key → where):
  CR/DG n    the seeds: MCO 305 Command Reference / Design Guide line n; "DG 7665-7690" is the list of FC 300
             parameters whose selections and defaults the MCO 305 changes.
  PG301      VLT AutomationDrive FC 301 Programming Manual, 3.6.1 "4-1* Motor Limits" (manualarchiveguide.com,
             Danfoss-VLT-AutomationDrive-FC-301-Programming-Manual-2997747, page 72): 4-10 selections, 4-11..4-14
             ranges.
  FCDG       FC 300 Design Guide (MG.33.B6/BC): conversion table and 4-12 factor 0.1 (manualshive.com 507599 page
             255); 4-14 written as 1000 = 100 Hz, 3-41 index -2 Uint32 (manualarchiveguide.com 2997341 page 238);
             16-14 read as current x 100 (manualarchiveguide.com 2997340 page 288).
  assumed    not found in a public source within reach: a plausible value for a 4-pole 50 Hz motor on a 400 V FC 302
             ("size related" in the guide means it depends on the drive; the simulated drive is one such drive).
"""

from __future__ import annotations

from dataclasses import dataclass

RPM, CELSIUS = 67, 100   # conversion indices that name a unit and scale by 1


@dataclass(frozen=True)
class FCParam:
    number: int            # 4-13 → 413, 16-13 → 1613: as GETVLT takes it (CR 1405 "GETVLT 413")
    name: str
    low: int               # transferred integers (already scaled by the conversion index)
    high: int
    default: int
    conversion: int = 0
    size: int = 0          # array elements for the SUB forms; 0 = not indexed
    low_par: int = 0       # the range ends at another parameter's value ("par. 4-11 - 60000 RPM", PG301)
    high_par: int = 0
    read_only: bool = False  # DG 7594: "Parameter groups 16-** and 34-** are read only"
    source: str = "assumed"

    @property
    def label(self) -> str:
        return f"{self.number // 100}-{self.number % 100:02d}"


def factor(conversion: int) -> float:
    """The conversion factor of an index (FCDG conversion table); the unit indices scale by 1."""
    return 1.0 if conversion in (RPM, CELSIUS) else 10.0 ** conversion


_ANY_OPTION = (0, 255)   # the selection lists are long; the simulation accepts any option number (assumed)
_BIG = 999_999_999       # ±999999.999 at index -3 (assumed from the LCP's 6+3 digits)

_TABLE = [
    # --- 0-** operation/display
    FCParam(25, "My Personal Menu", 0, 9999, 0, size=20,
            source="CR 4047 (index 1 set to 100); range 0-9999 parameter numbers and default assumed"),
    # --- 1-** load and motor: the motor data; the simulated plant does not use them (no electrical model)
    FCParam(120, "Motor Power [kW]", 9, 100_000, 400, conversion=1, source="assumed (4.0 kW)"),
    FCParam(122, "Motor Voltage", 10, 1000, 400, source="assumed"),
    FCParam(123, "Motor Frequency", 20, 1000, 50, source="assumed"),
    FCParam(124, "Motor Current", 1, 1_000_000, 820, conversion=-2,
            source="number and name CR 1390; index -2 and 8.20 A assumed"),
    FCParam(125, "Motor Nominal Speed", 100, 60000, 1420, conversion=RPM, source="assumed"),
    FCParam(139, "Motor Poles", 2, 100, 4, source="assumed"),
    # --- 3-** reference/ramps
    FCParam(300, "Reference Range", 0, 1, 0, source="assumed ([0] Min - Max)"),
    FCParam(302, "Minimum Reference", -_BIG, _BIG, 0, conversion=-3, high_par=303, source="index -3 as 3-03; assumed"),
    FCParam(303, "Maximum Reference", -_BIG, _BIG, 1_500_000, conversion=-3, low_par=302,
            source="name CR 1390, index -3 CR 4025-4027; default 1500.000 assumed"),
    *(FCParam(n, f"Ramp {r} Ramp {d} Time", 1, 360_000, 1, conversion=-2,
              source="default 0.01 s DG 7672-7676 (MCO 305); index -2 FCDG (3-41); range 0.01-3600 s assumed")
      for r, up, down in ((1, 341, 342), (2, 351, 352), (3, 361, 362), (4, 371, 372))
      for n, d in ((up, "Up"), (down, "Down"))),
    # --- 4-** limits/warnings
    FCParam(410, "Motor Speed Direction", 0, 2, 2, source="selections PG301; default [2] Both directions DG 7677"),
    FCParam(411, "Motor Speed Low Limit [RPM]", 0, 60000, 0, conversion=RPM, high_par=413,
            source="range PG301; default assumed"),
    FCParam(412, "Motor Speed Low Limit [Hz]", 0, 10000, 0, conversion=-1, high_par=414,
            source="range PG301, index -1 FCDG; default assumed"),
    FCParam(413, "Motor Speed High Limit [RPM]", 0, 60000, 1500, conversion=RPM, low_par=411,
            source="name CR 1405, range PG301; default 1500 RPM assumed"),
    FCParam(414, "Motor Speed High Limit [Hz]", 0, 10000, 500, conversion=-1, low_par=412, high_par=419,
            source="range PG301, index -1 FCDG (1000 = 100 Hz); default 50.0 Hz assumed"),
    FCParam(416, "Torque Limit Motor Mode", 0, 10000, 1600, conversion=-1, source="assumed (160 %)"),
    FCParam(417, "Torque Limit Generator Mode", 0, 10000, 1600, conversion=-1, source="assumed (160 %)"),
    FCParam(418, "Current Limit", 10, 10000, 1600, conversion=-1, source="assumed (160 %)"),
    FCParam(419, "Max Output Frequency", 10, 10000, 1320, conversion=-1, source="assumed (132.0 Hz)"),
    # --- 5-** digital in/out: the MCO 305 defaults (DG 7678-7684)
    *(FCParam(n, f"Terminal {t} Digital Input", *_ANY_OPTION, 0, source="default [0] No operation DG 7678")
      for n, t in ((510, 18), (511, 19), (512, 27), (513, 29))),
    FCParam(530, "Terminal 27 Digital Output", *_ANY_OPTION, 51, source="default [51] MCO controlled DG 7679"),
    FCParam(531, "Terminal 29 Digital Output", *_ANY_OPTION, 51, source="default [51] MCO controlled DG 7679"),
    FCParam(540, "Function Relay", *_ANY_OPTION, 51, size=2,
            source="name CR 1423, default [51] MCO controlled DG 7680; 2 relays (FC 302) assumed"),
    # --- 8-** communication
    FCParam(802, "Control Word Source", *_ANY_OPTION, 5, source="default [5] Option C0 DG 7683, DG 11534"),
    FCParam(810, "Control Word Profile", *_ANY_OPTION, 0, source="[0] FC profile, FCDG control word page"),
    # --- 16-** data readouts: read only (DG 7594); their values are computed by kernel/fc300.py
    FCParam(1600, "Control Word", 0, 0xFFFF, 0, read_only=True, source="FCDG control word (FC profile)"),
    FCParam(1601, "Reference [Unit]", -_BIG, _BIG, 0, conversion=-3, read_only=True, source="index assumed as 3-03"),
    FCParam(1602, "Reference %", -2000, 2000, 0, conversion=-1, read_only=True, source="assumed"),
    FCParam(1603, "Status Word", 0, 0xFFFF, 0, read_only=True, source="FC profile status word (docs/fc300.md)"),
    FCParam(1610, "Power [kW]", -_BIG, _BIG, 0, conversion=1, read_only=True, source="number DG 7626; index assumed"),
    FCParam(1612, "Motor Voltage", 0, 10000, 0, conversion=-1, read_only=True, source="assumed"),
    FCParam(1613, "Frequency", 0, 65535, 0, conversion=-1, read_only=True, source="index -1 CR 1394-1396"),
    FCParam(1614, "Motor Current", 0, _BIG, 0, conversion=-2, read_only=True, source="x 100 FCDG page 288"),
    FCParam(1616, "Torque [Nm]", -_BIG, _BIG, 0, conversion=-1, read_only=True, source="assumed"),
    FCParam(1617, "Speed [RPM]", -_BIG, _BIG, 0, conversion=RPM, read_only=True, source="assumed"),
    FCParam(1622, "Torque [%]", -32768, 32767, 0, read_only=True, source="assumed"),
    FCParam(1630, "DC Link Voltage", 0, 10000, 565, read_only=True, source="assumed (400 V mains x 1.41)"),
]

FC_PARAMETERS: dict[int, FCParam] = {p.number: p for p in _TABLE}


def link_number(key) -> int | None:
    """The FC 300 parameter a link names as "4-13" (the LCP's form), or None: the MCO 305's own groups 19, 32, 33
    and 34 are the controller's parameters, not the drive's."""
    group, dash, number = str(key).strip().partition("-")
    if not (dash and group.isdigit() and number.isdigit()) or int(group) in (19, 32, 33, 34):
        return None
    return int(group) * 100 + int(number) if int(number) < 100 else None

"""What TESTSETP records (DG 7121-7135: "TESTSTART n … n = 0 The max. number of samples is recorded, which fits
into the defined memory section", "TESTSETTYPE type: 0 = one time recording 1 = cyclic recording"), fingerprinted
so a change in how the recorder samples shows: every recording's list entry and upload, the arrays and the errors of
each program, and a Single Shot recording beside a TESTSETP one (DG 4668: it records "in a TESTSETP array").
The goldens are the recordings before TESTSETP moved onto the common sampler (decision S34)."""

import hashlib

from .helpers import run_source, start

MOVE = "VEL 100\nACC 100\nDEC 100\n"
SDO_INDICES = "0x01250001, 0x01250006, 0x01220202, 0x01220101"  # SDO-style, inputs, user parameter 19-00

PROGRAMS = {
    # stop when full into an array, 1 ms
    "array_1ms_once": f"DIM t[3000]\n{MOVE}TESTSETP 1 4097 4098 4102 t\nTESTSTART 400\nPOSA 20000\nDELAY 200\n",
    # cyclic, 3 ms, "fill available space" of a small array (20 sets), stopped by TESTSTOP 0
    "array_3ms_cyclic": f"DIM t[60]\n{MOVE}TESTSETP 3 4097 4119 4102 t\nTESTSETTYPE 1\nTESTSTART 0\n"
                        "POSA 30000\nDELAY 300\nTESTSTOP 0\nDELAY 50\n",
    # TESTSETINDEX with ten indices into dynamic memory every 7 ms; then a cyclic one the program's end stops
    "dynmem_7ms_index": f"{MOVE}TESTSETINDEX 4097, 4098, 4099, 4100, 4101, 4102, 4119, {SDO_INDICES}\n"
                        "TESTSETTIME 7\nTESTSETDEST DYNMEM\nTESTSTART 50\nPOSA 40000\nDELAY 500\n"
                        "TESTSETTYPE 1\nTESTSETTIME 1\nTESTSETINDEX 4119, 4098\nTESTSTART 30\nPOSA 0\nDELAY 200\n",
    # 7 ms into a 7-set array, restarted while it runs, then a one-index recording over the same array
    "array_7ms_restart": f"DIM s[21]\n{MOVE}TESTSETP 7 4097 4098 4119 s\nTESTSTART 0\nDELAY 30\nTESTSTART 3\n"
                         "POSA 5000\nDELAY 100\nTESTSETINDEX 4119\nTESTSETTYPE 1\nTESTSTART 0\nDELAY 100\n",
    "error_183_no_indices": "TESTSTART 10\n",
    "error_183_stop_method": "TESTSETINDEX 4119\nTESTSTART 10\nDELAY 20\nTESTSTOP 1\n",
    "error_195_21_indices": "TESTSETINDEX " + ", ".join(str(4097 + i) for i in range(21)) + "\n",
    "error_171_array_small": "DIM t[10]\nTESTSETP 1 4097 4098 4102 t\nTESTSTART 5\n",
    "error_194_dynmem_full": "TESTSETINDEX 4097\nTESTSETDEST DYNMEM\nTESTSTART 300000\n",
    "error_194_dynmem_twice": "TESTSETINDEX 4097\nTESTSTART 100\nDELAY 20\nTESTSTART 100\n",
}

GOLDEN = {
    "array_1ms_once": "cdf90870ca007285",
    "array_3ms_cyclic": "2bae9f8deecbb51b",
    "dynmem_7ms_index": "4175c6e9ba3140e0",
    "array_7ms_restart": "ba871753e5f9239e",
    "error_183_no_indices": "ead554fb36afbf95",
    "error_183_stop_method": "40109a6bf5fdcb59",
    "error_195_21_indices": "2fd5fe897e4a1dea",
    "error_171_array_small": "f78e0ca4665ec6d7",
    "error_194_dynmem_full": "e15cfd1a269c08e3",
    "error_194_dynmem_twice": "b9efc5737e7f41e8",
    "single_shot_beside_testsetp": "a91b61d7ab2ef52d",
}


def fingerprint(run, extra=()) -> str:
    link = run.link
    listed = link.call("list_recordings")
    uploads = [link.call("upload_recording", index=i) for i in range(len(listed))]
    arrays = [(a.name, list(a.data)) for a in run.controller.arrays.arrays]
    errors = [(e.number, e.time_ms) for e in run.errors]
    seen = repr((listed, uploads, arrays, errors, run.prints, list(extra)))
    return hashlib.sha256(seen.encode()).hexdigest()[:16]


def test_testsetp_recordings_match_their_fingerprints():
    got = {name: fingerprint(run_source(source, 2000)) for name, source in PROGRAMS.items()}
    assert got == {name: GOLDEN[name] for name in PROGRAMS}


def test_single_shot_beside_testsetp_matches_its_fingerprint():
    """A cyclic Single Shot every 3 ms into one array while the program's TESTSETP records every 7 ms into another."""
    run = start(f"DIM a[300]\nDIM b[90]\n{MOVE}TESTSETP 7 4097 4098 4119 a\nTESTSTART 0\nPOSA 20000\nDELAY 600\n")
    run.advance(5)
    run.link.call("start_recording", signals=["APOS", "CVEL", "4119"], interval_ms=3, destination="b",
                  cyclic=True, count=0)
    run.advance(400)
    shot = run.link.call("stop_recording")
    assert fingerprint(run, [shot]) == GOLDEN["single_shot_beside_testsetp"]

"""Readouts and arrays of issue 25 that ended with error 110: the ...DIFF overflow helpers, DELETE ARRAYS."""

from motiontool.kernel.master import MasterConfig

from .helpers import run_source

# (MAPOS - 2147483392) is a stored position 0x7FFFFF00 qc behind: beyond POS_LIMIT, so an overflow is assumed
OVERFLOW = 2147483392 - 0x80000000   # = -256


def test_iposdiff_is_ipos_minus_the_old_position_and_handles_an_overflow():
    # CR 1822: "Returns difference between IPOS and oldpos (res = IPOS – oldpos) in UU"; CR 1826-1828: "if the
    # difference is bigger than POS_LIMIT (0x3FFFFFFF). If so then it is assumed that an overflow happened"
    run = run_source("POSA 1000\nPRINT IPOS, \" \", IPOSDIFF (-5), \" \", IPOSDIFF (IPOS - 2147483392)\n", 5000)
    assert run.prints == [f"0 5 {OVERFLOW}"]     # IPOS, not APOS (1000)


def test_maposdiff_is_mapos_minus_the_old_position_and_handles_an_overflow():
    # CR 2156: "Returns difference between MAPOS and oldpos (res = MAPOS – oldpos) in UU"; CR 2161-2163 (POS_LIMIT)
    run = run_source("DELAY 100\nm = MAPOS\nPRINT m > 0, \" \", MAPOSDIFF (m - 7), \" \", "
                     "MAPOSDIFF (m - 2147483392)\n", 1000, master=MasterConfig(velocity=0.0, start_position_qc=4000))
    assert run.prints == [f"1 7 {OVERFLOW}"]


def test_miposdiff_is_mipos_minus_the_old_position_and_handles_an_overflow():
    # CR 2320: "Returns difference between MIPOS and oldpos (res = MIPOS – oldpos) in UU"; CR 2325-2327 (POS_LIMIT)
    run = run_source("DELAY 100\nPRINT MIPOS, \" \", MIPOSDIFF (-9), \" \", MIPOSDIFF (MIPOS - 2147483392)\n",
                     1000, master=MasterConfig(velocity=5.0))
    assert run.prints == [f"0 9 {OVERFLOW}"]     # MIPOS (no marker yet), not MAPOS (about 500)


def test_array_elements_cannot_be_accessed_after_delete_arrays():
    # CR 1003-1005: "If DELETE ARRAYS is carried out after a DIM assignment in the program, it is then no longer
    # possible to access the array elements"; DG 11718-11721 error 171 "Array too small": "An attempt was made to
    # describe an array element that is located outside of the defined array limits" (decision K119)
    run = run_source("DIM a[3]\na[1] = 5\nPRINT a[1]\nDELETE ARRAYS\nPRINT a[1]\n", 1000)
    assert run.prints == ["5"]
    assert [(e.number, e.line) for e in run.errors] == [(171, 5)]
    assert run.controller.arrays.arrays == []

"""The DPL front end's tables agree with the APC kernel's: every definition has the kernel's value, every
built-in function the checker accepts is a call the kernel runs with the same arguments and results."""

from __future__ import annotations

from motiontool.apc import ALIASES, READ_PARAMETERS, SIGNATURES
from motiontool.dpl.definitions import definitions, read_parameter_names
from motiontool.dpl.functions import function_table

# Functions the language runs itself (the checker also accepts calls marked `simulated = false`: the CTSync output
# channels of §8.2, documented in the SM-Applications manual; it warns, and the runtime stops there).
LANGUAGE = {"IWINDOW"}


def test_definitions_are_the_kernels_aliases():
    assert {d.name: d.value for d in definitions().values()} == ALIASES


def test_read_parameter_names_are_the_kernels():
    assert read_parameter_names() == {p.number: p.alias for p in READ_PARAMETERS.values() if p.alias}


def test_every_function_is_a_kernel_call_with_the_same_arguments_and_results():
    kernel = {name.upper(): sig for name, sig in SIGNATURES.items()}
    mismatches = []
    for key, fn in function_table().items():
        if key in LANGUAGE or not fn.simulated:
            continue
        sig = kernel.get(key)
        if sig is None:
            mismatches.append(f"{fn.name}: not a kernel call")
            continue
        outputs = len(sig.outputs) + (1 if sig.quick_status else 0)
        if len(sig.args) != len(fn.args) or outputs != len(fn.returns):
            mismatches.append(f"{fn.name}: {len(fn.args)} args, {len(fn.returns)} results here; kernel "
                              f"{len(sig.args)} args, {outputs} results")
    assert mismatches == []
    missing = sorted(sig.name for key, sig in kernel.items() if key not in function_table())
    assert missing == []


def test_calls_the_kernel_does_not_simulate_are_the_ctsync_output_channels():
    assert sorted(fn.name for fn in function_table().values() if not fn.simulated) == [
        "CTSyncEnableOutputChannel", "CTSyncSetupOutputChannel", "CTSyncWriteOutputChannel"]

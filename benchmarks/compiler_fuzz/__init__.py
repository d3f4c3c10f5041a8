"""The APOSS compiler fuzzer's generators and properties, shared by benchmarks/fuzz_compiler.py (the runner),
benchmarks/fuzz_files.py and tests/aposs/test_fuzz.py.

vocabulary   the words and the helpers over ``r`` (a ``random.Random``-like object)
tokens       generators 1, 2 and 5: token_stream, mutated_example, deep_nesting
expressions  the names in scope and the expressions of generated programs
programs     generators 3 and 4: valid_program, semantic_soup
chaos        the wrong values, statements and parts of semantic_soup
properties   check_compile and crash_site
"""

from __future__ import annotations

from .programs import ProgramGenerator, semantic_soup, valid_program
from .properties import PropertyViolation, check_compile, check_compile_once, crash_site, last_frames
from .tokens import TOKEN_RE, deep_nesting, mutate, mutated_example, token_stream
from .vocabulary import EXAMPLES_DIR, INPUT_PATH, REPO

# name: (generator, share of the benchmark's cases in per mille)
GENERATORS = {
    "token_stream": (token_stream, 400),
    "mutated_example": (mutated_example, 345),
    "semantic_soup": (semantic_soup, 150),
    "valid_program": (valid_program, 100),
    "deep_nesting": (deep_nesting, 5),
}


__all__ = ["EXAMPLES_DIR", "GENERATORS", "INPUT_PATH", "REPO", "TOKEN_RE", "ProgramGenerator", "PropertyViolation",
           "check_compile", "check_compile_once", "crash_site", "deep_nesting", "last_frames", "mutate",
           "mutated_example", "semantic_soup", "token_stream", "valid_program"]

"""The entry point of the unittest files here that drive the `sheetgen` CLI:
`--sheetgen PATH` (required; ctest passes the build's) sets the module's
SHEETGEN, the other arguments go to unittest."""
import argparse
import os
import sys
import unittest


def run_with_sheetgen(module):
    """Runs the tests of `module` (the __main__ module, whose SHEETGEN is set
    first) verbosely; returns the unittest result."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--sheetgen", required=True)
    args, rest = ap.parse_known_args()
    module.SHEETGEN = os.path.abspath(args.sheetgen)
    return unittest.main(module=module, argv=[sys.argv[0]] + rest, exit=False, verbosity=2).result

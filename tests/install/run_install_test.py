"""Runs one test of tests/install (MODULE.CLASS.METHOD) for ctest: exit 0 passed, 1 failed,
77 skipped (ctest's SKIP_RETURN_CODE), so a skip never reads as a pass."""
import os
import sys
import unittest

SKIPPED = 77

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
suite = unittest.defaultTestLoader.loadTestsFromName(sys.argv[1])
result = unittest.TextTestRunner(verbosity=2).run(suite)
if not result.wasSuccessful():
    sys.exit(1)
sys.exit(SKIPPED if result.skipped and len(result.skipped) == result.testsRun else 0)

"""Runs a test script's test_* functions in order, printing each, for ctest (no pytest needed)."""
import sys


def run_tests(namespace):
    for name, fn in list(namespace.items()):
        if name.startswith("test_") and callable(fn):
            fn()
            print(f"{name}: passed")
    sys.exit(0)

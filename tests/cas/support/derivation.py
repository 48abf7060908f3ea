"""What every re-derivation script in tests/cas shares: a list of failures, the two
checks that add to it, and the ending that prints them and sets the exit code (CTest,
label book, fails the script on any mismatch)."""
import sys

import sympy as sp

failures = []


def same(name, left, right):
    """Records a failure unless left - right simplifies to zero."""
    difference = sp.simplify(left - right)
    if difference != 0:
        failures.append(f"{name}: {difference} != 0")


def holds(name, condition):
    """Records a failure unless condition is true."""
    if not condition:
        failures.append(name)


def finish(script):
    """Prints every failure, prefixed by the script's name, and exits 1 if there was one."""
    for failure in failures:
        print(f"{script}: {failure}")
    sys.exit(1 if failures else 0)

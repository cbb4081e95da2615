"""The pass/fail count shared by the tools' self-tests (tools/test_*.py, run by ctest): check()
counts a check and prints a FAIL line with its detail; summary() prints "N passed, M failed" and
returns the exit code (1 on any failure)."""

passed = failed = 0


def check(name, condition, detail=None):
    global passed, failed
    if condition:
        passed += 1
    else:
        failed += 1
        print(f"FAIL: {name}" + ("" if detail is None else f" ({detail})"))


def summary():
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0

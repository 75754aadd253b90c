"""The checks of the test scripts run by ctest (tests/slow/bench_test.py,
tests/mpi/bench_ranks_test.py): each prints ok or FAILED with what it checks;
a script exits 1 when any failed."""

counts = {"passed": 0, "failed": 0}


def check(condition, what):
    counts["passed" if condition else "failed"] += 1
    print(f"{'ok' if condition else 'FAILED'}: {what}")
    return condition


def any_failed():
    return counts["failed"] > 0


def summary():
    """Prints the counts; the script's exit status."""
    print(f"{counts['passed']} passed, {counts['failed']} failed")
    return 1 if any_failed() else 0

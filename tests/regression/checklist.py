"""The pass/fail bookkeeping shared by the regression scripts: one line per check, then the
'N passed, M failed' line that CI reads, and the exit code."""
import sys


class Checklist:
    def __init__(self):
        self.passed, self.failures = 0, []

    def check(self, cond, what):
        if cond:
            self.passed += 1
            print(f"ok   {what}")
        else:
            self.failures.append(what)
            print(f"FAIL {what}")

    def finish(self):
        print(f"{self.passed} passed, {len(self.failures)} failed")
        sys.exit(1 if self.failures else 0)

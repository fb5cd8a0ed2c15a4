"""Test-wide settings.

Under CI (the CI environment variable set), hypothesis runs derandomized: the same examples
every run, so a submission's result does not depend on the dice. Locally it explores anew
each run, which is how new counterexamples are found. Neither holds an example to a deadline.
"""

import os

from hypothesis import settings

# No deadline: hypothesis's 200 ms per example is a timed assert, and a shared CI host's first
# (cold) example can take longer (test_cross_situational_ceiling_never_exceeds_the_oracle took
# 291 ms once and 75 ms on its rerun); speed lives in benchmarks/, not in tests.
settings.register_profile("ci", derandomize=True, print_blob=True, deadline=None)
settings.register_profile("local", deadline=None)
settings.load_profile("ci" if os.environ.get("CI") else "local")

# The tests hold the shipped domain: declarations of a user's own (`AILEEN_DOMAIN`, loaded by
# every command the tests run in this process) would change it for every test after the first.
# tests/test_domain_extensions.py names its own, in child processes.
os.environ.pop("AILEEN_DOMAIN", None)

# The stop signals at their defaults, however the tests were started: under `nohup` (SIGHUP
# ignored) or as a shell's background job (SIGINT and SIGQUIT ignored) the commands keep
# ignoring what they were started ignoring (`lifecycle.listened`), and the tests that send
# those signals, to this process or to the commands it starts, would see nothing happen.
import signal  # noqa: E402

for _name in ("SIGHUP", "SIGQUIT"):
    if hasattr(signal, _name) and signal.getsignal(getattr(signal, _name)) == signal.SIG_IGN:
        signal.signal(getattr(signal, _name), signal.SIG_DFL)
if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)

# The clingo limits are process-wide (`asp.set_solve_limit`): a command a test runs in this
# process (`aileen run`, default --rules-timeout 10 s) leaves them set for every later test,
# and on a loaded host a later test's plain solve then fails as a RulesTimeout (CI, stop 52:
# tests/test_extent.py at a load average of 13). Each test gets the limits it started with.
import pytest  # noqa: E402

from aileen.reasoning import asp, watchdog  # noqa: E402


@pytest.fixture(autouse=True)
def _clingo_limits_restored():
    seconds, label = asp.solve_limit()
    memory = watchdog.limits().megabytes
    yield
    asp.set_solve_limit(seconds, label, megabytes=memory)

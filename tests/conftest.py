"""Test-wide settings.

Under CI (the CI environment variable set), hypothesis runs derandomized: the same examples
every run, so a submission's result does not depend on the dice. Locally it explores anew
each run, which is how new counterexamples are found.
"""

import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")

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

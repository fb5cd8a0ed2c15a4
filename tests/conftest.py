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

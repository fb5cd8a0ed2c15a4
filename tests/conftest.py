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

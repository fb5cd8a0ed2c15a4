"""aileen: an interactive concept learner for embodied agents (a re-creation of AILEEN, ACS 2020)."""

__version__ = "0.1.0"

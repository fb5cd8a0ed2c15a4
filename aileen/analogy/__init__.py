"""Analogical processing: SME (structure mapping) and SAGE (generalization), pure Python.

See docs/concept-memory.md. No I/O and no clingo, OpenCV or pymunk here.
"""

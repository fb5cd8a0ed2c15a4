"""aileen's concept memory inside Soar (the optional extra `soar`, `pip install -e ".[soar]"`).

- `kernel`: the only module that imports `soar_sml`; a Soar kernel and one agent in-process.
- `wm`: the one boundary where `aileen.terms.Term` facts become working-memory structures and back.
- `bridge`: serves `ConceptMemory` commands placed on the output-link (create/store/query/project).
- `learner`: the paper's learner as Soar productions (`agent/*.soar`) behind the interpreter's agent
  methods.

See docs/soar.md for the structures, with a worked example.
"""

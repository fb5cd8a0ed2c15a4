"""aileen's concept memory inside Soar (the optional extra `soar`, `pip install -e ".[soar]"`).

- `kernel`: the only module that imports `soar_sml`; a Soar kernel and one agent in-process,
  Soar's output events, an optional listener for Soar's debugger.
- `wm`: the one boundary where `aileen.terms.Term` facts become working-memory structures and
  back, with every name coming off the output-link checked.
- `bridge`: serves `ConceptMemory` commands placed on the output-link (create/store/query/
  project, and plan).
- `perception`: the perceived state on the input-link.
- `learner`: the paper's learner as Soar productions (`agent/*.soar`) behind the interpreter's
  agent methods: smem on disk, demonstrations as epmem episodes, acting through `^act` commands.

See docs/soar.md for the structures, with a worked example.
"""

"""What the tests share besides fixtures (which live in tests/conftest.py): constants and
functions a test module imports from here, never from conftest.py or another test module.

What lives here:

- ``repo``: the repository's root and the parts of it that make the workflow.
- ``paper``: the paper's materials and problems (Table 1's Model problem, Table 2's two-contact
  case) and an end-pressure pulse driven through an axisymmetric rod.
- ``laws``: a contact law no module of the package knows (a linear spring).
- ``figures``: whether a figure is fit for a journal (units, legends, words, canvas).
- ``snakemake_cli``: snakemake's command line run in a copy of the project, and what its output
  says (the jobs it plans, the files it would write).
- ``copies``: copies of the project for the workflow tests (a fresh shrunk copy, a copy of a
  built one) and the one end-to-end build of ``.test/`` they share.

What it may import: rodimpact and third-party packages, and its own modules downwards in the
order above (``copies`` uses ``snakemake_cli`` and ``repo``); never a test module or conftest.
"""

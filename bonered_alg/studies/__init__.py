"""Paper studies: numeric reproductions run on a mechanism's generated module.

A study module has ``run(derivation, generated) -> pipeline.results.Study``: its data (for
the paper checks), the tables and plots it writes beside the report, and its report
sections.  A declaration names its studies by module path (``Mechanism.studies``).
"""

"""Workspace analysis from the generated modules (issue 4): grids, membership, chunked and
parallel scans, coordinate ranges by boundary search, plots, and the papers' comparisons
of the hybrid mechanisms with the Stewart platform (:mod:`.bone_reduction`)."""

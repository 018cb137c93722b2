"""The exact-fragility atlas: every record's outcome at every stripe of the check's lattice for
a grid of (α, 2π/p), per record set, intensity measure and floor, built once and read by
``check`` (:mod:`audit.engine.atlas.answers`) instead of solving each object again.

:mod:`~audit.engine.atlas.settings` says what an atlas depends on (and its key),
:mod:`~audit.engine.atlas.store` where it lives (the user cache) and how its chunks resume,
:mod:`~audit.engine.atlas.pipeline` builds it, :mod:`~audit.engine.atlas.answers` reads it.
"""

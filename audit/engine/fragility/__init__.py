"""The audit of a probabilistic procedure (``audit fragility``): its components' fragilities
against the exact overturning fragility, by multiple PGV stripes."""

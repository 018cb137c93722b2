"""The design level (``audit margins``, ``audit fragility``): stripes, fragility, required slenderness, FEMA P695 acceptance and the risk at a site."""

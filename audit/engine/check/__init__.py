"""The check of objects at a site (``audit check``)."""

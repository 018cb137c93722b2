"""The application around the physics: the audit pipeline, saved results and progress reporting."""

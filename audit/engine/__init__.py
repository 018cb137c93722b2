"""The application around the physics: the audit runner, saved results and progress reporting."""

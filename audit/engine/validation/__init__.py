"""Validation of the exact solver against shake-table campaigns (``audit validate``)."""

"""The audit run (``audit run``): every record, every procedure, every block of the grid."""

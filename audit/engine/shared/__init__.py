"""What every workflow of the engine shares: defaults, settings fields, the runtime and scheduler, the file schemas, cost guards, sites and blocks."""

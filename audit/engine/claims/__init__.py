"""The reproduction checklist of the reference report's claims."""

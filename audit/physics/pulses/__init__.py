"""Near-fault velocity pulses of real records: Shahi & Baker's (2014) identification on the
legacy db4 continuous transform, and the Mavroeidis & Papageorgiou (2003) pulse fitted to it."""

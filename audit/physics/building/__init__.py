"""Linear building models that turn a ground motion into the motion of a floor."""

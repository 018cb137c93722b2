"""The one error type for bad input, shared by every package of the project."""


class InputError(ValueError):
    """Bad input (file, field, name or value) that the user can fix.

    The message names the file or the option and says what is wrong, in one line;
    the command-line interface prints it and exits with status 2.
    """


class InputWarning(UserWarning):
    """Input that is accepted but probably wrong (e.g. a PGA implausibly small for the declared
    units); the command-line interface prints it on one line and carries on."""

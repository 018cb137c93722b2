"""The one error type for bad input, shared by every package of the project."""


class InputError(ValueError):
    """Bad input (file, field, name or value) that the user can fix.

    The message names the file or the argument and says what is wrong, in one line; the
    command-line interface prints it and exits with status 2. Below the command line a message
    names the argument as the Python API spells it (``size_s``, ``stripes``), never a
    command-line flag; ``fields`` lists the arguments it names, so that the command line can
    put its own flags in their place (``audit.cli.flags``).

    Parameters
    ----------
    message : str
    *fields : str
        The arguments (settings fields) the message names, as written in it.
    """

    def __init__(self, message: str = "", *fields: str):
        super().__init__(message)
        self.fields = fields


def field_name(argument: str | None, field: str) -> str:
    """The name a message gives ``field`` of a group of settings passed as ``argument``
    (``floor.z_over_h``, ``runtime.jobs``), or ``field`` alone where the group's fields are a
    function's own keywords (``argument`` None)."""
    return f"{argument}.{field}" if argument else field


class NoAtlas(InputError):
    """An atlas asked for (``method='atlas'``, or ``atlas_check``'s records) where none
    answers (:mod:`audit.engine.atlas`).

    Parameters
    ----------
    reason : str
        Why none answers (none built for these records and settings, a block outside its
        grid, stripes other than its own).
    build : dict, optional
        What builds the one asked for, as :func:`audit.api.build_atlas` takes it (``records``
        as the user named them, ``im``, ``solver``, ``floor``); None where one is built but
        cannot answer. The command line words it as its own ``atlas build`` command.
    field : str
        The argument that asked for it: ``method`` (then the direct solve is the way out) or
        ``records``.
    """

    def __init__(self, reason: str, build: dict | None = None, field: str = "method"):
        self.reason, self.build, self.field = reason, build, field
        steps = ([] if build is None else
                 [f"build it with audit.api.build_atlas() given the same {', '.join(build)}"])
        steps += ["use method='direct'"] if field == "method" else []
        asked = "atlas asked, but " if field == "method" else ""
        super().__init__(f"{field}: {asked}{reason}" + ("; " + ", or ".join(steps) if steps
                                                        else ""), field)


class InputWarning(UserWarning):
    """Input that is accepted but probably wrong (e.g. a PGA implausibly small for the declared
    units); the command-line interface prints it on one line and carries on."""

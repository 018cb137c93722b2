"""A plug-in's parameters, declared once and checked once, the OpenQuake hazardlib way.

A procedure or component provision declares what a user may set (:class:`Parameter`: the key
as the code writes it, the attribute that holds it, its unit, the range or words it takes, the
clause its default comes from and whether that default is the text's or an assumption) in its
class attribute ``parameters``; :func:`check_parameters` then validates an instance's values
when it is constructed (InputError naming the attribute), and :func:`parse_params` reads the
``params`` a user gives (``{"asce7_22": {"I_p": 1.5}}``, or ``--param asce7_22.I_p=1.5`` on the
command line) into each plug-in's attributes, refusing an unknown plug-in or key by name.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, is_dataclass
from numbers import Real

from audit.errors import InputError


@dataclass(frozen=True)
class Parameter:
    """One settable parameter of a plug-in.

    Attributes
    ----------
    key : str
        Its name as the code writes it, as typed in ``--param NAME.KEY=VALUE`` (``I_p``).
    attribute : str
        The plug-in's dataclass field that holds it (``importance``).
    unit : str
        ``-`` for a factor, else the SI unit (``m``, ``s``).
    meaning : str
        What it is, in a few words.
    clause : str
        Where its default comes from (the clause, the table's row).
    from_text : bool
        True when the default is read from the text (possibly second-hand: the module says),
        False when it is an assumption of this tool.
    low, high : float
        The range it takes (both ends included unless ``low_open``).
    low_open : bool
        ``low`` itself refused.
    words : dict
        Words it takes besides a number, each → the value held and what it means
        (``{"unknown": (None, "Eq. 13.3-5")}``).
    """

    key: str
    attribute: str
    unit: str
    meaning: str
    clause: str
    from_text: bool
    low: float = 0.0
    high: float = math.inf
    low_open: bool = False
    words: tuple = ()

    def expected(self) -> str:
        """What it takes, in words, for messages and the docs."""
        low = "(" if self.low_open else "["
        high = "∞)" if math.isinf(self.high) else f"{self.high:g}]"
        unit = "" if self.unit == "-" else f" {self.unit}"
        text = f"a number in {low}{self.low:g}, {high}{unit}"
        return text + "".join(f" or '{word}'" for word, _, _ in self.words)

    def value(self, given, where: str, label: str | None = None):
        """``given`` (a number, a numpy scalar, one of :attr:`words`, or the text typed on the
        command line) as the attribute holds it; InputError naming ``where`` (the message
        starting with ``where`` and ``label``) otherwise."""
        for word, held, _ in self.words:
            if given == held and not isinstance(given, Real):  # the word's own value (None)
                return held
            if isinstance(given, str) and given.strip().lower() == word.lower():
                return held
        number = given
        if isinstance(given, str):
            try:
                number = float(given)
            except ValueError:
                number = None
        below = (isinstance(number, Real) and not isinstance(number, bool)
                 and (number <= self.low if self.low_open else number < self.low))
        if (isinstance(number, bool) or not isinstance(number, Real) or below
                or not math.isfinite(number) or number > self.high):
            raise InputError(f"{where}{' ' + label if label else ''}: expected "
                             f"{self.expected()} ({self.key}, {self.meaning}), got {given!r}",
                             where)
        return float(number)

    def shown(self, held) -> str:
        """The value held, as a user reads it (a word where it is one)."""
        for word, value, _ in self.words:
            if held == value and not isinstance(held, Real):
                return word
        return f"{held:g}"


def check_parameters(instance) -> None:
    """Validate the declared parameters of a plug-in dataclass ``instance`` in place (numpy
    scalars become floats); InputError naming the attribute where one is out of range."""
    for parameter in type(instance).parameters:
        given = getattr(instance, parameter.attribute)
        held = parameter.value(given, parameter.attribute)
        if held is not given:
            object.__setattr__(instance, parameter.attribute, held)


def parameter_defaults(cls) -> dict:
    """Each declared parameter's default, by key (from the dataclass's fields)."""
    default = {f.name: f.default for f in fields(cls)} if is_dataclass(cls) else {}
    return {p.key: default.get(p.attribute) for p in cls.parameters}


def parameters_used(instance) -> list[dict]:
    """The instance's declared parameters as check.json lists them: key, value, unit, whether
    it is the default, the default's clause and whether that default is the text's."""
    defaults = parameter_defaults(type(instance))
    out = []
    for p in type(instance).parameters:
        held = getattr(instance, p.attribute)
        out.append({"key": p.key, "value": p.shown(held), "unit": p.unit,
                    "default": p.shown(defaults[p.key]), "given": held != defaults[p.key],
                    "clause": p.clause, "default_from_text": p.from_text,
                    "meaning": p.meaning})
    return out


def parse_params(params, plug_ins: dict, field: str = "params") -> dict:
    """The user's ``params`` as ``{plug-in name: {attribute: value}}``, each value checked.

    Parameters
    ----------
    params : dict or None
        ``{plug-in name: {key: value}}`` (keys as the code writes them, :attr:`Parameter.key`);
        or a sequence of ``"NAME.KEY=VALUE"`` texts (the command line's ``--param``).
    plug_ins : dict
        The plug-in classes by name that may be given parameters.
    field : str
        The argument's name for messages (``params``, or ``--param`` on the command line).
    """
    if params is None:
        return {}
    if isinstance(params, (list, tuple)):
        params = params_of_texts(params, field)
    if not isinstance(params, dict):
        raise InputError(f"{field}: expected {{procedure: {{key: value}}}}, got {params!r}",
                         field)
    out = {}
    for name, given in params.items():
        takers = sorted(n for n, cls in plug_ins.items() if cls.parameters)
        if name not in plug_ins:
            raise InputError(f"{field}: unknown procedure '{name}' (parameters are taken by "
                             f"{', '.join(takers)})", field)
        declared = {p.key: p for p in plug_ins[name].parameters}
        if not declared:
            raise InputError(f"{field}: {name} declares no parameters (they are taken by "
                             f"{', '.join(takers)})", field)
        if not isinstance(given, dict):
            raise InputError(f"{field}: {name}: expected {{key: value}}, got {given!r}", field)
        chosen = {}
        for key, value in given.items():
            if key not in declared:
                takes = ", ".join(declared)
                raise InputError(f"{field}: {name} has no parameter '{key}' (it takes "
                                 f"{takes})", field)
            parameter = declared[key]
            chosen[parameter.attribute] = parameter.value(value, field, f"{name}.{key}")
        out[name] = chosen
    return out


def params_of_texts(texts, field: str) -> dict:
    """``["asce7_22.I_p=1.5", …]`` as ``{"asce7_22": {"I_p": "1.5"}}``; a key given twice is
    refused."""
    out: dict = {}
    for text in texts:
        name_key, sep, value = str(text).partition("=")
        name, dot, key = name_key.strip().partition(".")
        if not (sep and dot and name and key.strip() and value.strip()):
            raise InputError(f"{field}: expected PROCEDURE.KEY=VALUE, got '{text}'", field)
        mine = out.setdefault(name, {})
        if key.strip() in mine:
            raise InputError(f"{field}: {name}.{key.strip()} given twice", field)
        mine[key.strip()] = value.strip()
    return out


__all__ = ["Parameter", "check_parameters", "parameter_defaults", "parameters_used", "params_of_texts",
           "parse_params"]

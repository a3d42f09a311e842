"""A small checker of JSON documents against schemas written as Python values (the schemas of graspmix's
formats are in formats.py, one per format).

Hand-written rather than jsonschema: graspmix's files need a handful of node kinds (numbers that must be
finite, rectangular arrays of numbers, poses), and the messages must name the file, the field's path
(``grasps[3].T_world_wrist``) and what was expected, in one line, quoting at most ~80 characters of the
value; a dependency would add little and its messages would need rewriting anyway.

    validate(doc, Obj({"rank": Int(lo=1)}, required=["rank"]), "grasps.json")
"""

from __future__ import annotations

import math

from .checks import quote


class SchemaError(ValueError):
    """A JSON document that does not follow its format's schema."""


def _is_number(v) -> bool:
    return type(v) in (int, float)


def describe(v) -> str:
    """What a JSON value is, for messages: its kind and a clipped quote."""
    if v is None:
        return "null"
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return f"the number {quote(v)}"
    if isinstance(v, str):
        return f"the string {quote(v)}"
    if isinstance(v, list):
        return f"a list of {len(v)} item{'s' if len(v) != 1 else ''}"
    if isinstance(v, dict):
        return "an object"
    return type(v).__name__


class Spec:
    expected = "a value"

    def check(self, v, where: str) -> None:  # raises _Mismatch
        raise NotImplementedError


class _Mismatch(Exception):
    """Where (field path) the document differs from its schema, and how."""

    def __init__(self, where: str, message: str):
        super().__init__(where, message)
        self.where, self.message = where, message


def _fail(spec: Spec, v, where: str):
    raise _Mismatch(where, f"must be {spec.expected}, got {describe(v)}")


class Any(Spec):
    def check(self, v, where):
        pass


class Num(Spec):
    """A JSON number (not a boolean): finite unless finite=False, never NaN; >= lo, > gt, <= hi; or one of
    `also` (e.g. the strings "-inf" and "inf" that grasps.json writes for rejected grasps, or None)."""

    def __init__(self, lo=None, hi=None, gt=None, finite=True, also=()):
        self.lo, self.hi, self.gt, self.finite, self.also = lo, hi, gt, finite, tuple(also)
        bounds = [
            f">= {lo:g}" if lo is not None else "",
            f"> {gt:g}" if gt is not None else "",
            f"<= {hi:g}" if hi is not None else "",
        ]
        text = ("a finite number" if finite else "a number") + "".join(f" {b}" for b in bounds if b)
        if also:
            text += " or " + " or ".join("null" if a is None else repr(a) for a in also)
        self.expected = text

    def ok(self, v) -> bool:
        if not _is_number(v):
            return False
        x = float(v) if not isinstance(v, int) or abs(v) < 2**1000 else math.copysign(math.inf, v)
        if math.isnan(x) or (self.finite and math.isinf(x)):
            return False
        return not (
            (self.lo is not None and x < self.lo)
            or (self.hi is not None and x > self.hi)
            or (self.gt is not None and x <= self.gt)
        )

    def check(self, v, where):
        if not self.ok(v) and not any(v is a or (a is not None and v == a and type(v) is type(a)) for a in self.also):
            _fail(self, v, where)


class Int(Spec):
    def __init__(self, lo=None, hi=None):
        self.lo, self.hi = lo, hi
        rng = f" in [{lo}, {hi}]" if lo is not None and hi is not None else (f" >= {lo}" if lo is not None else "")
        self.expected = "an integer" + rng

    def check(self, v, where):
        if type(v) is not int or (self.lo is not None and v < self.lo) or (self.hi is not None and v > self.hi):
            _fail(self, v, where)


class Str(Spec):
    """A string (valid UTF-8: it may name a file passed to C++), optionally one of `choices`."""

    def __init__(self, choices=None, nonempty=False):
        self.choices, self.nonempty = choices, nonempty
        self.expected = (
            ("one of " + ", ".join(repr(c) for c in choices))
            if choices
            else ("a non-empty string" if nonempty else "a string")
        )

    def check(self, v, where):
        if not isinstance(v, str) or (self.nonempty and not v) or (self.choices and v not in self.choices):
            _fail(self, v, where)
        try:
            v.encode("utf-8")
        except UnicodeEncodeError:
            raise _Mismatch(where, f"must be valid UTF-8 text, got {quote(v)}") from None


class Bool(Spec):
    expected = "true or false"

    def check(self, v, where):
        if not isinstance(v, bool):
            _fail(self, v, where)


class Null(Spec):
    expected = "null"

    def check(self, v, where):
        if v is not None:
            _fail(self, v, where)


class Arr(Spec):
    """A list of items of one spec, with at least min_len items (or exactly length)."""

    def __init__(self, item: Spec, min_len: int = 0, length: int | None = None):
        self.item, self.min_len, self.length = item, min_len, length
        what = _plural(item.expected)
        if length is not None:
            self.expected = f"a list of {length} {what}"
        else:
            self.expected = f"a non-empty list of {what}" if min_len >= 1 else f"a list of {what}"

    def check(self, v, where):
        if not isinstance(v, list) or len(v) < self.min_len or (self.length is not None and len(v) != self.length):
            _fail(self, v, where)
        for i, x in enumerate(v):
            self.item.check(x, f"{where}[{i}]")


class Tensor(Spec):
    """A rectangular array of finite numbers of ndim dimensions (lists of lists), with the given sizes
    (None: any) and at least one row; checked without recursion into Python per element where possible."""

    def __init__(self, ndim: int, shape: tuple = (), what: str | None = None):
        self.ndim, self.shape = ndim, tuple(shape) + (None,) * (ndim - len(shape))
        dims = " x ".join("N" if s is None else str(s) for s in self.shape)
        self.expected = what or f"a non-empty {dims} array of finite numbers"

    def check(self, v, where):
        self._check(v, where, 0, None)

    def _check(self, v, where, depth, sizes):
        want = self.shape[depth]
        if not isinstance(v, list) or not v or (want is not None and len(v) != want):
            if depth == 0:
                _fail(self, v, where)
            raise _Mismatch(
                where,
                f"must be a list of {want if want is not None else 'N'} "
                f"{'numbers' if depth == self.ndim - 1 else 'lists'}, got {describe(v)}",
            )
        if depth == self.ndim - 1:
            for i, x in enumerate(v):
                if type(x) not in (int, float) or not math.isfinite(x):
                    raise _Mismatch(f"{where}[{i}]", f"must be a finite number, got {describe(x)}")
            return
        first = None
        for i, row in enumerate(v):
            self._check(row, f"{where}[{i}]", depth + 1, None)
            if first is None:
                first = _dims(row)
            elif _dims(row) != first:
                raise _Mismatch(f"{where}[{i}]", f"has another size than {where}[0] (the array must be rectangular)")


def _dims(v) -> tuple:
    out = []
    while isinstance(v, list):
        out.append(len(v))
        v = v[0] if v else None
    return tuple(out)


class Obj(Spec):
    """A JSON object with known fields (extra fields are allowed: formats grow by adding fields)."""

    expected = "an object"

    def __init__(self, fields: dict, required=()):
        self.fields, self.required = fields, tuple(required)

    def check(self, v, where):
        if not isinstance(v, dict):
            _fail(self, v, where)
        for key in self.required:
            if key not in v:
                raise _Mismatch(_join(where, key), "is missing")
        for key, spec in self.fields.items():
            if key in v:
                spec.check(v[key], _join(where, key))


class Map(Spec):
    """A JSON object used as a mapping name -> value of one spec."""

    def __init__(self, value: Spec, what: str | None = None, nonempty: bool = False):
        self.value, self.nonempty = value, nonempty
        self.expected = what or f"an object of {_plural(value.expected)}"

    def check(self, v, where):
        if not isinstance(v, dict) or (self.nonempty and not v):
            _fail(self, v, where)
        for key, x in v.items():
            self.value.check(x, _join(where, key))


class Either(Spec):
    """One of several specs (the first whose kind matches decides the message)."""

    def __init__(self, *specs: Spec):
        self.specs = specs
        self.expected = " or ".join(s.expected for s in specs)

    def check(self, v, where):
        for s in self.specs:
            try:
                s.check(v, where)
                return
            except _Mismatch:
                continue
        _fail(self, v, where)


class Tagged(Spec):
    """An object whose field `key` selects its schema (e.g. a density's "kind")."""

    def __init__(self, key: str, variants: dict):
        self.key, self.variants = key, variants
        self.expected = f"an object with '{key}' one of " + ", ".join(repr(k) for k in variants)

    def check(self, v, where):
        if not isinstance(v, dict):
            _fail(self, v, where)
        tag = v.get(self.key)
        if not isinstance(tag, str) or tag not in self.variants:
            raise _Mismatch(
                _join(where, self.key),
                f"must be one of {', '.join(map(repr, self.variants))}, "
                f"got {describe(tag) if self.key in v else 'nothing'}",
            )
        self.variants[tag].check(v, where)


def _join(where: str, key: str) -> str:
    return f"{where}.{key}" if where else str(key)


def _plural(expected: str) -> str:
    for article in ("a ", "an "):
        if expected.startswith(article):
            return expected[len(article) :] + ("" if expected.endswith("s") else "s")
    return expected


def validate(doc, spec: Spec, path) -> None:
    """SchemaError "<path>: field 'x.y[3]' must be ..., got ..." at the first mismatch."""
    try:
        spec.check(doc, "")
    except _Mismatch as m:
        if m.where:
            where = m.where if len(m.where) <= 120 else m.where[:120] + "..."
            raise SchemaError(f"{path}: field '{where}' {m.message}") from None
        raise SchemaError(f"{path}: the document {m.message}") from None

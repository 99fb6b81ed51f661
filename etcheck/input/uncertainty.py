"""The ``[uncertainty]`` table of a mission: how well each input is known.

Each entry names one input and gives either a tolerance or a distribution::

    [uncertainty]
    bending_stiffness = "±15 %"                          # EI1 and EI2 by one common factor
    axial_field = { distribution = "lognormal", sigma = "30 %" }
    length = "±0.5 m"
    damping_time = { distribution = "log-uniform", factor = 10 }
    end_tension = { distribution = "normal", sigma = "0.2 N", bounds = ["-0.1 N", "0.5 N"] }

Meaning (stated in the report):

* a tolerance ``"±10 %"`` or ``"±0.5 m"`` is a *uniform* distribution over
  nominal ± tolerance (all that a tolerance says is "somewhere in this band");
* ``normal``: mean = the mission's value, ``sigma`` relative ("10 %") or
  absolute ("2 N m2");
* ``lognormal``: median = the mission's value, ``sigma`` the standard
  deviation of ln(x), a plain number or a percentage ("30 %" is 0.30);
* ``uniform`` needs ``bounds = [lo, hi]``; ``log-uniform`` needs ``bounds``
  or ``factor`` (nominal / factor ... nominal x factor);
* ``bounds`` on a normal or lognormal truncates it; a bound is a quantity or
  a percentage of the nominal value ("-20 %", "+20 %").

The nominal value of an input is the mission's value; for the current and the
field, given as ranges in ``[operation]``, it is the worst case |I|, |B0|
(ranges stay worst-case; the tolerance is around the worst case). Inputs that
are positive (stiffnesses, mass, length, damping time) or magnitudes (current,
field, spin) are truncated at zero when a normal distribution would reach it;
that is recorded as a note. Everything is converted to SI floats here: the
study works without units.
"""

from __future__ import annotations

import difflib
import math
import re
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from etcheck.errors import MissionError
from etcheck.input.echo import DistributionRecord, UncertaintyInputs
from etcheck.input.units import KINDS, QuantityProblem, to_quantity

#: input -> (quantity kind of etcheck.input.units, what it is, lower physical limit, strict)
INPUTS: dict[str, tuple[str | None, str, float | None, bool]] = {
    "bending_stiffness": (None, "both bending stiffnesses EI1 and EI2 (one common factor)", 0.0, True),
    "EI1": ("bending_stiffness", "the stiff-axis bending stiffness EI1", 0.0, True),
    "EI2": ("bending_stiffness", "the weak-axis bending stiffness EI2", 0.0, True),
    "torsional_stiffness": ("torsional_stiffness", "the torsional stiffness GJ", 0.0, True),
    "mass_per_length": ("mass_per_length", "the mass per length", 0.0, True),
    "length": ("length", "the tether length", 0.0, True),
    "current": ("current", "the current magnitude |I|", 0.0, False),
    "axial_field": ("field", "the axial field magnitude |B0|", 0.0, False),
    "spin_rate": ("angular_rate", "the spin rate", 0.0, False),
    "end_tension": ("force", "the end tension", None, False),
    "damping_time": ("time", "the Kelvin-Voigt damping time", 0.0, True),
}
DISTRIBUTIONS = ("uniform", "normal", "lognormal", "log-uniform")
_KEYS = {"distribution", "sigma", "bounds", "factor"}
_TOL = re.compile(r"^\s*(±|\+-|\+/-)\s*(.+?)\s*$")
_PCT = re.compile(r"^\s*([+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?)\s*%\s*$")


def _log_diff(la, lb) -> np.ndarray:
    """ln(exp(la) - exp(lb)) for la >= lb (vectorised; -inf where they are equal)."""
    la, lb = np.asarray(la, dtype=float), np.asarray(lb, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = la + np.log(-np.expm1(lb - la))
    return np.where(np.isneginf(lb), la, np.where(la <= lb, -np.inf, out))


@dataclass(frozen=True)
class Distribution:
    """One uncertain input as a distribution of SI floats (or of a factor).

    ``shape`` is uniform, normal, lognormal or log-uniform; ``a``, ``b`` its
    parameters in SI: uniform (lo, hi), normal (mean, sigma), lognormal
    (ln median, sigma of ln x), log-uniform (lo, hi). ``lower``, ``upper``
    truncate it. ``factor`` True: the samples multiply the mission's value
    (nominal 1, dimensionless); otherwise they replace it (``unit`` SI).
    ``text`` is the entry as written.
    """

    input: str
    shape: str
    nominal: float
    a: float
    b: float
    lower: float = -math.inf
    upper: float = math.inf
    factor: bool = False
    unit: str = ""
    text: str = ""

    # ------------------------------------------------------------------ the standard-normal coordinate
    # Every shape is a monotone map of a base variable s: standard normal for normal (s = (x - a) / b) and
    # lognormal (s = (ln x - a) / b), uniform on [0, 1] for uniform (s = (x - a) / (b - a)) and log-uniform
    # (s = ln(x / a) / ln(b / a)); the bounds truncate s to [s_lo, s_hi]. Distribution functions are computed
    # in logarithms from the near tail, so that z = Phi^-1(F(x)) keeps its relative accuracy at F ~ 1e-300.

    @property
    def _gaussian(self) -> bool:
        return self.shape in ("normal", "lognormal")

    def _s(self, x) -> np.ndarray:
        """The base variable at x (vectorised; -inf/+inf outside the support)."""
        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            if self.shape == "normal":
                return (x - self.a) / self.b
            if self.shape == "uniform":
                return (x - self.a) / (self.b - self.a)
            ref = math.exp(self.a) if self.shape == "lognormal" else self.a  # ln(x / ref): no cancellation near ref
            lx = np.where(x > 0, np.log(np.where(x > 0, x, 1.0) / ref), -np.inf)
            return lx / (self.b if self.shape == "lognormal" else math.log(self.b / self.a))

    def _x(self, s) -> np.ndarray:
        """x at the base variable s (vectorised)."""
        s = np.asarray(s, dtype=float)
        if self.shape == "normal":
            return self.a + self.b * s
        if self.shape == "uniform":
            return self.a + (self.b - self.a) * s
        if self.shape == "lognormal":
            return np.exp(self.a + self.b * s)
        return self.a * np.exp(s * math.log(self.b / self.a))

    def _bounds(self) -> tuple[float, float]:
        """The truncation of s: [s_lo, s_hi] (within [0, 1] for the uniform shapes)."""
        lo, hi = (float(self._s(v)) for v in (self.lower, self.upper))
        if not self._gaussian:
            lo, hi = max(lo, 0.0), min(hi, 1.0)
        return lo, hi

    def _log_mass(self) -> float:
        """ln of the base probability inside [s_lo, s_hi]."""
        from scipy import special
        lo, hi = self._bounds()
        if not self._gaussian:
            return math.log(hi - lo) if hi > lo else -math.inf
        if lo > 0:  # both in the upper tail: from the upper side
            lo, hi = -hi, -lo
        return float(_log_diff(special.log_ndtr(hi), special.log_ndtr(lo)))

    def log_cdf(self, x) -> np.ndarray:
        """ln P(X <= x) (vectorised; accurate far into the lower tail)."""
        from scipy import special
        lo, hi = self._bounds()
        s = np.clip(self._s(x), lo, hi)
        if not self._gaussian:
            with np.errstate(divide="ignore"):
                return np.log(s - lo) - self._log_mass()
        return _log_diff(special.log_ndtr(s), special.log_ndtr(lo)) - self._log_mass()

    def log_sf(self, x) -> np.ndarray:
        """ln P(X > x) (vectorised; accurate far into the upper tail)."""
        from scipy import special
        lo, hi = self._bounds()
        s = np.clip(self._s(x), lo, hi)
        if not self._gaussian:
            with np.errstate(divide="ignore"):
                return np.log(hi - s) - self._log_mass()
        return _log_diff(special.log_ndtr(-s), special.log_ndtr(-hi)) - self._log_mass()

    def to_normal(self, x) -> np.ndarray:
        """The standard-normal coordinate z of x: Phi(z) = P(X <= x), from the near tail (vectorised;
        -inf/+inf at or beyond the ends of the support)."""
        from scipy import special
        if self._gaussian and self._bounds() == (-math.inf, math.inf):
            return self._s(x)
        lc, ls = self.log_cdf(x), self.log_sf(x)
        return np.where(lc < ls, special.ndtri_exp(np.minimum(lc, 0.0)), -special.ndtri_exp(np.minimum(ls, 0.0)))

    def from_normal(self, z) -> np.ndarray:
        """x at the standard-normal coordinate z (the inverse of :meth:`to_normal`; vectorised)."""
        from scipy import special
        z = np.asarray(z, dtype=float)
        lo, hi = self._bounds()
        if self._gaussian and (lo, hi) == (-math.inf, math.inf):
            return self._x(z)
        lm = self._log_mass()
        if not self._gaussian:
            w = math.exp(lm)
            s = np.where(z <= 0, lo + special.ndtr(z) * w, hi - special.ndtr(-z) * w)
        else:
            with np.errstate(divide="ignore"):
                low = special.ndtri_exp(np.logaddexp(special.log_ndtr(lo), special.log_ndtr(z) + lm))
                high = -special.ndtri_exp(np.logaddexp(special.log_ndtr(-hi), special.log_ndtr(-z) + lm))
            s = np.where(z <= 0, low, high)
        return np.clip(self._x(np.clip(s, lo, hi)), self.lower, self.upper)

    def mass(self) -> float:
        """Probability mass of the untruncated distribution inside [lower, upper]."""
        return math.exp(self._log_mass())

    def ppf(self, u) -> np.ndarray:
        """Quantile function (vectorised over u in [0, 1])."""
        from scipy import special
        return self.from_normal(special.ndtri(np.asarray(u, dtype=float)))

    def cdf(self, x) -> np.ndarray:
        """P(X <= x) (vectorised)."""
        return np.exp(self.log_cdf(x))

    def sf(self, x) -> np.ndarray:
        """P(X > x) (vectorised; accurate far into the upper tail)."""
        return np.exp(self.log_sf(x))

    def interval(self) -> tuple[float, float]:
        """The tolerance range drawn in the tornado chart: the bounds of a uniform or
        log-uniform distribution, the central 95 % (2.5 %, 97.5 % quantiles) otherwise."""
        if self.shape in ("uniform", "log-uniform"):
            return (max(self.a, self.lower), min(self.b, self.upper))
        lo, hi = self.ppf([0.025, 0.975])
        return float(lo), float(hi)

    def log_spread(self) -> float:
        """Half the 16 %-84 % range of ln(x / nominal) (one 'sigma' in log terms); 0 if x can reach 0."""
        lo, hi = self.ppf([0.158655, 0.841345])
        if lo <= 0 or hi <= 0:
            lo = max(lo, 1e-300)
        return 0.5 * (math.log(hi) - math.log(lo))

    def describe(self) -> str:
        """Human text: the distribution and its parameters in SI (or as a factor)."""
        unit = "" if self.factor else f" {self.unit}"
        g = "{:.4g}".format
        if self.shape == "uniform":
            s = f"uniform on [{g(self.a)}, {g(self.b)}]{unit}"
        elif self.shape == "normal":
            s = f"normal, mean {g(self.a)}{unit}, sigma {g(self.b)}{unit}"
        elif self.shape == "lognormal":
            s = f"lognormal, median {g(math.exp(self.a))}{unit}, sigma of ln x {g(self.b)}"
        else:
            s = f"log-uniform on [{g(self.a)}, {g(self.b)}]{unit}"
        if math.isfinite(self.lower) or math.isfinite(self.upper):
            if not (self.shape in ("uniform", "log-uniform") and self.lower <= self.a and self.upper >= self.b):
                s += f", truncated to [{g(self.lower)}, {g(self.upper)}]{unit}"
        return s + (" (factor on the mission's value)" if self.factor else "")

    def echo(self) -> DistributionRecord:
        """The input as read, for the uncertainty section of the results."""
        lo, hi = self.interval()
        return DistributionRecord(input=self.input, written=self.text, distribution=self.shape, nominal=self.nominal,
                                  factor=self.factor, unit="" if self.factor else self.unit, describe=self.describe(),
                                  range=(lo, hi))


@dataclass(frozen=True)
class Uncertainty:
    """The parsed [uncertainty] table: one Distribution per uncertain input, and notes."""

    inputs: tuple[Distribution, ...]
    notes: tuple[str, ...] = field(default_factory=tuple)

    def get(self, name: str) -> Distribution | None:
        return next((d for d in self.inputs if d.input == name), None)

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(d.input for d in self.inputs)

    def echo(self) -> UncertaintyInputs:
        """The table as read, for the uncertainty section of the results."""
        return UncertaintyInputs(inputs=tuple(d.echo() for d in self.inputs), notes=self.notes)


def parse_uncertainty(table: Any, source: str, nominal: dict[str, Any], fixed: dict[str, str] | None = None) -> Uncertainty:
    """Validate an [uncertainty] table against the mission's nominal values.

    ``nominal`` maps input names to astropy quantities (or None when the
    mission does not give the value, e.g. damping_time by default: then only
    relative entries are accepted); ``fixed`` maps inputs that cannot vary
    independently to the reason (e.g. GJ derived from poisson_ratio).
    Raises MissionError naming ``uncertainty.FIELD`` and the fix.
    """
    fixed = fixed or {}
    if not isinstance(table, dict):
        raise MissionError(source, "uncertainty", "must be a table", 'write it as [uncertainty] with lines like length = "±1 %"')
    if not table:
        raise MissionError(source, "uncertainty", "is empty", 'give at least one input, e.g. bending_stiffness = "±15 %"')
    if "bending_stiffness" in table and ("EI1" in table or "EI2" in table):
        raise MissionError(source, "uncertainty.bending_stiffness",
                           "given together with EI1/EI2",
                           "give either bending_stiffness (one factor for both axes) or EI1 and/or EI2 (independent)")
    out, notes = [], []
    for key, value in table.items():
        fld = f"uncertainty.{key}"
        if key not in INPUTS:
            raise MissionError(source, fld, "unknown input" + _suggest(key, INPUTS), f"inputs are {', '.join(INPUTS)}")
        if key in fixed:
            raise MissionError(source, fld, f"cannot vary on its own: {fixed[key]}", "")
        d, note = _parse_one(key, value, source, nominal, fld)
        out.append(d)
        if note:
            notes.append(note)
    return Uncertainty(tuple(out), tuple(notes))


@dataclass(frozen=True)
class _Entry:
    """One [uncertainty] entry being read: its input, its nominal value (SI, or 1 for a factor) and where
    errors point (``source``, ``fld``)."""

    key: str
    kind: str | None  # None: bending_stiffness, one common factor on EI1 and EI2
    nominal: Any  # the mission's astropy quantity, or None (not given: relative entries only)
    source: str
    fld: str

    @property
    def as_factor(self) -> bool:
        return self.kind is None or self.nominal is None

    @property
    def unit(self) -> str:
        return "" if self.as_factor else KINDS[self.kind][0].to_string()

    @property
    def x0(self) -> float:
        return 1.0 if self.as_factor else float(self.nominal.to_value(KINDS[self.kind][0]))

    @property
    def example(self) -> str:
        return KINDS[self.kind][2] if self.kind else '"10 %"'

    def err(self, problem: str, fix: str = "") -> MissionError:
        return MissionError(self.source, self.fld, problem, fix)

    def amount(self, v: Any, part: str) -> tuple[float, bool]:
        """(value, relative?) of a percentage or a quantity; relative values are fractions."""
        if isinstance(v, bool) or not isinstance(v, str):
            raise self.err(f"{part}: expected a percentage such as \"10 %\" or a quantity such as {self.example}, "
                           f"got {v!r}")
        m = _PCT.match(v)
        if m:
            frac = float(m.group(1)) / 100.0
            if not math.isfinite(frac):
                raise self.err(f"{part}: {v!r} is not a finite number")
            return frac, True
        if self.kind is None:
            raise self.err(f"{part}: {v!r} is not a percentage; the common factor of both stiffnesses is relative",
                           'write e.g. "±15 %" (or give EI1/EI2 separately in N m2)')
        if self.nominal is None:
            raise self.err(f"{part}: {v!r} is absolute, but the mission gives no {self.key} (a default is used)",
                           f"give a relative value such as \"50 %\", or state {self.key} in the mission")
        try:
            q = to_quantity(v, self.kind)
        except QuantityProblem as exc:
            raise self.err(f"{part}: {exc}") from None
        return float(q.to_value(KINDS[self.kind][0])), False

    def deviation(self, v: Any, part: str) -> float:
        """A tolerance or sigma: positive, finite, absolute SI (or factor)."""
        a, rel = self.amount(v, part)
        if not a > 0:
            raise self.err(f"{part} must be positive, got {v!r}", "leave the input out of [uncertainty] to keep it exact")
        if not rel:
            return a
        if self.x0 == 0:
            raise self.err(f"{part}: a percentage of a zero {self.key} is zero",
                           f"give an absolute value such as {self.example}")
        return a * abs(self.x0)

    def bound(self, v: Any, part: str) -> float:
        a, rel = self.amount(v, part)
        return self.x0 * (1.0 + a) if rel else a


#: (shape, a, b, lower, upper) of a Distribution, before the physical limits
_Shape = tuple[str, float, float, float, float]


def _parse_one(key: str, value: Any, source: str, nominal: dict[str, Any], fld: str) -> tuple[Distribution, str]:
    kind = INPUTS[key][0]
    e = _Entry(key, kind, nominal.get(key) if kind else None, source, fld)
    if isinstance(value, str):
        shape, a, b, lower, upper = _tolerance(e, value)
    elif isinstance(value, dict):
        shape, a, b, lower, upper = _distribution(e, value)
    else:
        raise e.err(f"expected a tolerance such as \"±10 %\" or a distribution table, got {value!r}",
                    'e.g. { distribution = "normal", sigma = "10 %" }')
    lower, note = _physical_limit(e, shape, a, b, lower)
    text = value if isinstance(value, str) else as_written(value)
    d = Distribution(key, shape, e.x0, float(a), float(b), float(lower), float(upper), e.as_factor, e.unit, text)
    if not d.mass() > 0:
        raise e.err("the bounds leave no probability", "widen the bounds")
    return d, note


def as_written(value: Any) -> str:
    """An entry as the user wrote it in TOML: ``{ distribution = "normal", sigma = "15 %" }``."""
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {as_written(v)}" for k, v in value.items()) + " }"
    if isinstance(value, list):
        return "[" + ", ".join(as_written(v) for v in value) + "]"
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def _tolerance(e: _Entry, value: str) -> _Shape:
    """``"±10 %"`` or ``"±0.5 m"``: uniform over nominal ± tolerance."""
    m = _TOL.match(value)
    if not m:
        raise e.err(f"cannot read {value!r} as a tolerance",
                    'write a tolerance as "±10 %" or "±0.5 m", or a table such as '
                    '{ distribution = "normal", sigma = "10 %" }')
    t = e.deviation(m.group(2), "tolerance")
    return "uniform", e.x0 - t, e.x0 + t, -math.inf, math.inf


def _distribution(e: _Entry, value: dict) -> _Shape:
    """``{ distribution = ..., sigma / bounds / factor }``."""
    for k in value:
        if k not in _KEYS:
            raise e.err(f"unknown key {k!r}" + _suggest(k, _KEYS), f"keys are {', '.join(sorted(_KEYS))}")
    shape = value.get("distribution")
    if shape not in DISTRIBUTIONS:
        raise e.err(f"distribution {shape!r} is not known" + _suggest(str(shape), DISTRIBUTIONS),
                    f"use one of {', '.join(DISTRIBUTIONS)}")
    lower, upper = _bounds(e, value.get("bounds"))
    extra = _NOT_FOR[shape] & set(value)
    if extra:
        raise e.err(f"{', '.join(sorted(extra))} does not apply to a {shape} distribution",
                    {"uniform": "give bounds = [lo, hi]", "log-uniform": "give bounds = [lo, hi] or factor = 10"}.get(
                        shape, "give sigma (and optional bounds)"))
    a, b = _PARAMETERS[shape](e, value, lower, upper)
    return shape, a, b, lower, upper


#: keys of an entry that a distribution does not take
_NOT_FOR = {"uniform": {"sigma", "factor"}, "normal": {"factor"}, "lognormal": {"factor"}, "log-uniform": {"sigma"}}


def _suggest(word: str, options) -> str:
    close = difflib.get_close_matches(word, list(options), n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _bounds(e: _Entry, bnds: Any) -> tuple[float, float]:
    """``bounds = [lo, hi]`` (quantities or percentages of the nominal value) -> SI; unbounded when absent."""
    if bnds is None:
        return -math.inf, math.inf
    if not isinstance(bnds, list) or len(bnds) != 2:
        raise e.err(f"bounds: expected [lo, hi], got {bnds!r}", 'e.g. bounds = ["-20 %", "+20 %"]')
    lower, upper = e.bound(bnds[0], "bounds[0]"), e.bound(bnds[1], "bounds[1]")
    if not lower < upper:
        raise e.err(f"bounds {bnds!r}: lo must be below hi", "write them as [lo, hi]")
    if not lower <= e.x0 <= upper:
        raise e.err(f"bounds {bnds!r} do not contain the mission's value", "the nominal value must be possible")
    return lower, upper


def _sigma_needed(e: _Entry, value: dict, shape: str) -> Any:
    if "sigma" not in value:
        raise e.err(f"a {shape} distribution needs sigma", 'e.g. sigma = "10 %"')
    return value["sigma"]


def _normal(e: _Entry, value: dict, lower: float, upper: float) -> tuple[float, float]:
    """(mean, sigma): mean the mission's value."""
    return e.x0, e.deviation(_sigma_needed(e, value, "normal"), "sigma")


def _lognormal(e: _Entry, value: dict, lower: float, upper: float) -> tuple[float, float]:
    """(ln median, sigma of ln x): median the mission's value, sigma a plain number or a percentage."""
    s = _sigma_needed(e, value, "lognormal")
    if isinstance(s, (int, float)) and not isinstance(s, bool):
        b = float(s)
    elif isinstance(s, str) and _PCT.match(s):
        b = float(_PCT.match(s).group(1)) / 100.0
    else:
        raise e.err(f"sigma of a lognormal is the standard deviation of ln(x): a number or a percentage, got {s!r}",
                    'e.g. sigma = "30 %" or sigma = 0.3')
    if not (math.isfinite(b) and b > 0):
        raise e.err(f"sigma must be a positive finite number, got {s!r}")
    if e.x0 <= 0:
        raise e.err(f"a lognormal needs a positive {e.key}, the mission gives {e.x0:g}", "use a normal distribution")
    return math.log(e.x0), b


def _uniform(e: _Entry, value: dict, lower: float, upper: float) -> tuple[float, float]:
    if value.get("bounds") is None:
        raise e.err("a uniform distribution needs bounds = [lo, hi]",
                    'e.g. bounds = ["-10 %", "+10 %"] or a tolerance "±10 %"')
    return lower, upper


def _log_uniform(e: _Entry, value: dict, lower: float, upper: float) -> tuple[float, float]:
    """(lo, hi) from the bounds or nominal / factor ... nominal x factor."""
    if (value.get("bounds") is None) == ("factor" not in value):
        raise e.err("a log-uniform distribution needs bounds = [lo, hi] or factor (not both)", "e.g. factor = 10")
    a, b = lower, upper
    if "factor" in value:
        fct = value["factor"]
        if isinstance(fct, bool) or not isinstance(fct, (int, float)) or not math.isfinite(fct) or fct <= 1:
            raise e.err(f"factor must be a number > 1, got {fct!r}", "e.g. factor = 10 (nominal/10 ... nominal x 10)")
        if e.x0 <= 0:
            raise e.err(f"a log-uniform needs a positive {e.key}, the mission gives {e.x0:g}")
        a, b = e.x0 / fct, e.x0 * fct
    if not a > 0:
        raise e.err(f"a log-uniform distribution needs a positive lower bound, got {a:g}")
    return a, b


_PARAMETERS = {"normal": _normal, "lognormal": _lognormal, "uniform": _uniform, "log-uniform": _log_uniform}


def _physical_limit(e: _Entry, shape: str, a: float, b: float, lower: float) -> tuple[float, str]:
    """Positive inputs and magnitudes cannot go below zero: a uniform range reaching the limit is an error,
    a normal is truncated there (with a note); (lower bound, note)."""
    _, what, limit, strict = INPUTS[e.key]
    if limit is None:
        return lower, ""
    reach = max(a if shape in ("uniform", "log-uniform") else -math.inf if shape == "normal" else 0.0, lower)
    if not (reach < limit or (strict and reach == limit and shape == "uniform")):
        return lower, ""
    if shape == "uniform":
        raise e.err(f"the range reaches {reach:g}{'' if e.as_factor else ' ' + e.unit}, but {what} is "
                    f"{'positive' if strict else 'not negative'}", "narrow the tolerance")
    if shape != "normal" or lower >= limit:
        return lower, ""
    from scipy import stats  # scipy.stats is slow to import: only missions with a truncated normal need it here

    cut = float(stats.norm.cdf((limit - a) / b))
    return limit, (f"[uncertainty] {e.key}: the normal distribution is truncated at {limit:g} ({what} cannot be "
                   f"negative); the probability cut off is {cut:.2e}")

"""Numbers as the page shows them: integers counting units of the last displayed digit."""

from __future__ import annotations

import re
from dataclasses import dataclass
from decimal import ROUND_HALF_UP, Decimal

import numpy as np

MINUS = "\u2212"
SPECIAL = np.iinfo(np.int64).min  # marks a value the page shows in words (e.g. "∞"); null in JSON


def quantize(values, decimals: int, special: bool = False) -> np.ndarray:
    """Round to `decimals` digits (`shown_integers`: ties away from zero) and return the integer count of
    10**-decimals units.

    A value that rounds to zero becomes plain 0, so a page never shows "-0.000". With `special`,
    non-finite values (a singularity, or a quantity that does not exist there) become the SPECIAL marker.
    """
    values = np.asarray(values, dtype=float)
    infinite = ~np.isfinite(values) if special else None
    source = values if infinite is None else np.where(infinite, 0.0, values)
    quanta = shown_integers(source, decimals)  # -0.0 becomes plain 0: integers carry no sign of zero
    return quanta if infinite is None else np.where(infinite, SPECIAL, quanta)


# --- the one rounding rule -------------------------------------------------------------------------------------
# Every number a page shows is rounded the way a printed table is: to the nearest digit, and a value exactly
# half-way (0.125 to two decimals, 19.375 to two, -0.5625 to three) away from zero, judged on the double's
# exact value, never on a product that rounding made a tie. Tables are rounded here; the page's script rounds
# an expression's value by the same steps (sitegen.js toQuantum), and the build's checks compare with this.

_SPLIT = 134217729.0  # 2**27 + 1: Veltkamp's split of a double into two halves of 26 bits


def _product_error(a: np.ndarray, b: float, product: np.ndarray) -> np.ndarray:
    """a·b − product exactly, where product = fl(a·b) (Dekker's two-product, without a fused multiply-add)."""
    a_big = _SPLIT * a
    a_hi = a_big - (a_big - a)
    a_lo = a - a_hi
    b_big = _SPLIT * b
    b_hi = b_big - (b_big - b)
    b_lo = b - b_hi
    return ((a_hi * b_hi - product) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo


def shown_integers(values, power: int = 0) -> np.ndarray:
    """values × 10**power rounded to integers, each exact tie away from zero (int64).

    Rounding the double product is right except where the product itself lands on a half-integer: then the
    exact product (the double plus its rounding error) decides — above the tie, at it, or below. Negative
    powers divide, with the exact remainder deciding the same way. (No more arrays the size of `values` at
    once than two of doubles: tables run to millions of values.)"""
    values = np.asarray(values, dtype=float)
    scale = 10.0 ** abs(power)  # exact up to 10**22
    offset, nearest = np.empty(values.shape), np.empty(values.shape)  # arrays even for one value
    (np.multiply if power >= 0 else np.divide)(values, scale, out=offset)
    np.rint(offset, out=nearest)
    np.subtract(offset, nearest, out=offset)  # now scaled − nearest, in [−0.5, 0.5]
    at = np.flatnonzero((offset == 0.5) | (offset == -0.5))
    if at.size:
        value, scaled = values.reshape(-1)[at], nearest.reshape(-1)[at] + offset.reshape(-1)[at]  # exact halves
        if power >= 0:
            above = _product_error(value, scale, scaled)  # exact product − scaled
        else:  # value − scaled·scale, exactly (the two are within a factor of two: the difference is exact)
            above = (value - scaled * scale) - _product_error(scaled, scale, scaled * scale)
        away = np.where(scaled > 0, np.ceil(scaled), np.floor(scaled))
        nearest.reshape(-1)[at] = np.where(above > 0, np.ceil(scaled), np.where(above < 0, np.floor(scaled), away))
    del offset
    return nearest.astype(np.int64)


def format_quantum(quantum: int, decimals: int) -> str:
    """Write an integer count of 10**-decimals units as a decimal string, e.g. (-2333, 3) -> '−2.333'."""
    digits = str(abs(int(quantum))).rjust(decimals + 1, "0")
    body = f"{digits[:-decimals]}.{digits[-decimals:]}" if decimals else digits
    return (MINUS if quantum < 0 else "") + body


def fmt(value: float, decimals: int) -> str:
    """Format one number exactly as the page does."""
    return format_quantum(int(quantize(value, decimals)), decimals)


# --- significant digits: a readout whose values span decades ---------------------------------------------

PREFIXES = {-15: "f", -12: "p", -9: "n", -6: "µ", -3: "m", 0: "", 3: "k", 6: "M", 9: "G"}
_POWER_OF = {text: power for power, text in PREFIXES.items()}
# A unit an SI prefix may go on: an optional prefix, a base unit, then nothing or "/…", "·…" or " …" (not "m²").
_UNIT = re.compile(r"([fpnµmkMG]?)(Pa|Hz|m|s|g|J|W|N|K)(?=$|[/· ])(.*)")
# Prefixes that read naturally on a base unit (beyond them, a power of ten): no "Gm", "ks" or "MK".
_PREFIX_RANGE = {"m": (-12, 3), "s": (-15, 0), "g": (-6, 3), "K": (0, 0)}
_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")
_FROM_SUPERSCRIPT = str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")
_POWER_UNIT = re.compile(r"× 10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)")


@dataclass(frozen=True)
class Written:
    """How one value shown to significant digits is written: `shown` counts 10**-decimals and `suffix`
    follows it (the prefixed unit, or "× 10ⁿ" and the unit); the value in the output's declared unit is
    shown × 10**power."""

    shown: int
    decimals: int
    suffix: str
    power: int


def significant(values, digits: int, special: bool = False, floor: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Each value rounded to `digits` significant digits as (mantissa, exponent): value ≈ mantissa ×
    10**exponent with `digits` digits in the mantissa (zero as 0 × 10**0). Correctly rounded from the
    double (Python's own decimal formatting), an exact tie away from zero as every shown number is. With
    `special`, non-finite values get the SPECIAL mantissa; a value smaller in magnitude than `floor` (the
    output's accuracy) is zero."""
    values = np.asarray(values, dtype=float)
    mantissas, exponents = np.zeros(values.shape, np.int64), np.zeros(values.shape, np.int64)
    finite = np.isfinite(values)
    if special:
        mantissas[~finite] = SPECIAL
    shown = finite & (np.abs(values) >= floor) & (values != 0.0)
    # Only the shown values go through Python's formatting; "d.ddde±x" is read back as the integers dddd and ±x.
    form = f"%.{digits - 1}e"
    kept = values[shown].tolist()
    texts = " ".join([form % value for value in kept])
    both = np.fromstring(texts.replace(".", "").replace("e", " "), dtype=np.int64, sep=" ")
    both[1::2] -= digits - 1
    for k in _exact_ties(kept, digits):  # formatting rounds a tie to even: these go away from zero
        both[2 * k], both[2 * k + 1] = _away(kept[k], digits)
    mantissas[shown], exponents[shown] = both[0::2], both[1::2]
    return mantissas, exponents


def _exact_ties(values: list[float], digits: int) -> list[int]:
    """Indices of the values whose exact decimal expansion ends in a 5 just after `digits` significant digits."""
    longer = f"%.{digits}e"
    found = []
    for k, value in enumerate(values):
        text = longer % value
        if text.partition("e")[0][-1] == "5" and Decimal(value) == Decimal(text):
            found.append(k)
    return found


def _away(value: float, digits: int) -> tuple[int, int]:
    """(mantissa, exponent) of an exact tie rounded to `digits` significant digits away from zero."""
    exact = Decimal(value)
    exponent = exact.adjusted() - (digits - 1)
    mantissa = int(exact.scaleb(-exponent).quantize(Decimal(1), rounding=ROUND_HALF_UP))
    if abs(mantissa) == 10**digits:  # 9.995 -> 10.00: one digit more, so one place up
        mantissa, exponent = mantissa // 10, exponent + 1
    return mantissa, exponent


def written(mantissa: int, exponent: int, digits: int, unit: str) -> Written:
    """How mantissa × 10**exponent (in `unit`) is written: with the SI prefix that puts one to three digits
    before the point, or, where no prefix reads well (or the unit takes none), as a power of ten. A unit
    that is itself a power of ten ("× 10⁻⁶") is folded into the number."""
    if mantissa == 0:
        return Written(0, 0, with_unit("", unit), 0)
    shift, base, prefixable = _unit_parts(unit)
    lead = exponent + digits - 1 + shift  # the power of the leading digit in the base unit
    prefix = 3 * (lead // 3)
    low, high = _PREFIX_RANGE.get(prefixable, (-15, 9))
    if prefixable and low <= prefix <= high:
        suffix = f" {PREFIXES[prefix]}{base}"
    elif -4 <= lead <= 3 and not (prefixable and lead > high):  # plain decimals read best near 1
        prefix, suffix = 0, with_unit("", base)
    else:
        prefix = lead
        suffix = f"\u00a0×\u00a010{str(lead).translate(_SUPERSCRIPT)}" + (f" {base}" if base else "")
    places = exponent + shift - prefix  # the power of the mantissa's last digit, in units of 10**prefix
    extra = max(0, places)
    return Written(mantissa * 10**extra, max(0, -places), suffix, exponent - extra)


def _unit_parts(unit: str) -> tuple[int, str, str]:
    """(power of ten of the declared unit over its base, the base unit, the base a prefix may go on or "")."""
    power = _POWER_UNIT.fullmatch(unit)
    if power:
        return int(power[1].translate(_FROM_SUPERSCRIPT)), "", ""
    match = _UNIT.fullmatch(unit)
    if not match:
        return 0, unit, ""
    return _POWER_OF[match[1]], f"{match[2]}{match[3]}", match[2]


def significant_text(value: float, digits: int, unit: str) -> str:
    """One value as the page shows it to `digits` significant digits, e.g. (0.000564, 4, "J/m³") -> '564.0 µJ/m³'."""
    mantissa, exponent = significant([value], digits)
    form = written(int(mantissa[0]), int(exponent[0]), digits, unit)
    return format_quantum(form.shown, form.decimals) + form.suffix


def with_unit(text: str, unit: str) -> str:
    """A value and its unit; "×" and "°" hug the number ("1.00×", "90°"), other units are spaced."""
    if not unit:
        return text
    return f"{text}{unit}" if unit in ("×", "°") else f"{text} {unit}"

"""Numbers as the page shows them: integers counting units of the last displayed digit."""

from __future__ import annotations

import re
from dataclasses import dataclass

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
# Every number a page shows is rounded the way a printed table is: to the nearest digit, and a value half-way
# (0.125 to two decimals, 19.375 to two, -0.5625 to three) away from zero. "Half-way" is judged to 12 significant
# digits: a double computed from decimal inputs is off by about 1e-16, so 47.5 × 0.23 / 2, stored as
# 5.46250000000000036, and the same value interpolated by the page a few units of its last place below 5.4625,
# both read 5.463, as the exact 5.4625 does; 1.005, stored as 1.00499999999999989, reads 1.01. Tables are rounded here;
# the page's script rounds an expression's value by the same steps in
# the same order (sitegen.js toQuantum), and the build's digit comparison rounds by this rule.

TIE = 1e-12  # relative: a value this close to half a digit is half-way
_CHUNK = 1 << 16  # values rounded at a time (tables run to millions: the temporaries stay small)


def shown_integers(values, power=0) -> np.ndarray:
    """values × 10**power rounded to integers by the pages' rule (int64); `power` may be an array (one each)."""
    values = np.asarray(values, dtype=float)
    out = np.empty(values.shape, dtype=np.int64)
    flat, flat_out = values.reshape(-1), out.reshape(-1)
    powers = None if np.ndim(power) == 0 else np.broadcast_to(np.asarray(power), values.shape).reshape(-1)
    scratch = _Scratch(min(flat.size, _CHUNK))
    for start in range(0, flat.size, _CHUNK):
        part = slice(start, start + _CHUNK)
        flat_out[part] = scratch.half_away(flat[part], power if powers is None else powers[part])
    return out


class _Scratch:
    """Three reused blocks for the rule's steps: a table of millions of values rounds without allocating."""

    def __init__(self, size: int):
        self.scaled, self.whole, self.rest = np.empty(size), np.empty(size), np.empty(size)

    def half_away(self, values: np.ndarray, powers) -> np.ndarray:
        """The rule on one block, in sitegen.js toQuantum's steps: |x| split into its whole part and the rest,
        which rounds up from half a digit less 1e-12 of the value (of one digit, below 1)."""
        n = values.size
        scaled, whole, rest = self.scaled[:n], self.whole[:n], self.rest[:n]
        if np.ndim(powers) == 0 and powers >= 0:  # exact up to 10**22, as the script's Math.pow(10, d)
            np.multiply(values, 10.0**powers, out=scaled)
        elif np.ndim(powers) == 0:
            np.divide(values, 10.0**-powers, out=scaled)
        else:
            scales = 10.0 ** np.abs(powers)
            scaled[:] = np.where(powers >= 0, values * scales, values / scales)
        np.abs(scaled, out=rest)
        np.floor(rest, out=whole)
        rest -= whole  # the part below one unit
        threshold = np.maximum(whole, 1.0)
        threshold *= TIE
        np.subtract(0.5, threshold, out=threshold)
        whole += rest >= threshold
        np.copysign(whole, scaled, out=whole)
        return whole.astype(np.int64)  # -0.0 becomes plain 0: integers carry no sign of zero


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
    10**exponent with `digits` digits in the mantissa (zero as 0 × 10**0), by the pages' rule (a tie away
    from zero). With
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
    # Formatting rounds the double correctly, a tie to even; the pages' rule takes over at the digit it chose, and
    # where that carries into one digit more (9.995 -> 10.00), the last digit goes one place up.
    kept_mantissas = shown_integers(np.asarray(kept, dtype=float), -both[1::2])
    carried = np.abs(kept_mantissas) >= 10**digits
    both[0::2] = np.where(carried, kept_mantissas // 10, kept_mantissas)
    both[1::2] += carried
    mantissas[shown], exponents[shown] = both[0::2], both[1::2]
    return mantissas, exponents


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

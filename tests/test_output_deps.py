"""Every output's declared `deps` are exactly the parameters it depends on: none missing, none superfluous.

The build tabulates an output only over its deps, so a missing dep freezes a slider's effect and a superfluous
one wastes table bytes. The check is the one every build runs on a scene and a book's tests call
(`sitegen.testing.deps_problems`); here it runs on each built-in model across its whole domain, under each
effect set that changes what an output depends on.
"""

from __future__ import annotations

import functools

import pytest

from sitegen.registry import builtin_registry
from sitegen.testing import deps_problems

MODELS = builtin_registry().models
POINTS = 16  # seeded points of the domain per model and effect set, each parameter moved once from each
SEED = 20240611


def _effect_sets(model, output) -> list[frozenset[str]]:
    """The effect sets an output's deps are checked under: the effects it needs (its own and those of
    its parameters), and that set plus each effect that changes its deps (`deps_with`)."""
    declared = model.output(output.name)
    base = frozenset(e for e in (declared.effect, *(model.param(d).effect for d in declared.deps)) if e)
    extra = [
        base | {effect} | {model.param(d).effect for d in deps if model.param(d).effect}
        for effect, deps in declared.deps_with
    ]
    return list(dict.fromkeys([base, *extra]))


CASES = [
    pytest.param(model, output.name, effects, id=f"{name}-{output.name}" + "".join(f"+{e}" for e in sorted(effects)))
    for name, model in MODELS.items()
    for output in model.outputs
    for effects in _effect_sets(model, output)
]


@functools.cache  # every output of a model under one effect set is checked by one evaluation
def _problems(model, effects: frozenset[str]) -> tuple[str, ...]:
    return tuple(deps_problems(model(), effects, points=POINTS, seed=SEED, moves=1))


def _of(model, output: str, effects, kind: str) -> list[str]:
    """The problems of one output: its undeclared dependencies ("changes with") or its inert deps ("declares")."""
    return [p for p in _problems(model, effects) if f" output '{output}' {kind} " in f" {p.split(': ', 1)[1]}"]


# the bubble's outputs each solve its ODE at every point moved, seconds apiece: left to `make test`
MOVED_CASES = [
    pytest.param(*case.values, id=case.id, marks=pytest.mark.slow if case.values[0].name == "bubble" else ())
    for case in CASES
]


@pytest.mark.parametrize("model, output, effects", MOVED_CASES)
def test_output_ignores_parameters_outside_its_deps(model, output, effects):
    """Moving a parameter its deps leave out (under the effects) changes the output at no seeded point."""
    assert _of(model, output, effects, "changes with") == []


# The "responds" half needs points that move each dep enough to show; it is skipped where that cannot be had
# cheaply: the bubble's outputs come from ODE runs whose events and thresholds (Mach 0.2, the Blake radius, a
# stiffness limit) random points rarely cross, and acoustic_energy's validity flips at 154 dB, far outside the
# sampled levels; the chain's status flips at σ/a = 1, where the ends move a by one spacing. Their models' own
# tests cover those dependencies; the half above runs for them too. Two outputs are conserved by design, computed
# at every stop only to show that they stay the same (up to rounding): the acoustic power through a sphere of
# radius r, and the momentum after a collision.
THRESHOLD_MODELS = {"bubble"}
THRESHOLD_PHRASES = {("acoustic_energy", "validity"), ("chain", "status")}
CONSERVED = {("acoustic_energy", "power"), ("collision", "p_after")}
RESPONDING_CASES = [
    case
    for case in CASES
    if case.values[0].name not in THRESHOLD_MODELS
    and (case.values[0].name, case.values[1]) not in THRESHOLD_PHRASES | CONSERVED
]


@pytest.mark.parametrize("model, output, effects", RESPONDING_CASES)
def test_output_responds_to_every_declared_dep(model, output, effects):
    """Moving each dep (under the effects) changes the output at some seeded point (no superfluous dep)."""
    assert _of(model, output, effects, "declares") == []


@pytest.mark.parametrize("model, output, effects", CASES)
def test_deps_name_declared_parameters(model, output, effects):
    """Every dep of an output is one of the model's parameters, listed once, and every effect that
    changes its deps is one the model offers."""
    declared = model.output(output)
    deps = declared.deps + tuple(d for _, extra in declared.deps_with for d in extra)
    assert set(deps) <= {p.name for p in model.params}
    assert len(set(declared.deps)) == len(declared.deps)
    assert {effect for effect, _ in declared.deps_with} <= set(model.effects)

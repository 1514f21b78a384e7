"""The hard-case index of the models' references is covered: every entry maps to tests that exist in tests/.

The table below maps each hard case to the pytest node ids that test it (a function id covers all its
parametrized cases; an id with [...] names one case). The ids are checked against what pytest itself
collects, so a renamed or deleted test, or an entry whose test has not been written yet, fails here by
name.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

COLLISION = "tests/test_collision_model.py::"
WORK = "tests/test_work_model.py::"
LEVER = "tests/test_lever_model.py::"
CHAIN = "tests/test_chain_model.py::"
KINETIC = "tests/test_kinetic_model.py::"
SLAB = "tests/test_euler_slab_model.py::"
BUBBLE = "tests/test_bubble_model.py::"
BUBBLE_HARD = "tests/test_bubble_hard_cases.py::"
ACOUSTIC = "tests/test_acoustic_energy_model.py::"
PROPERTIES = "tests/test_properties.py::"
EXTRA = "tests/test_hard_cases_extra.py::"

# Hard case (category: entry) -> the tests that cover it.
INDEX: dict[str, list[str]] = {
    # --- Cancellation ---------------------------------------------------------------------------------------
    "Cancellation: I2 mass ratio, and K lost by subtraction": [
        COLLISION + "test_final_velocity_at_extreme_mass_ratio",  # ≤ 4ε max|v| at m2/m1 = 1e±9, 1e±15
        COLLISION + "test_kinetic_energy_lost_when_much_smaller_than_K",  # ≤ 8ε rel at m1/m2 = 1e±9, 1e±15
        PROPERTIES + "test_collision_final_velocities_are_the_exact_rationals",  # any ratio 1e−15…1e15
        PROPERTIES + "test_collision_energy_lost_is_the_exact_closed_form",
    ],
    "Cancellation: K3 absolute-pressure differences": [
        SLAB + "test_net_force_product_form_within_1e14_of_50_digit_reference",  # Δx/λ ∈ [1e−8, 0.5]
        SLAB + "test_absolute_pressure_difference_loses_digits_as_physics_md_measured",  # the naive form fails
        SLAB + "test_difference_of_perturbations_is_far_less_accurate_than_the_product",
    ],
    "Cancellation: K5 $1-R_r^2$": [
        ACOUSTIC + "test_one_minus_R_squared_is_computed_without_cancellation",
        ACOUSTIC + "test_naive_one_minus_R_squared_would_lose_digits_near_one",
        ACOUSTIC + "test_standing_wave_carries_exactly_zero_mean_intensity",
    ],
    # --- Branches and non-events ----------------------------------------------------------------------------
    "Branches and non-events: I2 separating bodies": [
        COLLISION + "test_no_contact_when_not_approaching",  # v_f == v_i bitwise at every stop with v1i ≤ v2i
        PROPERTIES + "test_bodies_that_do_not_approach_keep_their_velocities_bitwise",
    ],
    "Branches and non-events: I3 h → 0 verdict": [
        WORK + "test_drag_verdict_comes_from_the_force_not_from_comparing_paths",  # h ∈ {0, 1e−12, ...}
        WORK + "test_drag_costs_more_on_the_arc_by_the_extra_length",  # −bs(L_arc − c) within 1e−12 rel
        WORK + "test_spring_work_is_the_same_on_both_paths",  # |W_arc − W_dir| ≤ 1e−12 J
    ],
    "Branches and non-events: I4 balance off-grid": [
        LEVER + "test_off_grid_balance_point_balances_exactly_the_nearest_stop",
        LEVER + "test_off_grid_nearest_stop_shows_a_small_net_torque",  # −0.0981 N·m shown "−0.10"
        LEVER + "test_off_grid_balance_marker_is_shown",
        LEVER + "test_every_mass_pair_has_one_or_two_balanced_stops",
    ],
    "Branches and non-events: K4 Blake threshold": [
        BUBBLE + "test_ramp_across_the_blake_threshold",  # bounded at depth 0.99, unbounded at 1.01 (R0 = 1 µm)
        BUBBLE + "test_blake_threshold_is_the_minimum_of_the_quasi_static_pressure",
        BUBBLE_HARD + "test_blake_nucleus_just_short_of_the_threshold_settles",  # every R0 of the grid, 10x hold
        BUBBLE_HARD + "test_blake_nucleus_just_past_the_threshold_keeps_growing",
    ],
    "Branches and non-events: K4 resonance foldover": [
        EXTRA + "test_resonance_response_jumps_between_adjacent_frequencies_so_interpolation_fails",
        EXTRA + "test_resonance_readout_is_tabulated_at_every_stop_never_interpolated",
    ],
    # --- Singularities --------------------------------------------------------------------------------------
    "Singularities: I4 MA pole": [
        LEVER + "test_pivot_at_the_end",  # MA = ∞ sentinel, null in strict JSON, "∞" phrase; MA(0) = 0.00
    ],
    "Singularities: K4 R → 0 (event + guards; LSODA hang)": [
        BUBBLE_HARD + "test_every_solver_returns_within_an_evaluation_budget_at_every_preset_A_stop",
        BUBBLE_HARD + "test_collapse_without_terminal_events_is_stopped_by_the_guards",
        BUBBLE_HARD + "test_the_cap_counts_evaluations_so_a_capped_solve_ends_the_same_way_every_time",
    ],
    "Singularities: vdW R ≤ h": [
        BUBBLE_HARD + "test_reaching_the_hard_core_reports_a_loose_tolerance",
    ],
    "Singularities: KM Ṙ → c": [
        BUBBLE_HARD + "test_keller_miksis_run_stops_at_0_9_c",
        BUBBLE_HARD + "test_keller_miksis_start_beyond_0_9_c_is_refused",
        BUBBLE_HARD + "test_keller_miksis_right_hand_side_stays_finite_as_the_denominator_vanishes",
        BUBBLE_HARD + "test_keller_miksis_empty_collapse_stops_at_0_9_c",
    ],
    "Singularities: K5 $L_I$ = −∞": [
        ACOUSTIC + "test_standing_wave_level_is_minus_infinity_and_marked_special",
        ACOUSTIC + "test_standing_wave_level_is_shown_as_a_dash_and_the_json_is_valid",
    ],
    "Singularities: JSON NaN/Inf": [
        "tests/test_build.py::test_scene_tables_are_strict_json",
        "tests/test_author_errors.py::test_non_finite_output_fails_the_build_naming_the_stop",
        BUBBLE + "test_read_run_never_returns_nan_outside_the_curve_padding",
    ],
    # --- Integrators that mislead ---------------------------------------------------------------------------
    "Integrators that mislead: I5 VV at ν = 1 equals the continuum": [
        CHAIN + "test_verlet_at_the_magic_step_reproduces_the_string",  # ≤ 1.5e−8 A
        CHAIN + "test_exact_chain_keeps_its_dispersion_at_the_magic_step_case",  # dev ≥ 0.4 (measured 0.488)
        CHAIN + "test_exact_chain_agrees_with_a_dense_reference_at_the_magic_step_case",  # DST vs DOP853 1e−9
    ],
    "Integrators that mislead: VV energy near the CFL limit": [
        CHAIN + "test_verlet_energy_near_the_limit_is_not_conserved",
    ],
    "Integrators that mislead: VV past the CFL limit blows up": [
        CHAIN + "test_verlet_refuses_steps_at_or_past_the_stability_limit",
        CHAIN + "test_verlet_just_inside_the_limit_stays_bounded",
    ],
    "Integrators that mislead: K4 dense output near collapse": [
        BUBBLE_HARD + "test_plotted_layer_near_collapse_is_within_1e_3",
    ],
    "Integrators that mislead: K4 SI units with default atol": [
        BUBBLE_HARD + "test_si_units_with_default_atol_fail_where_nondimensional_units_succeed",
    ],
    "Integrators that mislead: K4 without KM is ill-conditioned": [
        BUBBLE_HARD + "test_violent_collapse_without_keller_miksis_is_flagged_invalid",
        BUBBLE_HARD + "test_mildly_driven_incompressible_bubble_past_0_2_c_is_flagged",
    ],
    "Integrators that mislead: K2 fixed-step reflection": [
        KINETIC + "test_fixed_step_reflection_loses_pressure_but_exact_counting_does_not",
    ],
    # --- Stiffness ------------------------------------------------------------------------------------------
    "Stiffness: K4 viscous micro-bubble (explicit methods 1000× slower)": [
        BUBBLE_HARD + "test_stiff_viscous_microbubble_gets_an_implicit_solver_under_5000_evaluations",
        BUBBLE_HARD + "test_stiff_viscous_microbubble_exhausts_an_explicit_solver",
    ],
    # --- Determinism ----------------------------------------------------------------------------------------
    "Determinism: K2 RNG streams (quantile default)": [
        EXTRA + "test_quantile_default_never_draws_from_numpys_generators",
        KINETIC + "test_same_inputs_give_bitwise_the_same_outputs",
        KINETIC + "test_random_sample_pressure_scatters_as_sqrt_2_over_N",  # random mode: statistical only
        KINETIC + "test_maxwell_wall_path_does_not_depend_on_the_windows_asked_for",
    ],
    "Determinism: §0.3 signed zero": [
        "tests/test_quantize.py::test_fmt[-1e-17-is-unsigned-zero]",  # fmt(−1e−17, 3) == "0.000"
        "tests/test_quantize.py::test_quantize_folds_negative_zero",
        WORK + "test_zero_work_is_shown_unsigned",
    ],
    # --- Tests that pass vacuously --------------------------------------------------------------------------
    "Tests that pass vacuously: I3 symmetric anchor": [
        WORK + "test_quadrature_of_the_spring_work_equals_the_potential_drop",  # x_c ∈ {−0.5, 0, 0.5}
        WORK + "test_sixteen_nodes_are_not_enough_on_the_arc_with_a_rest_length",  # x_c = 0.5 catches n = 16
        PROPERTIES + "test_spring_work_is_path_independent_by_quadrature",  # any anchor
    ],
    "Tests that pass vacuously: K5 matched FD steps": [
        ACOUSTIC + "test_matched_steps_make_the_balance_test_vacuous",
        ACOUSTIC + "test_local_balance_by_finite_differences_with_mismatched_steps",
        ACOUSTIC + "test_mismatched_steps_catch_a_wrong_intensity",
    ],
}


@pytest.fixture(scope="module")
def collected(collected_ids) -> tuple[set[str], set[str], str]:
    """(node ids, function ids, pytest's complaints) of every test pytest collects in tests/: this run's
    own collection when it took in every test file, else a collection of its own in a subprocess."""
    every_file = {f"tests/{path.name}" for path in (ROOT / "tests").glob("test_*.py")}
    if {node.split("::", 1)[0] for node in collected_ids} == every_file:
        nodes, errors = set(collected_ids), ""
    else:
        env = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}
        result = subprocess.run(
            [sys.executable, "-m", "pytest", "--collect-only", "-q", "-p", "no:cacheprovider", "tests"],
            cwd=ROOT,
            env=env,
            capture_output=True,
            text=True,
            timeout=600,
        )
        nodes = {line.strip() for line in result.stdout.splitlines() if "::" in line and not line.startswith(" ")}
        errors = (
            "\n".join(line for line in result.stdout.splitlines() if line.startswith(("ERROR", "E ")))
            or result.stderr[-2000:]
        )
        errors = errors if result.returncode else ""
    return nodes, {node.split("[", 1)[0] for node in nodes}, errors


@pytest.mark.parametrize("entry", list(INDEX), ids=[re.sub(r"\W+", "-", e).strip("-") for e in INDEX])
def test_hard_case_is_covered_by_existing_tests(entry, collected):
    """Each hard case maps to at least one test, and every test the table names exists in tests/."""
    nodes, functions, errors = collected
    assert INDEX[entry], f"hard case '{entry}': no test listed"
    missing = [t for t in INDEX[entry] if t not in (nodes if "[" in t else functions)]
    assert not missing, f"hard case '{entry}' is not covered: missing test(s) {missing}" + (
        f"\npytest could not collect:\n{errors}" if errors else ""
    )

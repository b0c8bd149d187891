"""The solver policy's ladders, solve by solve: a scripted back end records every ask
(back end, settings, the next solve's settings ``after``) and answers in turn; each row
gives the asks the policy's rules imply (rigidblocks/solvers/policy.py, module docstring
and the declarations of the ladders), written out by hand from them:

* a verdict: tight (1e-10) with Clarabel given the next solve's settings, a refined
  retry after a failure within REFINE_WITHIN iterations, then 1e-9 (where later tight
  solves start), given the defaults, then the defaults; a failure whose last iterate
  meets the next solve's tolerances is that solve's answer;
* a value: tight with VALUE_SETTINGS and never given the next solve, retried without
  them (later solves go without them where that answers), refined, then 1e-9 with them,
  then the defaults; FINER_SETTINGS first, checked, where a search asks;
* a confirmation: Clarabel at CONFIRM_SETTINGS alone, the verdict's ladder where that
  fails, the verdict's run where a back end's answer fails its check;
* a force state: the defaults once; an estimate: the defaults, refined;
* LP-only back ends hand a QP to Clarabel; an answer that fails its check, or a back
  end that fails, is solved again by Clarabel up the tight form of the ladder; a linear
  program on which Clarabel fails is solved by HiGHS.
"""

from __future__ import annotations

import math
from dataclasses import replace
from types import SimpleNamespace

import pytest

from rigidblocks.errors import SolverFailure
from rigidblocks.solvers import policy
from rigidblocks.solvers.base import SolverResult
from rigidblocks.solvers.policy import (
    CONFIRM_BY,
    CONFIRMATION,
    ESTIMATE,
    FINER_VALUE,
    REFINE_WITHIN,
    STATE,
    VALUE,
    VERDICT,
    Runner,
    ladder_of,
)

C = "clarabel"
T = policy.TIGHT_SETTINGS[C]  # 1e-10
N = policy.NEAR_TIGHT_SETTINGS[C]  # 1e-9
V = policy.VALUE_SETTINGS[C]
F = policy.FINER_SETTINGS[C]
R = policy.REFINE_SETTINGS[C]
CS = policy.CONFIRM_SETTINGS
D: dict = {}  # a back end's defaults
U = {"max_iter": 50}  # a user's setting, on top of every rung
UR = {"static_regularization_constant": 1e-9}  # a user's setting that REFINE_SETTINGS has


def on(*parts: dict) -> dict:
    """Settings ``parts`` merged, later ones on top."""
    out: dict = {}
    for p in parts:
        out.update(p)
    return out


#: the scripted answers: status, iterations, whether the last iterate meets the next
#: solve's tolerances, and whether the answer fails the policy's check
ANSWERS = {
    "ok": ("optimal", 10, False, False),
    "bad": ("optimal", 10, False, True),  # fails the residual check
    "stalled": ("optimal", 120, True, False),  # stopped where it met the next tolerances
    "few": ("failure", REFINE_WITHIN - 1, False, False),  # within REFINE_WITHIN
    "many": ("failure", REFINE_WITHIN, False, False),  # not within it
    "met": ("failure", 12, True, False),  # last iterate meets the next solve's
    "met-many": ("failure", 150, True, False),
    "none": ("infeasible", 10, False, False),  # with a certificate that passes
}


class Script:
    """A back end that answers the k-th solve with the k-th scripted answer and records
    what it was asked; a failure's raw status names its solve (``few #3``), so that an
    error message says which solve it reports."""

    def __init__(self, answers: list[str]):
        self.answers, self.asked = list(answers), []

    def __call__(self, problem, solver="clarabel", after=None, **settings) -> SolverResult:
        self.asked.append((solver, settings, after))
        assert self.answers, f"solve #{len(self.asked)} not scripted: {self.asked[-1]}"
        tag = self.answers.pop(0)
        status, iterations, met, bad = ANSWERS[tag]
        # (an infeasible answer with its certificate, the duals)
        y = [0.0] if status == "infeasible" else None
        return SolverResult(status, None, y, 1.0 if status == "optimal" else math.nan,
                            solver, f"{tag} #{len(self.asked)}", iterations=iterations,
                            next_met=met)


def checked(problem, res: SolverResult) -> SolverResult:
    """The policy's check, as the script says: a "bad" answer fails it."""
    bad = res.raw_status.startswith("bad")
    return replace(res, residuals={"primal": 1e-3 if bad else 1e-12}, verified=not bad)


#: a problem without a quadratic term whose cones are not all linear (the HiGHS rescue of
#: a linear program on which Clarabel fails does not apply: see
#: test_a_linear_program_on_which_clarabel_fails_is_solved_by_highs)
LP = SimpleNamespace(P=None, is_lp=False)
QP = SimpleNamespace(P="a quadratic term", is_lp=False)

# (name, back end, user settings, ladder, problem, known out of reach (tight, value),
#  answers, expected asks, expected answer: a status, or the SolverFailure message,
#  learnt out of reach (tight, value) afterwards)
CASES = [
    # -- a verdict ----------------------------------------------------------------
    ("verdict answered at 1e-10", C, {}, VERDICT, LP, ((), ()),
     ["ok"], [(C, T, N)], "optimal", ((), ())),
    ("verdict refined within REFINE_WITHIN", C, {}, VERDICT, LP, ((), ()),
     ["few", "ok"], [(C, T, N), (C, on(T, R), None)], "optimal", ((), ())),
    ("verdict failing everywhere", C, {}, VERDICT, LP, ((), ()),
     ["few", "few", "few", "many"],
     [(C, T, N), (C, on(T, R), None), (C, N, D), (C, D, None)],
     "clarabel could not solve the relaxation problem of the scene: status many #4",
     ((C,), ())),
    ("verdict failing after REFINE_WITHIN: 1e-9 next", C, {}, VERDICT, LP, ((), ()),
     ["many", "ok"], [(C, T, N), (C, N, D)], "optimal", ((C,), ())),
    ("verdict stalled with 1e-9 met", C, {}, VERDICT, LP, ((), ()),
     ["stalled"], [(C, T, N)], "optimal", ((C,), ())),
    ("verdict ended with 1e-9 met", C, {}, VERDICT, LP, ((), ()),
     ["met-many"], [(C, T, N)], "optimal", ((C,), ())),
    ("verdict ended with 1e-9 met, refined retry first", C, {}, VERDICT, LP, ((), ()),
     ["met", "few"], [(C, T, N), (C, on(T, R), None)], "optimal", ((C,), ())),
    ("verdict 1e-9 ended with the defaults met", C, {}, VERDICT, LP, ((), ()),
     ["many", "met"], [(C, T, N), (C, N, D)], "optimal", ((C,), ())),
    ("verdict starting at 1e-9 once out of reach", C, {}, VERDICT, LP, ((C,), ()),
     ["few", "few", "ok"], [(C, N, D), (C, on(N, R), None), (C, D, None)], "optimal",
     ((C,), ())),
    ("verdict at 1e-9 ended with the defaults met", C, {}, VERDICT, LP, ((C,), ()),
     ["met-many"], [(C, N, D)], "optimal", ((C,), ())),
    ("verdict with a user's setting on every rung", C, U, VERDICT, LP, ((), ()),
     ["few", "few", "many", "ok"],
     [(C, on(T, U), on(N, U)), (C, on(T, R, U), None), (C, on(N, U), U), (C, U, None)],
     "optimal", ((C,), ())),
    ("verdict not refined where the user set a refined setting", C, UR, VERDICT, LP,
     ((), ()), ["few", "few", "ok"],
     [(C, on(T, UR), on(N, UR)), (C, on(N, UR), UR), (C, UR, None)], "optimal",
     ((C,), ())),
    ("verdict without its refined retry", C, {}, ladder_of(tight=True, refine=False), LP,
     ((), ()), ["few", "few", "ok"], [(C, T, N), (C, N, D), (C, D, None)], "optimal",
     ((C,), ())),
    ("verdict by SCS: tight, then its defaults", "scs", {"verify": False}, VERDICT, LP,
     ((), ()), ["few", "ok"],
     [("scs", policy.SCS_TIGHT, D), ("scs", D, None)], "optimal", ((), ())),
    ("verdict by HiGHS: its defaults alone", "highs", {"verify": False}, VERDICT, LP,
     ((), ()), ["few"], [("highs", D, None)],
     "highs could not solve the relaxation problem of the scene: status few #1",
     ((), ())),
    # -- a value --------------------------------------------------------------------
    ("value answered", C, {}, VALUE, LP, ((), ()),
     ["ok"], [(C, on(T, V), None)], "optimal", ((), ())),
    ("value answered without VALUE_SETTINGS", C, {}, VALUE, LP, ((), ()),
     ["few", "ok"], [(C, on(T, V), None), (C, T, None)], "optimal", ((), (C,))),
    ("value answered refined", C, {}, VALUE, LP, ((), ()),
     ["few", "few", "ok"], [(C, on(T, V), None), (C, T, None), (C, on(T, R), None)],
     "optimal", ((), ())),
    ("value failing everywhere", C, {}, VALUE, LP, ((), ()),
     ["few", "few", "few", "few", "few"],
     [(C, on(T, V), None), (C, T, None), (C, on(T, R), None), (C, on(N, V), None),
      (C, D, None)],
     "clarabel could not solve the relaxation problem of the scene: status few #5",
     ((C,), ())),
    ("value failing after REFINE_WITHIN", C, {}, VALUE, LP, ((), ()),
     ["many", "ok"], [(C, on(T, V), None), (C, on(N, V), None)], "optimal", ((C,), ())),
    ("value once VALUE_SETTINGS were out of reach", C, {}, VALUE, LP, ((), (C,)),
     ["few", "few", "ok"], [(C, T, None), (C, on(T, R), None), (C, N, None)], "optimal",
     ((C,), (C,))),
    ("value once 1e-10 was out of reach", C, {}, VALUE, LP, ((C,), ()),
     ["few", "few", "few", "ok"],
     [(C, on(N, V), None), (C, N, None), (C, on(N, R), None), (C, D, None)], "optimal",
     ((C,), ())),
    ("value without its retries", C, {}, ladder_of(tight=True, stall=False, refine=False),
     LP, ((), ()), ["few", "ok"], [(C, on(T, V), None), (C, on(N, V), None)], "optimal",
     ((C,), ())),
    ("value at FINER_SETTINGS first", C, {}, FINER_VALUE, LP, ((), ()),
     ["ok"], [(C, on(T, F), None)], "optimal", ((), ())),
    ("value at FINER_SETTINGS failing", C, {}, FINER_VALUE, LP, ((), ()),
     ["few", "ok"], [(C, on(T, F), None), (C, on(T, V), None)], "optimal", ((), ())),
    ("value at FINER_SETTINGS failing its check", C, {}, FINER_VALUE, LP, ((), ()),
     ["bad", "ok"], [(C, on(T, F), None), (C, on(T, V), None)], "optimal", ((), ())),
    ("value at FINER_SETTINGS at 1e-10 even out of reach", C, U, FINER_VALUE, LP,
     ((C,), ()), ["few", "ok"], [(C, on(T, F, U), None), (C, on(N, V, U), None)],
     "optimal", ((C,), ())),
    # -- a confirmation -------------------------------------------------------------
    ("confirmation by Clarabel, at its settings alone", C, U, CONFIRMATION, LP, ((), ()),
     ["ok"], [(C, CS, None)], "optimal", ((), ())),
    ("confirmation failing: the verdict's ladder", C, {}, CONFIRMATION, LP, ((), ()),
     ["few", "few", "ok"], [(C, CS, None), (C, T, N), (C, on(T, R), None)], "optimal",
     ((), ())),
    ("confirmation by OSQP", "osqp", {"eps_abs": 1e-5}, CONFIRMATION, LP, ((), ()),
     ["ok"], [("osqp", CONFIRM_BY["osqp"], None)], "optimal", ((), ())),
    ("confirmation by OSQP failing its check: the verdict", "osqp", {}, CONFIRMATION, LP,
     ((), ()), ["bad", "ok"], [("osqp", CONFIRM_BY["osqp"], None), ("osqp", D, None)],
     "optimal", ((), ())),
    ("confirmation by OSQP failing: its verdict ladder", "osqp", U, CONFIRMATION, LP,
     ((), ()), ["few", "ok"],
     [("osqp", on(U, CONFIRM_BY["osqp"]), None), ("osqp", U, None)], "optimal",
     ((), ())),
    ("confirmation by OSQP failing twice", "osqp", U, CONFIRMATION, LP, ((), ()),
     ["few", "few"], [("osqp", on(U, CONFIRM_BY["osqp"]), None), ("osqp", U, None)],
     "osqp could not solve the relaxation problem of the scene: status few #2", ((), ())),
    ("confirmation by HiGHS: the verdict again", "highs", {}, CONFIRMATION, LP, ((), ()),
     ["ok"], [("highs", D, None)], "optimal", ((), ())),
    # -- a force state, an estimate -------------------------------------------------
    ("state at the defaults", C, U, STATE, QP, ((), ()), ["ok"], [(C, U, None)],
     "optimal", ((), ())),
    ("state failing: once", C, {}, STATE, QP, ((), ()), ["few"], [(C, D, None)],
     "clarabel could not solve the relaxation problem of the scene: status few #1",
     ((), ())),
    ("state of an LP-only back end: Clarabel", "highs", {"time_limit": 5}, STATE, QP,
     ((), ()), ["ok"], [(C, D, None)], "optimal", ((), ())),
    ("estimate at the defaults, refined", C, {}, ESTIMATE, LP, ((), ()),
     ["few", "ok"], [(C, D, None), (C, R, None)], "optimal", ((), ())),
    ("estimate failing, refined", C, {}, ESTIMATE, LP, ((), ()),
     ["few", "few"], [(C, D, None), (C, R, None)],
     "clarabel could not solve the relaxation problem of the scene: status few #2",
     ((), ())),
    ("estimate failing after REFINE_WITHIN", C, {}, ESTIMATE, LP, ((), ()),
     ["many"], [(C, D, None)],
     "clarabel could not solve the relaxation problem of the scene: status many #1",
     ((), ())),
    # -- answers solved again by Clarabel -------------------------------------------
    ("estimate by Clarabel failing its check: tight", C, {}, ESTIMATE, LP, ((), ()),
     ["bad", "few", "ok"], [(C, D, None), (C, T, N), (C, on(T, R), None)], "optimal",
     ((), ())),
    ("verdict by Clarabel failing its check: as it is", C, {}, VERDICT, LP, ((), ()),
     ["bad"], [(C, T, N)], "optimal", ((), ())),
    ("verdict by Clarabel failing its check with a user's setting", C, U, VERDICT, LP,
     ((), ()), ["bad", "ok"], [(C, on(T, U), on(N, U)), (C, T, N)], "optimal", ((), ())),
    ("state by OSQP failing its check: tight, not refined", "osqp", {}, STATE, QP,
     ((), ()), ["bad", "few", "ok"], [("osqp", D, None), (C, T, N), (C, N, D)],
     "optimal", ((C,), ())),
    ("verdict by HiGHS failing: Clarabel", "highs", {}, VERDICT, LP, ((), ()),
     ["few", "ok"], [("highs", D, None), (C, T, N)], "optimal", ((), ())),
    ("value by OSQP failing its check: Clarabel's value", "osqp", {}, FINER_VALUE, LP,
     ((), ()), ["bad", "few", "ok"], [("osqp", D, None), (C, on(T, V), None), (C, T, None)],
     "optimal", ((), (C,))),
    ("verdict by OSQP failing, Clarabel too", "osqp", {}, VERDICT, LP, ((), ()),
     ["many", "many", "many", "many"],
     [("osqp", D, None), (C, T, N), (C, N, D), (C, D, None)],
     "clarabel could not solve the relaxation problem of the scene: status many #4",
     ((C,), ())),
    ("verdict by OSQP failing its check, Clarabel failing", "osqp", {}, VERDICT, LP,
     ((), ()), ["bad", "many", "many", "many"],
     [("osqp", D, None), (C, T, N), (C, N, D), (C, D, None)], "optimal", ((C,), ())),
]


@pytest.mark.parametrize(
    "name, solver, settings, ladder, problem, known, answers, asks, answer, learnt",
    CASES, ids=[c[0] for c in CASES])
def test_a_ladder_asks_its_rungs_in_order(monkeypatch, name, solver, settings, ladder,
                                          problem, known, answers, asks, answer, learnt):
    script = Script(answers)
    monkeypatch.setattr(policy, "solve", script)
    monkeypatch.setattr(policy, "verified", checked)
    runner = Runner(solver, settings)
    runner.out_of_reach.update(known[0])
    runner.value_out_of_reach.update(known[1])
    if answer != "optimal":
        with pytest.raises(SolverFailure) as exc:
            runner.run(problem, "relaxation", ladder)
        assert str(exc.value) == answer
    else:
        assert runner.run(problem, "relaxation", ladder).status == answer
    assert script.asked == asks
    assert not script.answers, "scripted answers left unasked"
    assert runner.n_solves == len(asks)
    assert (sorted(runner.out_of_reach), sorted(runner.value_out_of_reach)) == \
        tuple(sorted(x) for x in learnt)


def test_a_runner_afresh_neither_uses_nor_keeps_what_it_learns(monkeypatch):
    """Inside ``Runner.afresh()`` the solves run as a fresh runner's would (Clarabel's
    tight settings tried again although known out of reach before) and learn as they do
    outside (the value case above: out of reach); after the block the runner knows
    what it knew before it (the non-associative friction's trials each run so)."""
    script = Script(["bad", "few", "ok"])
    monkeypatch.setattr(policy, "solve", script)
    monkeypatch.setattr(policy, "verified", checked)
    runner = Runner("osqp", {})
    runner.out_of_reach.add(C)
    with runner.afresh():
        runner.run(LP, "relaxation", FINER_VALUE)
        assert (runner.out_of_reach, runner.value_out_of_reach) == (set(), {C})
    assert script.asked == [("osqp", D, None), (C, on(T, V), None), (C, T, None)]
    assert (runner.out_of_reach, runner.value_out_of_reach) == ({C}, set())


def test_a_rejected_answer_is_noted_with_its_reason(monkeypatch):
    """An answer that fails its check, or a back end that fails, is solved again by
    Clarabel; the runner notes it and the answer carries the reason."""
    monkeypatch.setattr(policy, "verified", checked)
    for solver, answers, why in (
            ("osqp", ["bad", "ok"], "osqp optimal: primal residual 1.0e-03"),
            ("highs", ["many", "ok"], "highs ended with status many #1")):
        monkeypatch.setattr(policy, "solve", Script(answers))
        runner = Runner(solver)
        res = runner.run(LP, "relaxation", VERDICT)
        assert res.solver == C and res.residuals["rejected"] == why
        assert runner.rejected == [f"the relaxation problem ({why})"]
        assert runner.rejected[0].again_by is None  # (the usual back end: FALLBACK)
        assert runner.answered_by == ([solver, C] if answers[0] == "bad" else [C])


def test_a_linear_program_on_which_clarabel_fails_is_solved_by_highs(monkeypatch):
    """Clarabel, the default, failing on every rung of a linear program that HiGHS's
    simplex proves infeasible, its certificate checked: that is the answer, and the
    runner notes Clarabel's failure (the inclined corbel arch's maximum-load LP at f =
    0.7651, MaxIterations, was a "solver failure"). HiGHS's optimum is not taken (its
    accuracy is its tolerances' on the problem's scale), nor its failure: Clarabel's is
    raised; a problem with cones is not handed on."""
    monkeypatch.setattr(policy, "verified", checked)
    lp = SimpleNamespace(P=None, is_lp=True)
    script = Script(["few", "few", "few", "many", "none"])
    monkeypatch.setattr(policy, "solve", script)
    runner = Runner(C)
    res = runner.run(lp, "relaxation", VERDICT)
    assert res.solver == "highs" and res.status == "infeasible"
    assert [a[0] for a in script.asked] == [C, C, C, C, "highs"]
    why = "clarabel ended with status many #4; highs answered it"
    assert runner.rejected == [f"the relaxation problem ({why})"]
    assert runner.rejected[0].again_by == "highs"  # (the note names it from there)
    assert res.residuals["rejected"] == why and runner.answered_by == ["highs"]
    for highs in ("ok", "many"):
        monkeypatch.setattr(policy, "solve", Script(["few", "few", "few", "many", highs]))
        with pytest.raises(SolverFailure, match="clarabel could not solve .* many #4"):
            Runner(C).run(lp, "relaxation", VERDICT)
    monkeypatch.setattr(policy, "solve", Script(["few", "few", "few", "many"]))
    with pytest.raises(SolverFailure, match="many #4"):
        Runner(C).run(LP, "relaxation", VERDICT)


def test_attempt_is_one_checked_solve_or_none(monkeypatch):
    """Runner.attempt: one solve at the tight tolerances with the back end's entry of the
    settings on top (the user's last), checked, without retries; None where the back end
    has no entry."""
    monkeypatch.setattr(policy, "verified", checked)
    script = Script(["few", "bad"])
    monkeypatch.setattr(policy, "solve", script)
    runner = Runner(C, U)
    assert runner.attempt(LP, "maximum load", policy.FINER_SETTINGS).status == "failure"
    assert runner.attempt(LP, "maximum load", policy.FINER_SETTINGS).verified is False
    assert script.asked == [(C, on(T, F, U), None)] * 2
    assert Runner("highs").attempt(LP, "maximum load", policy.FINER_SETTINGS) is None

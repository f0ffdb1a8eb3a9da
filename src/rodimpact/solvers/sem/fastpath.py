"""The implicit scheme's steps inside a contact on a commensurate grid, as one tight loop.

A step from one grid node to the next while the bodies stay in contact is the same few
operations every time (:meth:`~rodimpact.solvers.sem.stepper._Stepper._step_implicit`
with the constant-cost rod sum of :mod:`.grid`). This loop does exactly those operations,
in the same order, on local variables, so it gives the same numbers bit for bit; it hands
back to the general step at anything else: the approach falling to zero (a contact may
end inside the step), a limit of the run, or the end of the grid.
"""

from __future__ import annotations

from typing import Any

__all__ = ["contact_steps", "extrapolated"]


def extrapolated(alpha: list[float], fallback: float) -> float:
    """The next approach extrapolated from the last three (quadratic), m: Newton's first guess.

    ``fallback`` when there are fewer than three.
    """
    if len(alpha) < 3:
        return fallback
    return 3.0 * (alpha[-1] - alpha[-2]) + alpha[-3]


def contact_steps(st: Any, t_max: float, force_bound: float, max_nodes: int) -> int:
    """Take grid steps while in contact; the number taken.

    Parameters
    ----------
    st : rodimpact.solvers.sem.stepper._Stepper
        An implicit run, in contact, with its last node on the grid.
    t_max : float
        Time horizon, s: the loop stops after the step that reaches it.
    force_bound : float
        The loop stops after a step whose force exceeds it, N.
    max_nodes : int
        The loop stops after the step that makes the history longer than this.

    Returns
    -------
    int
        Steps taken; the caller's checks then see the state after the last of them.
    """
    hist = st.hist
    grid = hist.grid
    h = grid.step
    a0, a1, c, w_coef, lag = grid.a0, grid.a1, grid.c, grid.w_coef, grid.lag
    impedance, m = hist.impedance, st.m
    coef = c / impedance
    b = h * h / (6.0 * m) + coef
    solve = st.law.solve_step_force
    T, P, Q, W = hist.t, hist.P, hist.Q, hist.W
    X, V, U, A = st.x, st.w, st.u_end, st.alpha
    t_app, p_app, q_app, w_app = T.append, P.append, Q.append, W.append
    x_app, v_app, u_app, a_app = X.append, V.append, U.append, A.append
    newton = 0
    taken = 0
    t_n, p_n, q_n = T[-1], P[-1], Q[-1]
    x, v = X[-1], V[-1]
    alpha_n = A[-1]
    if len(A) < 3:
        return 0
    alpha_prev, alpha_prev2 = A[-2], A[-3]
    k = len(W)  # index of the next grid node
    while True:
        i = k - lag
        known = a0 * q_n + a1 * p_n
        if i >= 0:
            known += w_coef * W[i]
        known /= impedance
        x_pred = x + v * h - h * h * (p_n / 3.0 + 0.0 / 6.0) / m
        a = x_pred - known
        if a <= 0.0:
            break
        guess = 3.0 * (alpha_n - alpha_prev) + alpha_prev2
        alpha_new, p_new, iterations = solve(a, b, guess)
        newton += iterations
        x_new = x + v * h - h * h * (p_n / 3.0 + p_new / 6.0) / m
        v_new = v - 0.5 * h * (p_n + p_new) / m
        u_new = known + coef * p_new
        t_new = k * h
        q_new = q_n + 0.5 * (p_n + p_new) * (t_new - t_n)
        t_app(t_new)
        p_app(p_new)
        q_app(q_new)
        w_app(0.5 * (impedance * u_new + q_new))
        x_app(x_new)
        v_app(v_new)
        u_app(u_new)
        alpha_prev2, alpha_prev, alpha_n = alpha_prev, alpha_n, x_new - u_new
        a_app(alpha_n)
        taken += 1
        k += 1
        t_n, p_n, q_n, x, v = t_new, p_new, q_new, x_new, v_new
        if t_new >= t_max or p_new > force_bound or len(T) > max_nodes:
            break
    st.n_newton += newton
    return taken

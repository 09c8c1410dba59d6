"""Euler–Poisson equations of a rigid body about a fixed point, derived with sympy.

The body has principal moments of inertia :math:`A, B, C` at the fixed point :math:`O`, mass
:math:`M` and centre of mass :math:`(x_0, y_0, z_0)` in the principal body frame. The unit vector
:math:`\\gamma = (\\gamma, \\gamma', \\gamma'')` of the *downward* vertical is written in body axes.
An attracting (Newtonian) centre :math:`O_1` lies on the vertical through :math:`O` at the
distance :math:`R`; its field at :math:`O` is :math:`g`. Expanding its potential to second order in
:math:`|r|/R` gives a uniform field :math:`g` (first order) plus the gravity gradient (second order).
``R = oo`` leaves the uniform field only.

Everything here is *derived*: the potential by expanding :math:`1/|R\\gamma - r|` and integrating
over the body, the torque as :math:`\\gamma \\times \\partial U/\\partial\\gamma`, the Euler equations
:math:`I\\dot\\omega = I\\omega\\times\\omega + N`, the Poisson equations
:math:`\\dot\\gamma = \\gamma\\times\\omega`, the integrals from the kinetic and potential energy,
and the dimensionless form by substitution.

References
----------
.. [1] Reference derivation of the project, ``shared/reference/derivation.md`` section (a), (b).
.. [2] The seed paper, "periodic solutions of a disk ... Newtonian force field and gravity",
   equations (1)–(5) (with the errata listed in the reference).
"""

from __future__ import annotations

import math
from functools import cache

import sympy as sp
from attrs import field, frozen

from perturb.errors import InvalidParameterError, bad_value
from perturb.system import EPS
from problems.rigid_body._stored import stored

__all__ = [
    "A",
    "A1",
    "B",
    "B1",
    "C",
    "C1",
    "DIMENSIONAL_STATE",
    "NONDIMENSIONAL_STATE",
    "NondimensionalParameters",
    "RigidBodyParameters",
    "body_potential",
    "euler_poisson_equations",
    "first_integrals",
    "inertia_ratio_values",
    "nondimensional_equations",
    "nondimensional_integrals",
    "nondimensional_substitution",
    "potential",
    "time_derivative",
    "torque",
]

# ---------------------------------------------------------------------------- symbols
#: Principal moments of inertia, mass, field strength at O, distance of the Newtonian centre.
A, B, C, M, g, R = sp.symbols("A B C M g R", positive=True)
#: Centre of mass in body axes.
x0, y0, z0 = sp.symbols("x0 y0 z0", real=True)
#: Time and the components of the angular velocity.
t = sp.Symbol("t", real=True)
p, q, r = sp.symbols("p q r", real=True)
#: Direction cosines of the downward vertical (the paper's gamma, gamma', gamma'').
gamma1, gamma2, gamma3 = sp.symbols("gamma1 gamma2 gamma3", real=True)
DIMENSIONAL_STATE = (p, q, r, gamma1, gamma2, gamma3)

#: Dimensionless quantities (reference section (b)). They carry no assumptions so that they match
#: symbols created by name elsewhere (e.g. ``QuasilinearSystem.with_values``).
a, b, k, x0p, y0p, z0p = sp.symbols("a b k x0p y0p z0p")
A1, B1, C1 = sp.symbols("A1 B1 C1")
#: Scales: c**2 = M g l / C, r0 = initial spin, l = distance of the centre of mass from the z axis.
c, r0, l = sp.symbols("c r0 l", positive=True)
tau = sp.Symbol("tau", real=True)
p1, q1, r1 = sp.symbols("p1 q1 r1")
NONDIMENSIONAL_STATE = (p1, q1, r1, gamma1, gamma2, gamma3)

#: Auxiliary symbols of the potential derivation: a body point, the bookkeeping scale of |r|/R
#: and the isotropic part of the second-moment tensor.
_xb, _yb, _zb = sp.symbols("x_b y_b z_b", real=True)
_s = sp.Symbol("s", positive=True)
_sigma = sp.Symbol("sigma")

#: Relative tolerance of the triangle inequalities of the moments (a disk has A + B = C exactly;
#: round-off in user input must not reject it).
TRIANGLE_RTOL = 1e-12
#: Tolerance on x0'**2 + y0'**2 = 1 for dimensionless parameters given directly.
UNIT_NORM_TOL = 1e-9

_GAMMA = sp.Matrix([gamma1, gamma2, gamma3])
_OMEGA = sp.Matrix([p, q, r])
_INERTIA = sp.diag(A, B, C)
_CENTRE = sp.Matrix([x0, y0, z0])


def _is_infinite(value) -> bool:
    return value is sp.oo or (isinstance(value, float) and math.isinf(value))


# ---------------------------------------------------------------------------- potential
@cache
def body_potential(order: int = 2) -> sp.Expr:
    """Potential energy of the body in the field of the centre, expanded and integrated, unreduced.

    The centre :math:`O_1` sits at :math:`R\\gamma` (body coordinates). Its potential energy on a mass
    element at :math:`r` is :math:`-G M_1\\,dm/|R\\gamma - r|` with :math:`G M_1 = g R^2`. With
    :math:`|\\gamma| = 1`, :math:`|R\\gamma - r|^2 = R^2 - 2R\\,\\gamma\\cdot r + r^2`; the inverse
    square root is expanded in powers of :math:`|r|/R` up to ``order`` and integrated over the body
    using :math:`\\int dm = M`, :math:`\\int r\\,dm = M r_G` and the second moments
    :math:`J = \\sigma\\,\\mathbb{1} - I` with :math:`\\sigma = \\tfrac12\\operatorname{tr} I`
    (principal axes: no products of inertia).

    Parameters
    ----------
    order : int
        Order of the expansion in :math:`|r|/R` (``2`` keeps the gravity gradient).

    Returns
    -------
    sympy.Expr
        The integrated potential energy, containing the auxiliary symbol ``sigma`` for the
        isotropic part of the second moments and a constant (gamma-independent) part.
    """
    if order != 2:
        raise bad_value("order", order, "only the second-order expansion (order=2) is implemented")
    # kept on disk: the series expansion is most of a warm run's symbolic work (0.14 s)
    return stored("body-potential", ("equations.py",), (order,), lambda: _body_potential(order))


def _body_potential(order: int) -> sp.Expr:
    body_point = sp.Matrix([_xb, _yb, _zb])
    # |R gamma - s r|^2 with |gamma| = 1; s counts powers of |r|/R.
    distance_sq = R**2 - 2 * R * _s * _GAMMA.dot(body_point) + _s**2 * body_point.dot(body_point)
    inverse_distance = sp.series(distance_sq ** sp.Rational(-1, 2), _s, 0, order + 1).removeO()
    integrand = sp.Poly(sp.expand(inverse_distance.subs(_s, 1)), _xb, _yb, _zb)
    second_moments = _sigma * sp.eye(3) - _INERTIA
    coords = (_xb, _yb, _zb)

    def moment(monomial: tuple[int, int, int]) -> sp.Expr:
        degree = sum(monomial)
        if degree == 0:
            return M
        if degree == 1:
            return M * _CENTRE[monomial.index(1)]
        if degree == 2:
            idx = [i for i, n in enumerate(monomial) for _ in range(n)]
            return second_moments[idx[0], idx[1]]
        raise AssertionError(f"moment of degree {degree} not available: {coords}")

    integrated = sum(coeff * moment(mono) for mono, coeff in integrand.terms())
    return sp.expand(-g * R**2 * integrated)


@cache
def potential(R_value=R) -> sp.Expr:
    """Potential energy :math:`U(\\gamma)` of gravity plus the Newtonian centre, up to a constant.

    Obtained from :func:`body_potential`: the part proportional to ``sigma`` is a multiple of
    :math:`|\\gamma|^2 - 1` (checked here), hence zero on the sphere and dropped; the
    :math:`\\gamma`-independent constant is dropped too. The result is

    .. math:: U = -Mg\\,r_G\\cdot\\gamma + \\frac{3g}{2R}\\,\\gamma\\cdot I\\gamma.

    Parameters
    ----------
    R_value : sympy.Expr, optional
        Distance of the centre. ``sympy.oo`` (or ``float('inf')``) drops the field term.
    """
    full = body_potential(2)
    isotropic = full.coeff(_sigma)
    on_sphere = sp.expand(isotropic.subs(gamma3**2, 1 - gamma1**2 - gamma2**2))
    if sp.simplify(on_sphere - on_sphere.subs({gamma1: 0, gamma2: 0, gamma3: 1})) != 0:
        raise AssertionError("the isotropic part of the potential is not constant on |gamma| = 1")
    u = sp.expand(full.subs(_sigma, 0))
    u = u - u.subs({gamma1: 0, gamma2: 0, gamma3: 0})
    return _with_distance(sp.expand(u), R_value)


def _with_distance(expr: sp.Expr, R_value) -> sp.Expr:
    if _is_infinite(R_value):
        return sp.expand(sp.limit(expr, R, sp.oo)) if expr.has(R) else expr
    if R_value is R:
        return expr
    return expr.subs(R, R_value)


@cache
def torque(R_value=R) -> sp.Matrix:
    """Moment of the external forces about O, :math:`N = \\gamma \\times \\partial U/\\partial\\gamma`.

    :math:`U` depends on the attitude only through the space-fixed :math:`\\gamma` seen from
    the body. A small rotation :math:`\\delta\\theta` changes it by
    :math:`\\delta\\gamma = \\gamma\\times\\delta\\theta`, so the virtual work is
    :math:`N\\cdot\\delta\\theta = -\\delta U = (\\gamma\\times\\partial U/\\partial\\gamma)\\cdot\\delta\\theta`;
    for uniform gravity this is :math:`Mg\\, r_G\\times\\gamma`.
    """
    u = potential(R_value)
    grad = sp.Matrix([sp.diff(u, gi) for gi in _GAMMA])
    return sp.Matrix([sp.factor_terms(sp.expand(e)) for e in _GAMMA.cross(grad)])


@cache
def euler_poisson_equations(R_value=R) -> sp.Matrix:
    """Right-hand side of the Euler–Poisson system for ``(p, q, r, gamma1, gamma2, gamma3)``.

    .. math::

        I\\dot\\omega = I\\omega\\times\\omega + N, \\qquad \\dot\\gamma = \\gamma\\times\\omega.

    Returns
    -------
    sympy.Matrix
        A 6x1 column: :math:`(\\dot p, \\dot q, \\dot r, \\dot\\gamma, \\dot\\gamma', \\dot\\gamma'')`.
    """
    omega_dot = _INERTIA.inv() * (((_INERTIA * _OMEGA).cross(_OMEGA)) + torque(R_value))
    gamma_dot = _GAMMA.cross(_OMEGA)
    return sp.Matrix([sp.expand(e) for e in list(omega_dot) + list(gamma_dot)])


@cache
def first_integrals(R_value=R) -> dict[str, sp.Expr]:
    """Energy, area and geometric integrals of the dimensional system.

    ``energy`` is :math:`2(T + U) = \\omega\\cdot I\\omega + 2U`, ``area`` is
    :math:`I\\omega\\cdot\\gamma` (angular momentum about the vertical) and ``geometric`` is
    :math:`|\\gamma|^2`.
    """
    kinetic = sp.Rational(1, 2) * _OMEGA.dot(_INERTIA * _OMEGA)
    return {
        "energy": sp.expand(2 * (kinetic + potential(R_value))),
        "area": sp.expand((_INERTIA * _OMEGA).dot(_GAMMA)),
        "geometric": sp.expand(_GAMMA.dot(_GAMMA)),
    }


def time_derivative(expr: sp.Expr, rhs, state) -> sp.Expr:
    """Derivative of ``expr`` along the vector field ``rhs`` on ``state`` (expanded)."""
    return sp.expand(sum(sp.diff(expr, s) * f for s, f in zip(state, rhs, strict=True)))


# ---------------------------------------------------------------------------- dimensionless form
def nondimensional_substitution() -> dict[sp.Symbol, sp.Expr]:
    """The substitution of the dimensional constants by the dimensionless ones.

    :math:`A = aC`, :math:`B = bC`, :math:`x_0 = x_0' l` (etc.), :math:`g = c^2 C/(Ml)` (from
    :math:`c^2 = Mgl/C`), :math:`R = 3C/(kMl)` (from :math:`k = 3C/(RMl)`), :math:`c = \\varepsilon r_0`.
    """
    return {
        A: a * C,
        B: b * C,
        x0: x0p * l,
        y0: y0p * l,
        z0: z0p * l,
        g: c**2 * C / (M * l),
        R: 3 * C / (k * M * l),
    }


def _to_dimensionless(expr: sp.Expr) -> sp.Expr:
    expr = expr.subs(nondimensional_substitution()).subs(c, EPS * r0)
    expr = sp.expand(sp.cancel(sp.expand(expr)))
    stray = expr.free_symbols & {A, B, C, M, g, R, l, r0, c}
    if stray:
        raise AssertionError(f"dimensional symbols {stray} survived the substitution")
    return expr


@cache
def nondimensional_equations(field_on: bool = True, ratios: bool = True) -> sp.Matrix:
    """Dimensionless Euler–Poisson equations in :math:`\\tau = r_0 t`, derived by substitution.

    :math:`p = c\\,p_1`, :math:`q = c\\,q_1`, :math:`r = r_0 r_1`, :math:`d/dt = r_0\\,d/d\\tau`,
    :math:`\\varepsilon = c/r_0`.

    Parameters
    ----------
    field_on : bool
        ``False`` drops the Newtonian centre (``R = oo``, i.e. ``k = 0``).
    ratios : bool
        ``True`` writes the Euler part with :math:`A_1 = (C-B)/A`, :math:`B_1 = (A-C)/B`,
        :math:`C_1 = (B-A)/C` as the reference prints it; ``False`` with :math:`a, b` only.
        In component :math:`i` the only moments present are the divisor and the difference of the
        other two, so the defining relation of the ratio is solved for the non-divisor moment
        (:math:`B = C - A_1A` in the first equation, cyclically).

    Returns
    -------
    sympy.Matrix
        :math:`(\\dot p_1, \\dot q_1, \\dot r_1, \\dot\\gamma, \\dot\\gamma', \\dot\\gamma'')` with respect
        to :math:`\\tau`.
    """
    rhs = euler_poisson_equations(R if field_on else sp.oo)
    scale = {p: c * p1, q: c * q1, r: r0 * r1}
    # d(p1)/dtau = (dp/dt) / (c r0), d(r1)/dtau = (dr/dt) / r0**2, d(gamma)/dtau = (dgamma/dt) / r0
    divisors = (c * r0, c * r0, r0**2, r0, r0, r0)
    ratio_subs = ({B: C - A1 * A}, {C: A - B1 * B}, {A: B - C1 * C}, {}, {}, {})
    out = []
    for expr, divisor, rsub in zip(rhs, divisors, ratio_subs, strict=True):
        expr = expr.subs(scale) / divisor
        if ratios:
            expr = sp.expand(expr.subs(rsub))
        out.append(_to_dimensionless(expr))
    return sp.Matrix(out)


def inertia_ratio_values(disk: bool = False) -> dict[sp.Symbol, sp.Expr]:
    """Values of :math:`A_1, B_1, C_1` in terms of :math:`a, b`.

    For the general body :math:`A_1 = (1-b)/a`, :math:`B_1 = (a-1)/b`, :math:`C_1 = b-a`.
    For the disk (``disk=True``, :math:`C = A + B`) the dimensional definitions give
    :math:`A_1 = 1`, :math:`B_1 = -1` exactly, and :math:`C_1 = b - a`.
    """
    definitions = {A1: (C - B) / A, B1: (A - C) / B, C1: (B - A) / C}
    out = {}
    for symbol, value in definitions.items():
        general = sp.cancel(value.subs(nondimensional_substitution()))
        if disk:
            # C = A + B is used only where it turns the ratio into a number (A1 = 1, B1 = -1), the
            # reference's convention; C1 = (B - A)/C = b - a needs no relation.
            on_disk = sp.cancel(value.subs(C, A + B))
            general = on_disk if on_disk.is_number else general
        out[symbol] = general
    return out


@cache
def nondimensional_integrals(field_on: bool = True) -> dict[str, sp.Expr]:
    """Dimensionless integrals: energy / (C r0**2), area / (C r0), geometric."""
    ints = first_integrals(R if field_on else sp.oo)
    scale = {p: c * p1, q: c * q1, r: r0 * r1}
    return {
        "energy": _to_dimensionless(ints["energy"].subs(scale) / (C * r0**2)),
        "area": _to_dimensionless(ints["area"].subs(scale) / (C * r0)),
        "geometric": ints["geometric"],
    }


# ---------------------------------------------------------------------------- parameters
def _check_finite(name: str, value: float) -> float:
    value = float(value)
    if math.isnan(value) or math.isinf(value):
        raise bad_value(name, value, "give a finite real number")
    return value


def _check_positive(name: str, value: float, allow_inf: bool = False) -> float:
    value = float(value)
    if math.isnan(value):
        raise bad_value(name, value, "give a positive real number, not NaN")
    if value <= 0 or (math.isinf(value) and not allow_inf):
        hint = " (float('inf') for no Newtonian centre)" if allow_inf else ""
        raise bad_value(name, value, f"give a positive finite number{hint}")
    return value


def _check_triangle(values: dict[str, float]) -> None:
    names = list(values)
    for i in range(3):
        x, y, z = names[i], names[(i + 1) % 3], names[(i + 2) % 3]
        if values[x] + values[y] < values[z] * (1 - TRIANGLE_RTOL):
            raise InvalidParameterError(
                f"`{z}` = {values[z]!r} is invalid: the principal moments must satisfy the triangle "
                f"inequality {x} + {y} >= {z} (got {values[x]!r} + {values[y]!r}); "
                f"give {z} <= {values[x] + values[y]!r}"
            )


@frozen
class RigidBodyParameters:
    """Physical data of the body (dimensional, any consistent units).

    Parameters
    ----------
    A, B, C : float
        Principal moments of inertia at the fixed point (positive, triangle inequality).
    x0, y0, z0 : float
        Centre of mass in body axes.
    M : float
        Mass (positive).
    g : float
        Field strength at the fixed point (positive).
    R : float
        Distance of the Newtonian centre (positive; ``inf`` for uniform gravity only).

    Raises
    ------
    InvalidParameterError
        For non-positive or NaN moments, mass, field or distance, or moments violating the triangle
        inequality.
    """

    A: float = field(converter=float)
    B: float = field(converter=float)
    C: float = field(converter=float)
    x0: float = field(converter=float)
    y0: float = field(converter=float)
    z0: float = field(default=0.0, converter=float)
    M: float = field(default=1.0, converter=float)
    g: float = field(default=1.0, converter=float)
    R: float = field(default=math.inf, converter=float)

    def __attrs_post_init__(self):
        for name in ("A", "B", "C", "M", "g"):
            _check_positive(name, getattr(self, name))
        _check_positive("R", self.R, allow_inf=True)
        for name in ("x0", "y0", "z0"):
            _check_finite(name, getattr(self, name))
        _check_triangle({"A": self.A, "B": self.B, "C": self.C})

    @classmethod
    def from_paper(cls) -> RigidBodyParameters:
        """The example (31) of the seed paper (z0 = 0; g = 1.5e-7 reproduces its c)."""
        return cls(A=9, B=11, C=20, x0=1, y0=6, z0=0, M=200, g=1.5e-7, R=2000)

    @property
    def gradient(self) -> float:
        """The gravity-gradient coefficient 3g/R (0 for R = inf)."""
        return 3 * self.g / self.R

    @property
    def arm(self) -> float:
        """l = sqrt(x0**2 + y0**2)."""
        return math.hypot(self.x0, self.y0)

    def values(self) -> dict[sp.Symbol, float]:
        """The symbol -> value map for the dimensional symbols."""
        return {
            A: self.A,
            B: self.B,
            C: self.C,
            x0: self.x0,
            y0: self.y0,
            z0: self.z0,
            M: self.M,
            g: self.g,
            R: self.R,
        }


@frozen
class NondimensionalParameters:
    """Dimensionless data of the fast-spin scaling (reference section (b)).

    Parameters
    ----------
    a, b : float
        A/C and B/C (positive; a + b >= 1, |a - b| <= 1).
    k : float
        3C/(RMl) (non-negative; 0 means no Newtonian centre).
    x0p, y0p : float
        x0/l, y0/l (x0p**2 + y0p**2 = 1).
    z0p : float
        z0/l.
    eps : float
        c/r0 (positive).
    """

    a: float = field(converter=float)
    b: float = field(converter=float)
    k: float = field(converter=float)
    x0p: float = field(converter=float)
    y0p: float = field(converter=float)
    z0p: float = field(default=0.0, converter=float)
    eps: float = field(default=0.01, converter=float)

    def __attrs_post_init__(self):
        _check_positive("a", self.a)
        _check_positive("b", self.b)
        _check_positive("eps", self.eps)
        if math.isnan(self.k) or self.k < 0 or math.isinf(self.k):
            raise bad_value("k", self.k, "give k = 3C/(RMl) >= 0 (0 for no Newtonian centre)")
        for name in ("x0p", "y0p", "z0p"):
            _check_finite(name, getattr(self, name))
        if abs(self.x0p**2 + self.y0p**2 - 1) > UNIT_NORM_TOL:
            raise bad_value(
                "x0p", self.x0p, f"x0p**2 + y0p**2 must be 1 (y0p = {self.y0p!r}); divide by l"
            )
        _check_triangle({"a": self.a, "b": self.b, "1": 1.0})

    @classmethod
    def from_dimensional(
        cls, body: RigidBodyParameters, r0_value: float
    ) -> NondimensionalParameters:
        """Scale ``body`` with the initial spin ``r0_value``."""
        r0_value = _check_positive("r0", r0_value)
        arm = body.arm
        if arm == 0:
            raise bad_value("x0", body.x0, "x0 and y0 are both 0: the scaling needs l > 0")
        c_value = math.sqrt(body.M * body.g * arm / body.C)
        return cls(
            a=body.A / body.C,
            b=body.B / body.C,
            k=3 * body.C / (body.R * body.M * arm),
            x0p=body.x0 / arm,
            y0p=body.y0 / arm,
            z0p=body.z0 / arm,
            eps=c_value / r0_value,
        )

    def values(self) -> dict[sp.Symbol, float]:
        """The symbol -> value map (including ``epsilon``)."""
        return {
            a: self.a,
            b: self.b,
            k: self.k,
            x0p: self.x0p,
            y0p: self.y0p,
            z0p: self.z0p,
            EPS: self.eps,
        }


# The numeric functions moved to :mod:`problems.rigid_body.numeric` (one concern per module);
# that module hands them back to this one, so they are still importable from here.

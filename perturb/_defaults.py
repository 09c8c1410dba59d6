"""Named numerical constants of perturb, each with the reason for its value (one source for each)."""

#: Default number of samples over one period when the user gives no times (CLI contract, issue 2).
DEFAULT_SAMPLES = 101

#: Largest order the engine accepts: beyond it the symbolic work grows past any use in practice.
MAX_ORDER = 12

#: Relative size under which a numerically evaluated coefficient counts as zero when probing the rank
#: of the periodicity conditions at random parameter values (float64 round-off times a safety factor).
RANK_TOL = 1e-9

#: Number of random parameter points used to decide, numerically, whether a symbolic condition vanishes.
ZERO_PROBES = 3

#: Sample points per period for the numeric Fourier (quadrature) fallback used on non-polynomial
#: perturbations; a power of two, enough for ~30 significant harmonics.
FFT_POINTS = 256

#: A pole or branch point of a non-polynomial right-hand side counts as reached by the generating
#: solution when its companion (the base of sqrt, the argument of log...) comes within this relative
#: distance of zero on the quadrature grid: the Taylor expansion about the orbit has no radius there,
#: and a crossing between grid points shows up as a sign change (a value <= 0) anyway.
SINGULARITY_MARGIN = 1e-8

#: Fourier coefficients of the numeric fallback below this magnitude (relative to the largest) are dropped.
FFT_TRIM = 1e-13

#: Distance of a frequency ratio to an integer below which a non-resonant coordinate is flagged as
#: near-resonant (small divisor 1/(omega_i**2 - j**2) larger than 1/NEAR_RESONANCE).
NEAR_RESONANCE = 1e-3

#: Floating-point coefficients smaller than this (in absolute value) are round-off of the numeric
#: quadrature (FFT of O(1) samples carries errors ~1e-16 times the number of harmonics) and are
#: set to zero before the periodicity conditions are solved.
NUMERIC_ZERO = 1e-12

#: Digits of the evaluation at a generic point that confirms a condition vanishes once solved:
#: far beyond double precision, so cancellation among large terms cannot fake a zero or a non-zero.
PROBE_DIGITS = 30

#: Time budget (seconds) of sympy's solve on one order's nonlinear amplitude equations: the textbook
#: and the disk's equations take well under a second; equations whose roots have no closed form can
#: keep sympy busy for hours.
SOLVE_SECONDS = 30.0

#: Numeric roots of the amplitude equations (Groebner path): a root of the triangular system is
#: accepted where every polynomial of its variable vanishes to this fraction of its coefficients'
#: size (companion-matrix roots of well-scaled polynomials are good to ~1e-12).
ROOT_RESIDUAL = 1e-8
#: A numeric root this close to a rational with a small denominator is taken exact (2.0000000000001 -> 2).
ROOT_RATIONAL_TOL = 1e-11
ROOT_MAX_DENOMINATOR = 10_000

#: Most output times a command accepts (``--times``): 10⁷ points of a 6-component state printed as
#: text are ~1.5 GB, past any use at a terminal; beyond it, call ``evaluate`` from Python.
MAX_TIMES = 10_000_000

# --------------------------------------------------------------------------------------------------
# The numerical oracle (perturb.oracle): integrators and shooting
# --------------------------------------------------------------------------------------------------

#: Default relative tolerance of the adaptive scipy integrators when used as an oracle.  DOP853 holds
#: about this relative accuracy per unit time; 1e-12 leaves three digits of head-room above float64
#: round-off (the SUMMARY's oracle: DOP853 rtol 1e-12 gives integral drift <= 1e-11).
DEFAULT_RTOL = 1e-12

#: Components of the scale vector smaller than this fraction of the largest one are raised to it when
#: building a per-component ``atol``.  A component that starts at zero (x'(0) = 0 on a section) is
#: assumed to reach at least 1e-3 of the largest component; erring small costs only a few DOP853 steps
#: (an 8th-order method needs 10**(3/8) ~ 2.4x more steps for a 1e3 tighter tolerance at worst).
ATOL_FLOOR_FRACTION = 1e-3

#: Default tolerance of the Taylor integrator.  heyoka's default is the machine epsilon of its floating
#: point type; we keep that (``None`` = let heyoka choose), documented here so there is one source.
DEFAULT_HEYOKA_TOL = None

#: Systems with at least this many equations are compiled by heyoka in compact mode: the JIT time of
#: the fully unrolled Taylor decomposition grows quickly with size (variational 6-D system: 42 eqs).
HEYOKA_COMPACT_MODE_MIN_DIM = 20

#: Default number of RK4 steps per unit of time.  The seed paper used a fixed-step RK4; 200 steps per
#: unit time (~1250 per 2*pi period) gives a global error ~1e-10 on unit-frequency oscillators.
DEFAULT_RK4_STEPS_PER_UNIT = 200

#: Largest number of steps an adaptive integrator may take before reporting failure (guards against
#: stiffness or blow-up turning a check into an endless loop).  A million python-driven scipy steps
#: take ~20 s; DOP853 at rtol 1e-14 needs ~30 steps per unit-frequency period, so 1e6 allows >3e4
#: periods.
MAX_STEPS = 1_000_000

#: Default convergence tolerance of the shooting Newton iteration on the relative periodicity residual
#: ||y(T) - y(0)||_inf / scale; a few hundred float64 ulps, reachable by an integrator at rtol 1e-13.
SHOOTING_TOL = 1e-12

#: Default cap on Newton iterations: quadratic convergence from a guess inside the basin needs < 10;
#: 30 allows for damped steps from a poor guess.
SHOOTING_MAX_ITER = 30

#: Number of halvings tried in the backtracking line search before a Newton step is accepted anyway.
SHOOTING_MAX_HALVINGS = 8

#: Relative Newton step size below which further iterations cannot improve the solution: the
#: residual is then dominated by the integration error, and the iteration stops as stalled.
SHOOTING_STALL_STEP = 1e-14

#: Relative step of the centred finite differences used for the Jacobian when the user gives none
#: and the rhs is not symbolic: eps**(1/3) balances truncation (h**2) and round-off (eps/h) errors.
FD_REL_STEP = 6e-6

#: Default relative tolerance of the integrator used *inside* the shooting method; one decade tighter
#: than :data:`SHOOTING_TOL` so that the residual can actually get below the tolerance.
SHOOTING_INTEGRATOR_RTOL = 1e-13

#: A converged "orbit" whose motion over one period, max|f(y0)| * T, is below this fraction of the
#: state scale is an equilibrium: the residual vanishes there for any period.  1e-8 is far above the
#: round-off motion of a true fixed point and far below any physical oscillation we look for.
EQUILIBRIUM_MOTION = 1e-8

#: Relative tolerance of Radau on stiff systems: its Newton iterations stop converging much
#: below 1e-10, and a stiff relaxation cycle is not reproducible to better than that anyway.
STIFF_RTOL = 1e-10

#: A Floquet multiplier within this distance of 1 counts as trivial in
#: :attr:`perturb.oracle.PeriodicOrbit.n_trivial_found`.  A trivial multiplier in a Jordan block of
#: size 2 (a family whose period varies along it) splits by ~sqrt(delta) under a perturbation delta
#: of the monodromy: delta ~ 1e-13 from the integration gives ~3e-7; 1e-5 leaves a margin of 30.
TRIVIAL_MULTIPLIER_TOL = 1e-5

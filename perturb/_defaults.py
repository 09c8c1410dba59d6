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

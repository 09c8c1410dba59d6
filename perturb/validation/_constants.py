"""Named constants of :mod:`perturb.validation`, each with the reason for its value."""

#: Default tolerance of the accuracy checks (``tol=`` / ``--tol``): the largest distance of the
#: analytic orbit from the true one, relative to the orbit's size, and the largest relative period
#: error, of a solution still called valid.  10 % is where a plot of the analytic and the true curves
#: visibly separates; pass a smaller ``tol`` to demand more.
DEFAULT_TOL = 0.1

#: The former name of :data:`DEFAULT_TOL` (kept: tests and user code import it).
MAX_RELATIVE_ERROR = DEFAULT_TOL

#: Kept for code that imports it; no longer part of the verdict.  It was a precondition |ε| <= 0.3
#: that gave the same motion different verdicts under a rescaling (Duffing (ε, A) and (4ε, A/2)):
#: the verdict now rests on measurements only.
EPSILON_LIMIT = 0.3

#: A measured slope may fall this far below the theoretical order + 1 and still count as consistent
#: (the band of the order check): four ε points a factor 2 apart leave an uncertainty of a few
#: tenths from the next-order terms.
SLOPE_TOLERANCE = 0.5

#: Factors applied to the problem's own small parameter for the order check: geometric, at and below
#: the user's value (the question is whether the user's ε is in the asymptotic regime); |ε| is scaled
#: and its sign kept.
SLOPE_FACTORS = (0.125, 0.25, 0.5, 1.0)

#: Relative errors below this are at the level of the oracle's own accuracy (rtol 1e-12 over a
#: period plus the evaluation round-off of the series); such points are dropped from the slope fit.
ERROR_FLOOR = 1e-10

#: Output samples per period of the trajectory comparison: 40 points resolve a harmonic of order
#: ~10 well enough that the sampled maximum of the error is within a few % of the true maximum.
SAMPLES_PER_PERIOD = 40

#: Default number of periods of the trajectory comparison (information only: not in the verdict).
DEFAULT_PERIODS = 10

#: Most output points of the trajectory comparison (``periods * samples_per_period``): 10^6 points
#: of a 6-component state are 48 MB; beyond that the horizon is refused with a one-line error.
MAX_OUTPUT_SAMPLES = 1_000_000

#: Points of the analytic orbit at which the Jacobian eigenvalues are sampled for stiffness.
STIFFNESS_SAMPLES = 16

#: Stiffness ratio max|Re λ| / max(max|Im λ|, 2π/T) above which explicit methods are abandoned for
#: Radau: the decay rate then exceeds the oscillation rate tenfold, and an explicit method's stability
#: limit (|h λ| ≲ 3) sets its step instead of the accuracy.
STIFFNESS_THRESHOLD = 10.0

#: Distance from 1 below which a trivial Floquet multiplier counts as 1.  A conservative family has a
#: Jordan block at 1 whose computed eigenvalues split like sqrt(integration error) ~ sqrt(1e-13) ~ 3e-7.
FLOQUET_TOL = 1e-5
#: Smallest periodicity defect a double-precision shooting can certify (relative to the amplitudes):
#: round-off of the state over one period.
SHOOTING_PRECISION = 1e-13
#: Distance from 1 below which a Floquet multiplier cannot be told from a trivial one: the monodromy
#: of a double-precision variational integration (error ~1e-12) splits a double multiplier 1 by
#: about the square root of that error.
MULTIPLIER_FLOOR = 1e-6
#: Largest shooting uncertainty (relative to the amplitudes) at which the orbit is still used to judge
#: the analytic solution (the existence check's tolerance): 1 % of the default accuracy tolerance.
ORBIT_RESOLUTION_LIMIT = 1e-3

#: Amplitudes below this fraction of the largest one are raised to it for the relative errors
#: (a component identically zero would otherwise divide by zero).
AMPLITUDE_FLOOR = 1e-9

#: Relative tolerance of the scipy integrators of the oracle (DOP853/Radau): three digits above
#: float64 round-off, as the reference's DOP853 oracle (integral drift <= 1e-11).
DEFAULT_RTOL = 1e-12

#: Periodicity tolerance of the double-precision shooting (relative defect): a few hundred times
#: float64 round-off, what a period of integration at rtol 1e-12/1e-13 can certify.
SHOOTING_TOL = 1e-12

#: Newton iterations allowed to the shooting: from a seed within O(ε^(n+1)) it converges in < 8;
#: the cap bounds the time spent when the expansion is wrong and the seed is far from any orbit.
SHOOTING_ITERATIONS = 20

#: Relative tolerance of Radau on stiff systems: its Newton iterations stop converging much
#: below 1e-10, and a stiff relaxation cycle is not reproducible to better than that anyway.
STIFF_RTOL = 1e-10

#: Shooting on a stiff system: Radau at rtol 1e-11 (explicit and Taylor methods crawl at the
#: stability limit).  The periodicity tolerance is looser than for smooth motion because the fast
#: transitions of a relaxation cycle amplify the per-step error ~1e4-fold over one period
#: (van der Pol at eps = 10 stalls at a residual ~1e-7).
STIFF_SHOOTING_RTOL = 1e-11
STIFF_SHOOTING_TOL = 1e-6

#: Factor by which a parameter is scaled to test whether it is a pure-ε knob; any value far enough
#: from 1 to measure the exponent to ~1e-12 works.
KNOB_PROBE = 2.0

#: A component whose analytic value varies over one period by less than this fraction of its size
#: is treated as a family parameter (a first integral's value: a spin, a direction cosine) and is
#: pinned in the derived shooting set-up of models on a physical (non-quasilinear) state.
SLOW_COMPONENT = 1e-2

#: Step budget of every integration when a problem's own validity estimate fails: the measurement
#: still runs, but an analytic state far from any orbit (a tumbling body started from a meaningless
#: series) can need 1e7 steps per period; 20 000 Taylor steps take ~0.1 s.  A cut by this budget
#: makes the trajectory information partial and the checks that need it undecided.
ESTIMATE_FAILED_MAX_STEPS = 20_000
#: The former name of :data:`ESTIMATE_FAILED_MAX_STEPS`.
INVALID_MAX_STEPS = ESTIMATE_FAILED_MAX_STEPS

#: A velocity component counts as zero at the start (candidate Poincaré section) below this fraction
#: of the state scale.
SECTION_ZERO = 1e-8

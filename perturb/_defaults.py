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
#: The same probe on the native backend (:func:`perturb.method.exact.vanishes_native`): 400 bits
#: (120 digits) of fixed precision, so that cancellation among terms up to 10^80 leaves the value
#: good to far below NUMERIC_ZERO; a value above PROBE_NONZERO is non-zero beyond doubt, anything
#: nearer the threshold is left to the 30-digit adaptive evaluation of sympy.
PROBE_BITS = 400
PROBE_NONZERO = 1e-6

#: Time budget (seconds) of sympy's solve on one order's nonlinear amplitude equations: the textbook
#: and the disk's equations take well under a second; equations whose roots have no closed form can
#: keep sympy busy for hours.
SOLVE_SECONDS = 30.0

#: Time given to the helper interpreter of a budgeted solve to start (import sympy: 0.5-1.2 s
#: measured on 2 shared cores), where the solve cannot run in a forked child (a Dask worker, a
#: thread other than the main one); the solve's own budget is counted after it.
CHILD_START_SECONDS = 10.0

#: Linear periodicity conditions with at most this many terms in all are solved by sympy's
#: ``linsolve`` (toy systems: milliseconds, and their results stay the very expressions they always
#: were); larger ones (the rigid body's, with rational-function coefficients in its parameters) on
#: the native backend (:mod:`perturb.method.linear`), where sympy takes seconds to minutes an order.
LINEAR_SYMPY_MAX_TERMS = 32

#: Numeric roots of the amplitude equations (Groebner path): a root of the triangular system is
#: accepted where every polynomial of its variable vanishes to this fraction of its coefficients'
#: size (companion-matrix roots of well-scaled polynomials are good to ~1e-12).
ROOT_RESIDUAL = 1e-8
#: A numeric root this close to a rational with a small denominator is taken exact (2.0000000000001 -> 2).
ROOT_RATIONAL_TOL = 1e-11
ROOT_MAX_DENOMINATOR = 10_000

#: Largest magnitude of a problem parameter: the series raise parameters to powers and multiply
#: them (a cubic term at order 12 holds powers past 30), so 10¹⁰⁰ keeps every product the
#: construction and an integration form within the floats (10³⁰⁸); beyond it the numbers overflow
#: and the answer would be ``inf`` or a normal-looking value of nothing (``kappa = 1e308``). A
#: parameter that admits ``inf`` (the disk's distance R: "no centre") enters through its inverse
#: and is not bounded.
PARAMETER_MAX_MAGNITUDE = 1e100

#: Most output times a command accepts (``--times``, a scene's periods x samples, a sweep's
#: times): 10⁶ times of the Duffing oscillator printed as CSV take 10 s and 240 MB (10⁷ took 105 s
#: and 1.6 GB, a rigid body's 6 components more than the memory of a small machine), past any use
#: at a terminal; beyond it, call ``evaluate`` from Python.
MAX_TIMES = 1_000_000

#: Largest ``--times @FILE`` read: 10⁶ times (MAX_TIMES) of up to 32 characters each. A larger
#: file (``@/dev/zero`` has no end) is refused before it is read.
TIMES_FILE_MAX_BYTES = 32 * MAX_TIMES

#: Largest problem file imported (``perturb solve path/file.py:Class``): a problem's module is a
#: few kB to a few hundred; a larger file is not one (Python would read it whole into memory).
PROBLEM_FILE_MAX_BYTES = 16 * 2**20

#: Largest scene file read: a scene is a page of TOML (the shipped ones are under 2 kB).
SCENE_MAX_BYTES = 1 << 20

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

#: Largest p and q of a driven system's resonance Omega = (p/q) omega + eps sigma
#: (perturb.excitation): the response's period is p forcing periods, and a harmonic q*m of Omega/p
#: is what the reference coordinate responds at; beyond 9 the periodicity conditions are of so
#: high an order that the first non-trivial one lies past any order a construction reaches.
MAX_RESONANCE_INTEGER = 9

#: The shooting's precision floor (perturb.oracle.shooting): a tolerance below what the working
#: precision can show is not a convergence test. The float64 defect y(T) - y(0) carries a few ulps
#: of the states subtracted (one for each rounding of y(T), y(0) and the difference, one spare);
#: the integration error is measured once Newton stops gaining, by a second shot with an integrator
#: NOISE_PROBE_FACTOR times looser (its error is about factor - 1 times the first one's: 100 makes
#: it stand clear of round-off at double precision). A residual within FLOOR_SAFETY of that floor
#: is converged: the estimate holds to a factor of a few (the error is proportional to the
#: tolerance only roughly), and an order of magnitude covers it while a genuine stall far above
#: the floor (a poor guess, a wrong section) still fails.
ROUNDING_ULPS = 4
NOISE_PROBE_FACTOR = 100.0
FLOOR_SAFETY = 10.0

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

# ---------------------------------------------------------------------------------- scenes
#: Default horizon of a scene, in periods: three periods show the motion repeating and let a
#: trajectory error that grows secularly (a period error) become visible on the error plot.
SCENE_PERIODS = 3

#: Samples per period of a scene's tables and plots: 100 resolve a harmonic of order ~10 with
#: ten points a wavelength, enough for a smooth curve in a publication figure.
SCENE_SAMPLES_PER_PERIOD = 100

#: Longest scene horizon, in periods: a report is files to read and figures to look at; beyond
#: this the CSV grows past tens of MB and curves fill the plot (``perturb validate --periods``
#: measures long horizons without writing them out).
SCENE_MAX_PERIODS = 1000

#: Most samples per period of a scene (with SCENE_MAX_PERIODS, periods x samples is checked
#: against MAX_TIMES).
SCENE_MAX_SAMPLES_PER_PERIOD = 10_000

#: Most repeated runs per work-precision point a scene may ask for (the median is reported; more
#: than 100 buys no accuracy and multiplies the run time).
SCENE_MAX_REPEAT = 100

#: Closeness (difflib ratio) above which an unknown name in a scene gets a "did you mean".
SCENE_SUGGESTION_CUTOFF = 0.6

# ---------------------------------------------------------------------------------- sweeps
#: A sweep of more points than this asks for confirmation (``--yes``, ``yes=True``): at 10^5
#: points/s an evaluation of 10^7 points already takes minutes and its store hundreds of MB, and a
#: typing slip (an extra zero in N) should not start an hour of work unasked.
SWEEP_CONFIRM_POINTS = 10_000_000

#: Estimated work (seconds on one core) above which a request needs confirmation (``--yes``),
#: whatever it is made of (perturb.cost: a response's values and order, the points shot against
#: the true motion, a validated sweep): an hour is a plan, not a typing slip, and a slip (an extra
#: zero, an order of 12) must not start it unasked. The 100 x 100 validated map of the disk
#: (README, about 8 minutes) stays below it.
CONFIRM_SECONDS = 3600.0

#: The estimate's figures (CPU seconds on one core, measured on the shipped driven problems;
#: benchmarks/hostile_cli.md): the response's derivation at order 1 (the amplitude equations and
#: the continuation's compiled series, 0.5-2.5 s) and its growth with each order (1.7-2.5 a step
#: from order 3 to 7: forced Duffing 1.8, 4.9, 25 s at orders 3, 5, 7), a grid value read off the
#: continued curves per order (5-10 ms at order 3, 200 values), the points shot against the true
#: motion besides those asked (the largest amplitude, both sides of each fold, the ends), a shot
#: (0.4-1.6 s), a point of a continued true curve (about 10 ms), the branches a driven problem
#: typically has (lower, middle, upper), an evaluated sweep point (1-3 x 10^5 points a second,
#: benchmarks/bench_sweep.md) and a validated one (0.07-0.3 s).
RESPONSE_DERIVE_SECONDS = 0.5

#: The certified first-order census of a driven problem (its steady states: the real roots of
#: 2n cubic amplitude equations, Bezout 9^n): 0.35 s of CPU for one mode, and about 12 times more
#: for each further mode (coupled Duffings, 2 modes: 4 s; the 3-mass chain: 49 s; measured by
#: `perturb response PROBLEM --sweep Omega=1.05:1.1:3 --order 1`, benchmarks/hostile_cli.md).
#: The response pays it once, the phase diagram at every point of its grid.
CENSUS_SECONDS = 0.35
CENSUS_MODE_GROWTH = 12.0

#: Estimated work past which a request that may start says how long it will take, in one line
#: on stderr (a progress bar is drawn only on a terminal; a run of minutes is never silent).
NOTICE_SECONDS = 60.0
RESPONSE_ORDER_GROWTH = 2.5
RESPONSE_SECONDS_PER_VALUE = 0.02
RESPONSE_ALWAYS_SHOT = 4
SHOT_SECONDS = 1.0
TRUE_POINT_SECONDS = 0.01
RESPONSE_TYPICAL_BRANCHES = 3
SWEEP_POINT_SECONDS = 1e-5
SWEEP_VALIDATION_SECONDS = 0.3

#: Most values of one axis (``--grid``, ``--sweep``, a scene's grid), checked before any is made:
#: 10⁷ values are 80 MB as an array and 320 MB as the axis's tuple of floats (and 10⁷ points need
#: ``--yes`` anyway); 10⁹ were 8 GB made before any other check.
AXIS_MAX_VALUES = 10_000_000

#: Seconds of one pass of work-precision's methods (the analytic orders, RK4, the scipy methods
#: at their tolerances, heyoka) over one period of the problem, on one core: the Duffing
#: oscillator's --repeat 1 and 3 over 10 periods differ by 16.5 s a pass on a machine loaded 3
#: times over (0.55 s a period unloaded), the van der Pol oscillator's 0.7 s.
WORK_PRECISION_PERIOD_SECONDS = 0.6

#: Recorded times of a sweep's state that count as one point against the grid's limits
#: (SWEEP_CONFIRM_POINTS, SWEEP_MAX_POINTS): a point's own results are about ten numbers, so ten
#: times of its state weigh as much again; 10⁶ times at each of 10⁵ points would be 10¹¹ values.
SWEEP_STATE_SHARE = 10

#: Most points of one sweep even with confirmation: 10^10 float64 values per quantity are 80 GB
#: a variable; beyond it the grid is a mistake rather than a plan.
SWEEP_MAX_POINTS = 10_000_000_000

#: Samples of one period from which a component's amplitude (half its range) is found; each
#: extreme is then refined on the quartic through it and its four neighbours (the quartic's
#: interpolation error, max|x^(5)| (2 pi/256)^5 1.41/120: ~1e-10 of a first harmonic's amplitude).
#: Solutions evaluated in one vectorised call are refined on their own trigonometric polynomial,
#: exact to rounding; the samples only find which extreme is the highest.
SWEEP_AMPLITUDE_SAMPLES = 256

#: Work one task (a chunk of points) should hold: Dask's scheduling costs a few ms a task and the
#: driver's write of a chunk's results about 30-50 ms (``benchmarks/bench_sweep.md``), so 2 s
#: keeps both under 3 %, inside the 5 % allowed, while a 10^4-point validated map still makes
#: hundreds of chunks to share among the workers.
SWEEP_TASK_SECONDS = 2.0

#: What a task costs besides its points (Dask's scheduling, the result's trip back, the driver's
#: write): 9-35 ms measured on 2 cores (``benchmarks/bench_sweep.md``, overhead section).
SWEEP_TASK_OVERHEAD_SECONDS = 0.025

#: The share of a task's work its overhead may take: a chunk holds at least
#: SWEEP_TASK_OVERHEAD_SECONDS / SWEEP_OVERHEAD_SHARE (0.5 s) of work when the grid has it, even
#: if that leaves fewer than SWEEP_CHUNKS_PER_WORKER chunks per worker (a grid of cheap points).
SWEEP_OVERHEAD_SHARE = 0.05

#: Fewest chunks per worker when the grid allows it: with four, the last chunks to finish keep
#: every worker busy, and an interrupted sweep loses at most a quarter of a worker's share.
SWEEP_CHUNKS_PER_WORKER = 4

#: Points evaluated on the driver to time one point before the chunks are sized (evaluation; a
#: validated sweep times SWEEP_PILOT_VALIDATIONS points one by one and takes the median, after a
#: first one that pays the one-time costs). When they take less than SWEEP_PILOT_SECONDS, a
#: batch up to SWEEP_PILOT_GROWTH times larger is timed too, and a point's cost is the difference
#: over the extra points: a chunk's fixed cost (2 ms) is then not counted as the points' (it made
#: a point of van der Pol look 10 times dearer than it is).
SWEEP_PILOT_POINTS = 64
SWEEP_PILOT_SECONDS = 0.05
SWEEP_PILOT_GROWTH = 16
SWEEP_PILOT_VALIDATIONS = 3

#: A sweep whose swept parameters enter the problem's derivation makes each distinct derivation
#: once (per point) rather than one symbolic derivation when each serves this many points on
#: average: the disk at order 2 (measured, benchmarks/bench_sweep.md) derives one parameter set in
#: ~2.5 s and then validates a point in ~0.07 s, against ~0.18 s a point from the symbolic
#: solution, so a derivation pays for itself after ~20 points.
SWEEP_POINTS_PER_DERIVATION = 20

#: Most points of one chunk: a chunk's results travel back to the driver in one message, and its
#: state at many times grows as points x times x components.
SWEEP_MAX_CHUNK_POINTS = 100_000

#: Most memory the results of a sweep kept in memory (no store: ``--format csv|json``, Python
#: without ``output``) may take: a quarter of a small machine's 8 GiB, as numpy arrays; a larger
#: sweep writes a Zarr store, which holds one chunk at a time (a 10^5 x 10^5 grid asked for 18.6
#: GiB and failed with a MemoryError before this bound).
SWEEP_MEMORY_BYTES = 2 * 2**30

#: Bytes a text value of a sweep (a reason, a warning) is counted at in that estimate: a Python
#: string object of a few dozen characters.
SWEEP_TEXT_BYTES = 80

#: Times the chunks of a sweep whose scattered job was lost with a worker (the only one holding it)
#: are sent again with the job scattered afresh: killing workers again and again, a sweep still ends.
SWEEP_RESCATTERS = 3

#: Seconds a sweep waits on a cluster that has no worker (an existing scheduler whose workers
#: were stopped or never started) before it ends with a failed status ("no worker: start one,
#: then --resume"): a worker being restarted by its nanny is back in a few seconds.
SWEEP_NO_WORKER_SECONDS = 20.0

#: Pause between two looks at the cluster's workers while tasks are out.
SWEEP_WORKER_POLL_SECONDS = 1.0

#: Seconds to wait for an existing Dask scheduler (``--scheduler``) before giving up with one
#: line (exit 2): a scheduler on the network answers in well under a second.
SWEEP_CONNECT_SECONDS = 10.0

#: Pause between attempts to reach a scheduler that refuses the connection (it may be starting:
#: ``dask scheduler`` takes a few seconds), within ``--timeout``.
SWEEP_CONNECT_RETRY = 0.25

#: Longest wait for a scheduler that can be asked for (``--timeout``): a larger value is refused.
#: Dask's own connection timeout is 30 s; a scheduler that has not answered in a minute is not
#: starting up, and a run must never wait for ever on a silent port.
SWEEP_MAX_CONNECT_SECONDS = 60.0

#: Largest first frame a Dask scheduler sends when a connection opens (its handshake, about 60
#: bytes): an 8-byte length beyond this is another kind of server (an HTTP reply read as a frame
#: length asked Dask for 3 EiB).
SWEEP_HANDSHAKE_BYTES = 1 << 20

#: Most worker processes of a local cluster per core of the machine: each holds an interpreter,
#: numpy and sympy (about 150 MB); beyond a few per core they only compete for the cores (a
#: million asked for would start until the machine runs out of memory).
SWEEP_WORKERS_PER_CORE = 8

#: Points of a sweep's grid (its ends and evenly between) at which a family named by ``--family``
#: is looked for when the problem's own values do not have it (a driven problem's upper branch
#: exists only past its fold): each costs one root-finding of the amplitude equations.
SWEEP_FAMILY_PROBES = 9

#: Relative margin of the vectorised domain screen: a point whose terms are within this fraction of
#: failing (or passing) the check is decided by :func:`perturb.domain.series_domain` itself, so the
#: screen's round-off (float64 against sympy's evaluation) can never change a status.
SWEEP_DOMAIN_MARGIN = 1e-9


# --------------------------------------------------------------------------------------------------
# Validation (perturb.validation): the verdict's tolerances and the measurements' settings
# (its integrator and shooting tolerances are the oracle's DEFAULT_RTOL, SHOOTING_TOL, STIFF_RTOL above)
# --------------------------------------------------------------------------------------------------
#: Default tolerance of the accuracy checks (``tol=`` / ``--tol``): the largest distance of the
#: analytic orbit from the true one, relative to the orbit's size, and the largest relative period
#: error, of a solution still called valid.  10 % is where a plot of the analytic and the true curves
#: visibly separates; pass a smaller ``tol`` to demand more.
DEFAULT_TOL = 0.1

#: A series whose next term is estimated (perturb.domain.next_term) at more than this fraction of
#: its leading term is flagged as beyond its validity (a response point, a family, a sweep point):
#: the default accuracy tolerance, where the analytic and the true curves visibly separate. Forced
#: Duffing swept to eps = 10 has an estimate of 0.5 and amplitudes 8-20 % off the true motion.
VALIDITY_ESTIMATE_LIMIT = DEFAULT_TOL

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

#: Newton iterations allowed to the shooting: from a seed within O(ε^(n+1)) it converges in < 8;
#: the cap bounds the time spent when the expansion is wrong and the seed is far from any orbit.
SHOOTING_ITERATIONS = 20

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

#: A root of a parameter map's inverse (a fold's σ mapped back to Ω, the user values at another ε)
#: counts as real when its imaginary part is below this, relative to its size: sympy evaluates the
#: closed-form root in floating point, which can leave a round-off imaginary part of ~1e-16.
REAL_ROOT_TOL = 1e-12

#: Singular values below this fraction of the largest count as zero in the rank of the shooting's
#: Newton matrix (its columns are O(1) near the identity; 1e-9 keeps directions resolved to
#: ~1e-7 of the state, well above what an integration at 1e-12 can blur).
SHOOTING_RANK_RTOL = 1e-9

#: Relative size (to the largest) below which a slow-flow eigenvalue's real part counts as zero.
SLOW_FLOW_ZERO = 1e-9

#: Amplitudes at which the backbone is drawn (the backbone is drawn through the region the
#: response occupies: from 0 to BACKBONE_REACH times the largest response amplitude).
BACKBONE_SAMPLES = 41
#: The backbone is drawn up to this multiple of the largest response amplitude.
BACKBONE_REACH = 1.05
# --------------------------------------------------------------------------------------------------
# Pseudo-arclength continuation (perturb.continuation)
# --------------------------------------------------------------------------------------------------
#: The corrector (Newton on {G = 0, t.(x - x_pred) = 0}) has converged when its step is below this
#: fraction of max(1, |x|): Newton's error after such a step is of its square, ~1e-20, at the
#: rounding of float64.
CORRECTOR_TOL = 1e-10
#: Newton iterations the corrector may take: from a predictor inside its basin it needs 2-4; one
#: that needs more is on a step too long (it is rejected and the step halved).
CORRECTOR_MAX_ITER = 8
#: Iterations of a comfortable step: fewer and the step grows, more and it shrinks.
CORRECTOR_NOMINAL_ITER = 3
#: Growth of the step after a corrector that needed at most 2 iterations, and after a nominal one;
#: shrink after a slower one. Halving on a rejected step.
STEP_GROWTH_FAST = 1.6
STEP_GROWTH_NOMINAL = 1.2
STEP_SHRINK = 0.7
#: Largest angle (radians) between the tangents at two consecutive points: a longer step across
#: a bend risks landing on a neighbouring branch or stepping over two sign changes of a test
#: function (which cancel); 0.3 rad (17 degrees) keeps a bend's chord within 1 % of its arc.
MAX_TURN = 0.3
#: The default initial and largest step as fractions of the parameter range's width: at least 50
#: steps across the range, so values read off the curve start inside Newton's basin.
INITIAL_STEP_FRACTION = 0.005
MAX_STEP_FRACTION = 0.02
#: The floor of the step, a fraction of the initial step: below it the corrector fails where no
#: step would succeed (a singular point not passed, a curve that ends): a failed status says where.
MIN_STEP_FRACTION = 1e-9
#: Most points of one continuation: 50 steps per range and the growth above leave 10^4 as room for
#: a curve that winds many times through the range; past it the budget is spent and says so.
CONTINUATION_MAX_POINTS = 10_000
#: A sign change of a test function is located on its segment to this fraction of the segment's
#: arclength (the secant's bracket), with at most EVENT_MAX_ITER corrections: Illinois' secant
#: gains about 1.4 digits an iteration, bisection one bit, so 80 covers the worst case.
EVENT_TOL = 1e-13
EVENT_MAX_ITER = 80
#: A curve that comes back within this fraction of a step of its first point, running the same
#: way, is closed (a loop): its continuation stops there.
CLOSURE_FRACTION = 0.5
#: Newton iterations of a value read off the curve at a given parameter (from the cubic Hermite
#: interpolant of its segment): more and the reading falls back to the secant along the segment.
READ_MAX_ITER = 6

# --------------------------------------------------------------------------------------------------
# The order-N response (perturb.response): continuation, stability, measures
# --------------------------------------------------------------------------------------------------
#: Magnus steps over one period of the variational equation along the order-N series (sixth
#: order, three Gauss nodes a step): its error falls like S^-6 (a factor 64 a doubling, measured)
#: and at S = 128 the multipliers agree with DOP853 on the same equation (rtol 1e-12) to 4e-10 at
#: the forced Duffing's largest amplitude (|x| = 3.5 at Omega = 1.2, eps = 0.05; 2e-8 at S = 64),
#: far below the series' own O(eps^(N+1)) (tests/response/test_floquet.py); the product of the
#: multipliers is exp of the divergence's quadrature exactly, whatever S.
MAGNUS_STEPS = 128
#: The same along the drawn curves (every continuation point), where the multipliers only colour
#: the curve and bracket the Neimark-Sacker test's sign changes (each then located with
#: MAGNUS_STEPS): at 32 steps their error is ~2e-6 at the largest amplitude, and Liouville's
#: product is exact all the same.
MAGNUS_DRAW_STEPS = 32
#: A largest multiplier within this distance of the unit circle is marginal (stable = None): a
#: fold of the curve, or an undamped system whose multipliers lie on the circle (Liouville makes
#: their product exactly 1 there: a pair on the circle is at 1 to rounding, 1e-15).
MARGINAL_MULTIPLIER = 1e-9
#: A response curve is followed while its amplitudes stay below this many times the largest one
#: of the first-order census at the window's ends (and 1): beyond it ε a² is no longer small in
#: any problem the series is meant for, and the curve leaves the domain with that said.
AMPLITUDE_CAP = 10.0
#: The first-order points of a curve tried for the lift to order N (the homotopy in the
#: truncation), best-conditioned first: one suffices unless the homotopy turns back from it.
LIFT_TRIES = 6
#: The window of a response beyond its grid on each side, as a fraction of the grid's width: the
#: folds, branch points and Neimark-Sacker points just outside the sweep are found and reported
#: (marked outside), and a branch that turns just beyond an end is followed back into it.
WINDOW_MARGIN = 0.1

# --------------------------------------------------------------------------------------------------
# The true curve past the series (perturb.oracle.driven_family, perturb.response.true_curve)
# --------------------------------------------------------------------------------------------------
#: heyoka compiles a driven family's augmented field (state, parameters, monodromy, sensitivity:
#: 19 equations for one oscillator with 5 parameters) in compact mode: measured on the forced
#: Duffing, 1.1 s to compile and 0.7 ms a shot against 2.8 s and 0.37 ms unrolled; a true curve
#: takes a few hundred to a few thousand shots, so compact mode is the faster at every size met.
FAMILY_COMPACT_MODE = True
#: The most points of one true curve by default (``perturb response --true``; half each way from its
#: seed), and the most a user may ask for: a curve across a sweep takes 150-650 points on the
#: shipped problems (steps of 0.5-2 % of the range's width in scaled units, shorter at bends and
#: folds; benchmarks/bench_true_curve.md), each a Newton correction of 3-5 shots of ~1 ms of CPU;
#: 10^4 points is a few minutes of the oracle, the budget's ceiling.
TRUE_CURVE_POINTS = 1000
TRUE_CURVE_MAX_POINTS = 10_000
#: The true curves are followed this fraction of the sweep's width past each end, so that a
#: special point just outside the sweep is reported (as outside).
TRUE_CURVE_MARGIN = 0.05
#: Samples of a true orbit per response period for its peak |x| (refined by a parabola through the
#: largest three: relative error ~(pi/n)^4 m^4, 1e-7 for the resonant harmonic m = 1) and its
#: resonant harmonic's amplitude (the trapezoid rule on a periodic orbit: spectrally accurate).
TRUE_CURVE_SAMPLES = 128
#: A largest |Floquet multiplier| within this of 1 is marginal (None: a conservative orbit, whose
#: multipliers lie on the circle to the integration's accuracy, ~1e-13); a Neimark-Sacker test
#: below it is round-off (a conservative map's pairs all have product 1), and the square root of
#: it is how close to the circle a located pair must lie (an eigenvalue of a double root moves
#: like the square root of the perturbation).
TRUE_CURVE_MULTIPLIER_TOL = 1e-9
#: Two scaled points (state / its scale, parameter / the sweep's width) closer than this are one
#: orbit: a seed on a curve already followed. The corrector converges to 1e-10; distinct branches
#: lie orders of magnitude further apart.
TRUE_CURVE_SAME_ORBIT = 1e-6

# -- perturb.response.true_maps, true_branches (the whole diagram of the true responses)
#: Newton on the minimally augmented system {R = 0, ψ = 0} of a special point: converged when a
#: step is below this (relative to max(1, |x|), in the scaled unknowns); its gradient of ψ by
#: central differences of this relative step (shots accurate to ~1e-15: the difference's error
#: ~1e-15/1e-6 + 1e-12, far below the 1e-8 asked of a located point); a point that needs more
#: than REFINE_MAX_ITER steps keeps the secant's location, and says so.
REFINE_TOL = 1e-11
REFINE_STEP = 1e-6
REFINE_MAX_ITER = 12
#: The first step onto a branch born at a branch point or a period doubling, along the null
#: direction, as a fraction of the continuation's largest step: far enough that the corrector on
#: the hyperplane across it finds the new branch, not the parent (which crosses it at distance
#: ~0 only at the birth), near enough to stay in its basin.
BRANCH_SWITCH_FRACTION = 0.25
#: The longest cascade of period doublings followed by default (a response of 2 periods: the
#: first doubling), and the most a user may ask for (``--max-period``): past 16 periods a
#: cascade's steps are closer than the location's own tolerance in most systems (Feigenbaum's
#: ratio 4.67: the fifth doubling lies 2e-3 of the first interval from the accumulation point).
MAX_PERIOD_DEFAULT = 2
MAX_PERIOD_CAP = 16
#: The most branches one diagram follows (each a continuation of up to the --true budget): a
#: symmetric system's pair at each of a few pitchforks and their doublings is tens; past it the
#: remaining births are listed, not followed.
MAX_BRANCHES = 64

# -- perturb.continuation.reading
#: Two readings closer than this (relative to max(1, |x|)) are one point: the same crossing seen
#: from the two segments that share an end, far below any distance between distinct branches.
SAME_READING = 1e-8

# -- perturb.cache
#: Age, in seconds, past which a writer's temporary file in the cache folder is a leftover: a
#: writer renames its file onto the entry within milliseconds, so an hour-old one was left by a
#: process killed while writing (it is removed at the process's first write into the folder).
CACHE_LEFTOVER_SECONDS = 3600

# -- perturb.case.parameters
#: Digits of the evaluation of an inverse at the given doubles (taken as exact): far past double
#: precision, so the double returned is the correctly rounded value of the exact inverse.
EVAL_DIGITS = 30

# -- perturb.case.case
#: User values moved to another ε (:meth:`perturb.case.Case.with_epsilon`) kept in the disk cache
#: (kind ``moved-values``), the most recently written: under 1 kB each; the order check of a
#: validated sweep moves four times at every point.
MOVED_VALUES_CACHE_ENTRIES = 1024

# -- perturb.domain
#: A solution's coefficients evaluated at a point's values, kept in the disk cache (kind
#: ``series-numbers``), the most recently written: a few kB each; a validated sweep makes new
#: ones at every point (its values, and the order check's four rescaled ones).
SERIES_NUMBERS_CACHE_ENTRIES = 512

# -- perturb._lambdify
#: Generated numpy functions whose source is kept in the disk cache (kind ``lambdified``), the
#: most recently written: a few kB each; a sweep makes new ones at every point (its fields hold the
#: point's numbers).
LAMBDIFIED_CACHE_ENTRIES = 512

# -- perturb.oracle.heyoka
#: Compiled heyoka integrators kept in the disk cache (kind ``taylor``), the most recently written:
#: each holds its machine code (0.3-0.6 MB for the disk's fields), and a sweep integrates a new
#: field at every point, so without a bound a validated 441-point map would leave ~0.4 GB.  The
#: warm single commands reuse a handful; a re-run sweep compiles again past this many.
TAYLOR_CACHE_ENTRIES = 32

# -- perturb.oracle.symbolic
#: Fields whose numeric functions are kept by value (:func:`_derived`): a sweep builds an equal
#: field at every point, and a validation asks each for its numeric functions.
DERIVED_CACHE_SIZE = 64

# -- perturb.method.families
#: How many orders past the requested one a continuum with several free amplitudes is carried to
#: see whether a later order restricts it (Hénon–Heiles: the directions of its lines are fixed by
#: the conditions of order 4, i.e. carrying order 2, from the requested order 1: one order more;
#: two leave room for a family order of 2 on a quadratic right-hand side's neighbour).
PROBE_ORDERS = 2

#: Successive restrictions of one continuum (each removes at least one free amplitude).
MAX_RESTRICTIONS = 4

# -- perturb.method.family_names
#: A standing wave of n coordinates is "localised" when its participation number is at most this
#: fraction of n + 1: it moves fewer than about half of the coordinates (module notes, rule 4).
LOCALISED_BELOW = 0.5
#: A driven response's coordinate is at rest when its amplitude is at most this fraction of the
#: largest (``response_shape``): far below any amplitude a forcing gives (a symmetry's exact zero
#: comes out of the certified roots as ~1e-38), far above the roots' rounding.
AT_REST = 1e-12

# -- perturb.algebra.certified
#: On the msolve route a leaf's linear pivot is put in only when it raises the largest total
#: degree by at most this: the frequency correction of a free system (3 -> 4; the chain of 6:
#: 13 s -> 2 s) is, a driven system's forced amplitude is not (a cubic into cubics, 3 -> 9:
#: the forced pair's four unknowns took 1.2 s that way against 0.06 s as typed).
PIVOT_GROWTH = 1

# -- perturb.steady.singular
#: A singular point is a branch point when :math:`|w\cdot P_\lambda| \le` this times
#: :math:`|P_\lambda|` (w of unit length): symmetry makes the product zero exactly, the roots come
#: from a certified isolation to 2**-128, so their rounding leaves ~1e-15; a fold's is of order 1.
BRANCH_POINT_TOL = 1e-8
#: Relative distance below which two singular points are one: the same value and the same
#: amplitude of every coordinate (a shift by a forcing period rotates the phases, never the norms).
SAME_POINT = 1e-9

# -- perturb.sweep.phase
#: Budget of one line's exact first-order singular points (five unknowns for a pair: msolve on
#: {P1 = 0, det J = 0} takes seconds to tens of seconds; past it the line's boundaries are missing
#: and said so in ``failures``).
SINGULAR_SECONDS = 120.0

# -- perturb.workprecision
#: Tolerance of the reference when heyoka's extended precision is unavailable: one decade below the
#: tightest compared tolerance.
REFERENCE_RTOL = 1e-13

#: Timed runs per point after the warm-up (the best is reported); 3 removes most scheduling noise.
DEFAULT_REPEAT = 3

# -- perturb.solution
#: Parameter sets whose coefficients a solution keeps (:meth:`PeriodicSolution.coefficients`): a
#: validation asks at its own set and at the sets of its order check (four values of epsilon).
RECENT_COEFFICIENTS = 8

#: Coefficients with more operations than this are shown as computed: factoring them would take
#: longer than anyone waits for a printout.
DISPLAY_SIMPLIFY_MAX_OPS = 4000

# -- perturb.response.model
#: Most points ``--validate`` shoots on each branch besides the ones it always shoots (largest
#: amplitude, fold sides, ends): each is a shooting with variational equations, 0.05-0.5 s.
MAX_VALIDATE = 50

# -- perturb.response.true_partings
#: Amplitudes below this are the trivial response x = 0 (as the analytic branches' TRIVIAL).
TRIVIAL_AMPLITUDE = 1e-12

# -- perturb.response.true_curve
#: Seeds tried on one analytic branch before it is given up (each costs an analytic solution at
#: its value and a Newton correction).
SEED_TRIES = 3

# -- perturb.response.truth
#: Samples of the true orbit over one period: its trigonometric interpolant holds harmonics up to
#: 511, whose coefficients for a smooth weakly nonlinear orbit are at rounding long before that.
TRUTH_SAMPLES = 1024

#: How far beside a fold its two checked points lie, as a fraction of the curve's arclength in
#: the sweep (at least one continuation step): off the fold's singular Newton matrix, near enough
#: to show the branch's end.
FOLD_SIDE = 0.01

# -- perturb.response.hysteresis
#: Samples per forcing period of the envelope.
SAMPLES_PER_FORCING_PERIOD = 40

#: The window (a fraction of the sweep's periods) over which a jump's change is measured.
JUMP_WINDOW = 0.05

#: Forcing periods the response settles for at the start frequency before the ramp begins.
SETTLE_PERIODS = 400

# -- perturb.dynamics (where the motion goes: basins, transients, ramps)
#: A steady state is stable when its largest |Floquet multiplier| is below 1 by more than this,
#: a saddle when above 1 by more: the shooting's multipliers are good to ~1e-10, and a state
#: within 1e-6 of the unit circle attracts too slowly to be told from a marginal one in a cap
#: of periods (it is neither an attractor nor a saddle of the catalogue).
DYNAMICS_MULTIPLIER_MARGIN = 1e-6

#: The capture radius of an attractor, as a share of the distance from its stroboscopic points to
#: the nearest other catalogued state (another attractor, a saddle, its own next point): a tenth
#: keeps the ball inside the immediate basin of a hyperbolic focus (the basin boundary passes
#: through the saddle, ten radii away), where the map is near its linearisation.
BASIN_CAPTURE_SHARE = 0.1

#: Consecutive stroboscopic returns inside the capture radius that classify a point: one could
#: be a passage; four of a focus contracting by 0.97 a period are the approach itself.
BASIN_CAPTURE_RETURNS = 4

#: Drive periods integrated between two classifications of the points still running: the
#: integrator's calls (per batch of lanes) are amortised over them, and a point classified runs
#: at most this many periods too long (a capture takes ~100). Measured on the forced Duffing
#: (CPU per initial state, 16 lanes): 0.207 ms at 4, 0.183 at 8, 0.167 at 16.
BASIN_BLOCK_PERIODS = 16

#: The default cap of drive periods: the forced Duffing at its defaults (contraction e^(-eps
#: zeta T) = 0.969 a period) comes within a tenth of a basin's size from anywhere in ~200.
BASIN_DEFAULT_PERIODS = 1000

#: The longest period (in drive periods) a recurrence is looked for at.
BASIN_RECURRENCE_MAX_PERIOD = 8

#: A recurrence of period k: the k-th return within this of the point (relative to the scale
#: of the states) for BASIN_CAPTURE_RETURNS returns in a row — converged to an orbit, which a
#: transient contracting by 0.97 a period does not mimic (its returns move by 3 % of its distance).
BASIN_RECURRENCE_TOL = 1e-7

#: A point whose state grows past this many times the scale of the catalogued states escapes
#: (an unbounded motion, e.g. over a softening potential's barrier): its integration stops.
BASIN_ESCAPE_FACTOR = 50.0

#: A basin study of at most this many initial states runs in this process unless workers are
#: asked for: a LocalCluster takes 2-4 s to start, which 2,500 states (about 1 s) do not repay.
BASIN_LOCAL_POINTS = 2500

#: Seconds of one core per initial state, for sizing chunks and the cost rule: 0.4 ms measured
#: on the forced Duffing (heyoka, ~100 periods to capture; benchmarks/bench_basins.md); the
#: numpy route is ~30 times slower.
BASIN_POINT_SECONDS = 4e-4

#: A transient samples at most this many drive periods (TRANSIENT_SAMPLES states each: 256 MB
#: for a two-coordinate state); a longer one is a slip (an extra zero), not a plan.
TRANSIENT_MAX_PERIODS = 1_000_000

#: Seconds of one core per drive period of a transient or a ramp (heyoka's dense output, tens of
#: samples a period; measured ~1e-4 s on the forced Duffing), for the cost rule.
DYNAMICS_PERIOD_SECONDS = 1e-4

#: A ramp's run lasts at most this many drive periods (its envelope is sampled 40 times a period:
#: ~250 MB of states); a rate that needs more is a slip, or a study for a faster rate first.
RAMP_MAX_PERIODS = 200_000

#: The seed of the random initial states of a basin-stability estimate (``--samples``): the
#: same states on every run and every worker.
BASIN_SEED = 0

#: Tolerance of the batch Taylor integrator of an ensemble: a basin's classification needs the
#: stroboscopic point to well below the capture radius (~1e-2), and 1e-10 keeps the route within
#: 1e-8 of scipy's DOP853 at rtol 1e-12 over a cap of periods (tests/dynamics) while taking 20 %
#: fewer steps than machine precision.
ENSEMBLE_TOL = 1e-10

#: Lanes of the batch Taylor integrator (a multiple of the 4 doubles of an AVX2 register):
#: measured ~1.4 us per point and period on the forced Duffing at 4, 8 and 16 lanes alike, and
#: 16 halves the calls (0.167 ms per initial state against 0.176 at 8; bench_basins.md).
ENSEMBLE_LANES = 16

#: Steps of the numpy route's classical Runge-Kutta per drive period: on the forced Duffing its
#: global error after 20 periods from |x| <= 3 is 6e-5 at 128 steps and 4e-6 at 256 (h^4), so
#: ~2e-4 after a cap of 1000 periods, far below a capture radius (~1e-1).
ENSEMBLE_RK4_STEPS = 256

#: Samples per drive period of a transient's true motion (its envelope, the plotted curve).
TRANSIENT_SAMPLES = 32

#: The slow flow's separatrix starts this far from the saddle along the stable eigenvector
#: (relative to the saddle's amplitude): the linearisation holds there to ~1e-8.
SEPARATRIX_OFFSET = 1e-4

#: The separatrix is followed backwards in slow time until it leaves the picture's box enlarged
#: by this factor, or for at most SEPARATRIX_SPAN units of slow time (eps t).
SEPARATRIX_MARGIN = 1.5
SEPARATRIX_SPAN = 200.0

#: A ramp's jump is the largest change of its envelope over this many drive periods: a window
#: of periods, not a share of the ramp, shrinks in the ramped parameter with the rate (the
#: response needs ~1/(eps zeta) of time to fall to the other branch; ten periods see its start).
RAMP_JUMP_PERIODS = 10

#: The jump is the first run of windows changing by at least this share of the largest change:
#: after a jump the response swings about its new branch (an overshoot, beats), by less than the
#: jump itself but by more than a fifth of it.
RAMP_JUMP_SHARE = 0.5

# -- perturb.sweep.evaluate
#: A sampled component whose step from the end of the period back to its start exceeds this many
#: times its largest step within the period does not return: it is not periodic (no amplitude).
#: A smooth periodic component's steps differ by O(1) factors, a phase's wrap by the sample count.
NOT_PERIODIC_STEP = 8.0

#: Rows computed at once: the Newton steps' temporaries (4096 complex numbers, 64 KiB) stay below
#: the size from which malloc maps fresh pages from the system for each array — which a Dask
#: worker's MALLOC_TRIM_THRESHOLD_ makes it do for every large one (the temporaries of a whole
#: chunk made the amplitudes 4 times slower on a worker than here); measured best of 512 to 4096.
SWEEP_SAMPLE_BLOCK = 4096

#: Newton steps that polish an extreme of a trigonometric polynomial found on the samples (the
#: sample is within half a spacing; Newton converges quadratically from there).
SWEEP_NEWTON_STEPS = 4

# -- perturb.algebra.triangular
#: Separating linear forms tried on a component whose lex basis is not in shape position.
SEPARATING_FORMS = 3

#: Digits of the floats given beside the exact values.
TRIANGULAR_DIGITS = 30

# -- perturb.algebra.msolve
#: Threads given to msolve. One: on 2 cores shared with other work, ``-t 2`` made the same
#: chain-of-4 solve take 0.5-19.5 s from run to run against 0.6-1.0 s with one thread.
MSOLVE_THREADS = 1

#: Digits beyond those a root's size needs, in its Newton refinement (``_refined``).
GUARD_DIGITS = 15

#: Newton steps of a refinement; from msolve's midpoint (38 correct digits) a few suffice.
MSOLVE_NEWTON_STEPS = 8

# -- perturb.algebra.rootset
#: Digits of a root handed to the construction when it is not known exactly (the later orders
#: are then computed in floats of this precision; msolve's boxes are narrower than 1e-38).
NUMBER_DIGITS = 30

# -- perturb.algebra.split
#: Pieces one system may be cut into before the cutting stops (each is then solved as it is).
SPLIT_MAX_PIECES = 256

# -- perturb.cli._progress
#: A step of a run not on a terminal (stderr a file or a pipe) is printed once it has lasted this
#: long: a long run says what it is doing within a second, a quick one prints nothing.
PROGRESS_FIRST_SECONDS = 0.5
#: ... and again every this many seconds while it lasts (a log of a ten-minute sweep: 60 lines).
PROGRESS_LINE_SECONDS = 10.0
#: A terminal's line is redrawn at least this often while a step lasts (its elapsed time ticks).
PROGRESS_REDRAW_SECONDS = 1.0
#: The heartbeat's period: how late a due line or redraw may come.
PROGRESS_TICK_SECONDS = 0.1

# -- perturb.cli._parser, perturb.cli._order
#: The default order of ``perturb response``: the curve is continued, so order 3 costs about
#: what order 1 does, and at the forced Duffing's defaults it places the jump-down fold within
#: 1.1e-4 of the true one (order 1: 5e-3 beyond it; tests/response/test_special_points.py).
RESPONSE_ORDER = 3
#: The default order of every command for a driven problem: the response's, so that
#: ``validate``, ``families``, ``solve``, ``sweep`` and ``phase-diagram`` use the series
#: ``response`` draws (the amplitude equations of the shipped driven problems at order 3: 0.2 to
#: 3 s to derive, against 0.1 to 0.2 s at order 1).
DRIVEN_ORDER = RESPONSE_ORDER
#: ... and for a free problem: a rigid body's derivation grows steeply with the order (the disk
#: at order 3: 13 s symbolic), and a free problem's series is not continued.
FREE_ORDER = 1

# -- perturb.solution
#: Points per block in the scalar evaluation: small enough for the block's complex work arrays to
#: stay in the L2 cache (16384 complex numbers = 256 KiB), which makes in-place Horner ~3x faster.
EVAL_BLOCK = 1 << 14

# -- perturb.continuation.events
#: Where the corrector fails at the secant's point (exactly on a branch point, where the bordered
#: matrix is singular), the point is moved this fraction of the way to the bracket's far end, then
#: further: any point off the singular one will do, the bracket still holds the zero.
NUDGES = (1e-6, 1e-3, 0.1)

# -- perturb.algebra.split
#: Terms of the value of a linear pivot put in while cutting (longer ones wait for the leaf:
#: putting the frequency correction into every piece cost 8 of the 10 s of the chain of 6).
SHORT_PIVOT = 2

# -- perturb.algebra.certified
#: Digits of an irrational exact root's approximation, carried through the back-substitution
#: (the construction is handed 30, :data:`~perturb.algebra.rootset.NUMBER_DIGITS`).
LIFT_DIGITS = 40

#: With ``backend="auto"`` each piece is first given this long on the exact route (exact
#: radicals, the same values as without the extra), then msolve: the chain of 3's piece takes
#: 0.5 s exactly, the chain of 4's runs past 60 s, which msolve isolates in 0.4 s.
EXACT_FIRST_SECONDS = 2.0

#: Digits to which a root with inexact values must satisfy a continuum's equations to count as a
#: point of it (its values carry at least 30, NUMBER_DIGITS; cubic equations: scale**3).
ON_DIGITS = 20

# -- perturb.steady.measures
#: Samples of one period on which the largest |x| is found before Newton polishes it: 256 resolve
#: the harmonics of an order-12 series of a cubic system (up to 3^12 is not reached: a series'
#: harmonics grow like the order times the nonlinearity's degree, ~40) with several samples each.
PEAK_SAMPLES = 256

#: Terms below this fraction of the largest one do not count in the check that the terms
#: decrease: far from resonance the detuning makes them comparable (ε σ ~ 0.5 at the forced
#: Duffing's Ω = 1.46) while each is 1e-5 of the amplitude, a change no figure and no tolerance
#: sees; a diverging series is flagged as soon as its terms reach it.
NEGLIGIBLE_TERM = 1e-4

#: Newton steps polishing an extreme from the nearest sample (quadratic from half a spacing).
PEAK_NEWTON = 5

# -- perturb.steady.line
#: Relative step of the centred differences of a map that is not affine (eps^(1/3)).
MAP_STEP = 6e-6

# -- perturb.steady.polynomial
#: Rows with at most this many (monomial, variable) pairs are generated as Python code
#: (:meth:`CompiledPolynomials.function`): a few thousand float operations, tens of microseconds;
#: beyond it numpy's arrays win.
GENERATED_MAX_TERMS = 4000

# -- perturb.steady.roots
#: Budget of one parameter point's equations: a driven system's response equations (two to four
#: unknowns, low degree) take milliseconds; when it is spent the status says so with the size.
RESPONSE_SECONDS = 60.0

# -- perturb.steady.traced
#: The homotopy's range beyond [0, 1]: it is followed until it leaves it, so that τ = 1 is read
#: inside the curve.
HOMOTOPY_MARGIN = 0.05

#: The homotopy's initial and largest steps, as fractions of 1 + the amplitude it starts from: its
#: arclength runs in the amplitudes as much as in τ, and a root moves by O(ε) of its size.
HOMOTOPY_STEP = 0.02

HOMOTOPY_MAX_STEP = 0.1

# -- perturb.steady.census
#: Two responses whose amplitudes (or one's image) agree to this relative distance are one orbit:
#: far above the census' isolation width and the corrector's tolerance, far below any two
#: distinct branches.
CENSUS_SAME_ORBIT = 1e-7

# -- perturb.steady.lineage
#: An order-N branch carried to the order-(N−1) equations (Newton or the homotopy, each polished to
#: the corrector's tolerance) lands on the order-(N−1) branch whose amplitudes agree with the root
#: it reached to this relative distance: far above both correctors' tolerances (~1e-10), far
#: below any two distinct branches (CENSUS_SAME_ORBIT is the census' own, tighter, identity).
ORDER_LINK = 1e-6

#: A branch not carried to one order lower is paired with the nearest order-(N−1) branch only
#: when they differ by less than this fraction of the larger size (besides being each other's
#: nearest, closer than half the distance to any other): two responses whose amplitudes differ
#: by half their size are not one orbit corrected by one more order.
ORDER_NEAREST = 0.5

#: Largest fraction 1/G of the forcing period tried as a symmetry of the equations: beyond the
#: largest harmonic a driven system's forcing has (MAX_RESONANCE_INTEGER) with room to spare.
MAX_SHIFT_DIVISOR = 24

#: Points (state, θ, parameters and ε drawn in [0.2, 0.6], a fixed seed: the same everywhere) at which
#: a shift of θ is tried, and the agreement that counts as invariant: the rounding of a
#: right-hand side of size O(1) is ~1e-15, a term that moves under the shift moves it by O(1).
SYMMETRY_PROBES = 3

SYMMETRY_SEED = 20_290

SYMMETRY_TOL = 1e-9

#: Budget of the exact first-order folds on a line: a driven system's take 0.5-4 s (the absorber's
#: five unknowns); a budget spent leaves the census at interior points to find closed branches.
FOLD_SECONDS = 30.0

#: Budget of the order-N census at a window's end (every real root of the order-N equations,
#: certified): one oscillator's order-3 equations (degree 9 in two unknowns, 81 complex roots)
#: take 0.1-0.3 s; a budget spent leaves the first-order seeds alone (said nowhere: they were
#: the seeds before).
ORDER_CENSUS_SECONDS = 10.0

#: The order-N census is tried when the Bezout bound of the order-N equations (the product of
#: their total degrees) is at most this: one oscillator to order 3 (9 x 9 = 81) or 4 (121) and
#: two at order 1 take well under a second; a chain of three at order 2 (7^6 = 117649) spends
#: any budget (measured: 20 s not enough), so its first-order seeds are the only ones.
ORDER_CENSUS_BEZOUT = 400

#: A root of the order-N census seeds a curve only when the series' own estimate of its error
#: (the last correction, max over a period of |x_N - x_(N-1)|) is at most this fraction of its
#: amplitude, the limit of its validity (VALIDITY_ESTIMATE_LIMIT): a truncated series has roots
#: far from every motion whose terms still decrease (the forced Duffing at its defaults, order 3,
#: Omega = 1.48, past the true jump-down 1.2629: an "upper branch" of amplitude 5.8 with a
#: correction of 17 % of it; order 2, amplitude 15: 30 %), where a motion the series describes
#: has a correction of 1e-7 to a few per cent. A branch whose seeds are all above it is still
#: seeded by the first-order census, as before the order-N census.
ORDER_SEED_ERROR = 0.1

#: How far beyond the window (in the line's scaled unit μ: σ when sweeping Ω) the response's
#: curves are followed, and the first-order folds taken as seeds: a branch of the order-N
#: equations whose first-order counterpart turns just outside the window is continued in from
#: there, and a fold of the order-N curve within this of the window is reported (marked
#: outside). The order-N fold lies O(ε) in σ from the first-order one (0.04 for a softening
#: Duffing at ε = 0.1); half a unit of σ covers that with room.
FOLD_REACH = 0.5

#: A fold of order N and one of the order below (or of the first-order equations) are the same
#: fold when their amplitudes agree to this fraction of the larger (and the nearest such in
#: (amplitudes, μ) is taken, each once): the series moves a fold's amplitude by O(ε) of it,
#: while a response's two folds differ in amplitude by O(1) (jump-up 0.9, jump-down 4.0 on the
#: README's Duffing).
FOLD_PAIRING = 0.3

#: Beyond the window the continuation's largest step is this share of the reach's width (within
#: it, the window's own MAX_STEP_FRACTION): a narrow sweep's reach, many windows wide, is
#: crossed in a few hundred steps, not thousands.
REACH_STEP_SHARE = 0.25

# -- perturb.steady.evaluate
#: An order-N point whose Newton step to the order-(N−1) equations moves it by less than this
#: fraction of its amplitudes has a counterpart one order lower (the orders' roots differ by
#: O(ε^N) away from folds); a longer move is decided by the homotopy in the truncation.
LOWER_LEAP = 0.5

#: The homotopy back to order N − 1 stays within this many times the point's amplitude.
LOWER_CAP = 4.0

#: Along a continued curve the order-(N−1) counterpart is tried at every this-many points, and at
#: every point between two that disagree: consecutive points are a step apart (at most 2 % of
#: the window), far closer than the features of a lower order's curve.
ALONG_STRIDE = 4

# -- perturb.steady.continued
#: A fold and a branch point this close (relative, in λ and amplitudes) are one point: a
#: pitchfork, where the branch crossing the other turns in λ too.
SAME_CONTINUED_POINT = 1e-6

# -- perturb.steady.branches
#: The window in the detuning σ around one point over which its branches are followed: at least
#: this wide on each side, and this share of |σ| (the order-N folds lie O(ε σ-scale) from the
#: first-order ones: 4 in σ for the forced Duffing's defaults at order 1, where ε a² ~ 0.5).
SINGLE_POINT_WINDOW = 2.0

SINGLE_POINT_SHARE = 0.5

# -- perturb.workprecision
#: Steps per unit time of the RK4 runs: a factor 2 apart, from visibly inaccurate (error ~1e-3 on
#: unit-frequency oscillators over 10 periods) to the round-off plateau.
RK4_STEPS = (10, 20, 40, 80, 160, 320)

#: Tolerances of the scipy runs: from engineering accuracy to three digits above round-off.
SCIPY_TOLERANCES = (1e-6, 1e-8, 1e-10, 1e-12)

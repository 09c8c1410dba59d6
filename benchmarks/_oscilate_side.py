# Run by benchmarks/bench_oscilate.py in a scratch venv where `pip install oscilate` was done
# (OSCILATE is never a dependency of perturb).
"""Run inside a venv with oscilate: print JSON of the backbone (omega, xmax) at amplitudes, and
the steady-state amplitudes of the forced response at one frequency, with the times."""

import json
import sys
import time

t0 = time.perf_counter()

from oscilate import MMS  # noqa: E402 (imported after the clock starts: its import is timed)
from sympy import Function, symbols  # noqa: E402

which, Ne = sys.argv[1], int(sys.argv[2])
omega0, F, c = symbols(r"\omega_0, F, c", real=True, positive=True)
gamma = symbols(r"\gamma", real=True)
t = symbols("t")
x = Function(r"x", real=True)(t)
Eq = x.diff(t, 2) + omega0**2 * x + gamma * x**3 + c * x.diff(t)
if which == "direct":
    dyn = MMS.Dynamical_system(t, x, Eq, omega0, F=F)
    ratio = 1
else:
    dyn = MMS.Dynamical_system(t, x, Eq, omega0, fF=-2 * x, F=F)
    ratio = 2
eps = symbols(r"\epsilon", real=True, positive=True)
param_scaled, sub_scaling = MMS.scale_parameters((gamma, F, c), (1, Ne, Ne), eps)
mms = MMS.Multiple_scales_oscillator(dyn, eps, Ne, omega0, sub_scaling, ratio_omegaMMS=ratio)
mms.apply_MMS() if which == "direct" else mms.apply_MMS(orders_polar="all")
ss = MMS.Steady_state(mms)
ss.solve_bbc(solve_dof=0, c=param_scaled[-1])
ss.solve_forced(solve_dof=0)
ss.stability_analysis_forced(coord="polar", eigenvalues=True)
derive = time.perf_counter() - t0

a0 = ss.coord.a[0]
g_t = [s for s in ss.sol_bbc.omega.free_symbols if "gamma" in s.name][0]
subs = {eps: 1, omega0: 1, g_t: 0.2}
out = {"derive_seconds": derive, "backbone": []}
for a in (0.2, 0.6, 1.0):
    w = float(ss.sol_bbc.omega.subs(subs).subs(a0, a))
    xm = ss.sol_bbc.xmax.subs(subs).subs(a0, a)
    xm = float(xm.subs({s: 1 for s in xm.free_symbols}) if xm.free_symbols else xm)
    out["backbone"].append({"a": a, "omega": w, "xmax": abs(xm)})
print("JSON" + json.dumps(out))

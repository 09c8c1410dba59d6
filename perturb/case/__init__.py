"""Cases: a system, the map from its user's parameters, one point of values (the seam).

:class:`ParameterMap` declares how user parameters become the system's symbols and ε;
:class:`Case` holds one point of them and answers every question a client asks of a problem's
numbers (another point, another ε, many points as columns, many points checked with the one
model serving them (:class:`CasePoints`), a system value back in user terms).
"""

from perturb.case.case import Case, CaseColumns
from perturb.case.parameters import EPSILON_KEY, ParameterMap
from perturb.case.points import CasePoints

__all__ = ["EPSILON_KEY", "Case", "CaseColumns", "CasePoints", "ParameterMap"]

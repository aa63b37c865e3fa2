"""Small helpers the study and benchmark scripts share for their tables."""
import math


def fmt(x, spec):
    """x formatted with spec, "-" for None or nan (a value a run did not give)."""
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    return format(x, spec)

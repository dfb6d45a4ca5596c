"""The exported model as one C99 file (libm only): ``bk_steady``, ``bk_steady_at``, the
``bk_state`` struct, ``bk_init`` and ``bk_step``."""

from __future__ import annotations

from string import Template

from .. import __version__
from .model import ExportModel
from .text import ascii_units, constants, header_lines

_SOURCE = Template('''/*
 * Friction model exported by breakaway $version from a $kind identification report.
 * C99, no dependencies beyond libm (link with -lm).
 *
$header
 *
 * double bk_steady(double v);               Fss(v) [$F] at T_0, v [$v]
 * double bk_steady_at(double v, double t);  Fss(v) [$F] at time t [$t] (drift)
 * void   bk_init(bk_state *s);              the virgin state
 * double bk_step(bk_state *s, double x, double t);
 *                                           friction [$F] at x [$x], t [$t]; t must
 *                                           increase (NAN, state unchanged, if not)
 */
#include <math.h>

$constants

/* Reversal memory of (E6') and the previous sample. */
typedef struct {
    int started;   /* 0 until the first sample */
    int d;         /* direction of motion: +1, -1; 0 before the first motion */
    double x_r;    /* position at the last reversal [$x] */
    double F_r;    /* friction at the last reversal [$F] */
    double x_prev; /* previous sample: position [$x] */
    double t_prev; /* time [$t] */
    double F_prev; /* friction [$F] */
} bk_state;

/* g(v) of (E2) [$F] with the levels of the direction, times the drift factor. */
static double bk_magnitude(double v, int negative, double t)
{
    double fc = negative ? BK_FC_NEG : BK_FC;
    double fs = negative ? BK_FS_NEG : BK_FS;
    double level;
    if (v == 0.0)
        level = BK_DELTA > 0.0 ? fs : fc; /* the limits of g at rest */
    else
        level = fc + (fs - fc) * exp(-pow(fabs(v) / BK_V, BK_DELTA));
    return level * (1.0 + BK_ALPHA * (t - BK_T_0));
}

/* SIGMA*sgn(v)*|v|^N [$F] (N = 1: linear viscous friction). */
static double bk_viscous(double v)
{
    return copysign(BK_SIGMA * pow(fabs(v), BK_N), v);
}

double bk_steady_at(double v, double t)
{
    if (v == 0.0)
        return 0.0;
    return copysign(bk_magnitude(v, v < 0.0, t), v) + bk_viscous(v);
}

double bk_steady(double v)
{
    return bk_steady_at(v, BK_T_0);
}

void bk_init(bk_state *s)
{
    s->started = 0;
    s->d = 0;
    s->x_r = 0.0;
    s->F_r = 0.0;
    s->x_prev = 0.0;
    s->t_prev = 0.0;
    s->F_prev = 0.0;
}

double bk_step(bk_state *s, double x, double t)
{
    double v = 0.0, target, z, shape, F;
    if (!s->started) {
        s->started = 1;
        s->x_r = x;
    } else {
        double dx = x - s->x_prev;
        if (!(t > s->t_prev))
            return NAN;
        v = dx / (t - s->t_prev); /* backward difference [$v] */
        if (dx != 0.0) {
            int sign = dx > 0.0 ? 1 : -1;
            if (s->d == 0) {
                s->d = sign; /* the first motion: no reversal */
            } else if (sign != s->d) {
                /* a reversal: a new branch from the previous sample */
                s->x_r = s->x_prev;
                s->F_r = s->F_prev;
                s->d = sign;
            }
        }
    }
    target = s->d * bk_magnitude(v, s->d < 0, t) + bk_viscous(v);
    z = fmin(BK_S * fabs(x - s->x_r), 1.0);
    shape = z > 0.0 ? z * (1.0 - log(z)) : 0.0; /* f(z) of (E4) */
    F = s->F_r + (target - s->F_r) * shape;     /* (E6') */
    s->x_prev = x;
    s->t_prev = t;
    s->F_prev = F;
    return F;
}
''')


def c_source(model: ExportModel) -> str:
    """The C99 source for ``model`` (see the module docstring for its functions)."""
    units = {key: ascii_units(value) for key, value in model.units.items()}
    rows = constants(model, ascii=True)
    return _SOURCE.substitute(
        version=__version__, kind=model.kind,
        header="\n".join(f" * {line}".rstrip() for line in header_lines(model, ascii=True)),
        constants="\n".join(f"static const double BK_{name} = {value}; /* {comment} */"
                            for name, value, comment in rows),
        F=units["F"], v=units["v"], x=units["x"], t=units["t"])


__all__ = ["c_source"]

/*
 * Sample-by-sample geometry of a move table in C: the exact positions of samples along lines
 * and plain arcs, and their distance from the programmed contour (planner/geometry/movetable.py
 * keeps the NumPy forms as the reference they are tested against, the fallback where this
 * module is not built, and the only form for the rows this one leaves: blends, arcs in a
 * turned frame, spirals and arcs of a large radius for positions).
 *
 * Same formulas and the same operations in the same order as the NumPy code (built with
 * -ffp-contract=off: no fused multiply-add); sin, cos and atan2 are the C library's, which may
 * differ from NumPy's in the last bit.
 *
 * Arrays come through the buffer protocol (no NumPy headers: it builds with what `make`
 * installs), checked for their element type and shape; the table's columns may be strided
 * (a column that repeats one row is a broadcast view of stride 0), the outputs are contiguous.
 */
#include "../_buffers.h"
#include <math.h>

/* element k of 1-D buffer i, and element (r, c) of 2-D buffer i */
#define AT(i, T, k) (*(const T *)((const char *)b[i].view.buf + (k) * b[i].s0))
#define DV(i, k) AT(i, double, k)
#define QV(i, k) AT(i, long long, k)
#define BV(i, k) AT(i, unsigned char, k)
#define D2(i, r, c) (*(const double *)((const char *)b[i].view.buf + (r) * b[i].s0 + (c) * b[i].s1))

static double clip01(double x)
{
    /* np.clip(x, 0, 1): NaN stays NaN */
    if (x < 0.0)
        return 0.0;
    if (x > 1.0)
        return 1.0;
    return x;
}

/* contour_error(start, delta, length, is_arc, is_blend, turn, first, second, cx, cy, r0, r1,
 *               theta0, sweep, row, q, u, out) -> number of samples left (NaN in out)
 * out[i]: distance of q[i] from move row[i]'s programmed geometry, as movetable.contour_error;
 * samples of blends and of arcs in a turned frame are left NaN for the NumPy form. */
static PyObject *contour_error(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *o[18];
    if (!PyArg_ParseTuple(args, "OOOOOOOOOOOOOOOOOO", &o[0], &o[1], &o[2], &o[3], &o[4], &o[5], &o[6],
                          &o[7], &o[8], &o[9], &o[10], &o[11], &o[12], &o[13], &o[14], &o[15], &o[16],
                          &o[17]))
        return NULL;
    static const char *fmt[18] = {"d", "d", "d", "?", "?", "d", "q", "q", "d", "d", "d", "d", "d", "d",
                                  "q", "d", "d", "d"};
    static const int nd[18] = {2, 2, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 2, 1, 1};
    static const char *names[18] = {"start", "delta", "length", "is_arc", "is_blend", "turn", "first",
                                    "second", "cx", "cy", "r0", "r1", "theta0", "sweep", "row", "q", "u",
                                    "out"};
    Buf b[18];
    if (take_all(o, b, 18, fmt, nd, names, BUF_STRIDED_IN) < 0)
        return NULL;
    Py_ssize_t n_rows = b[0].view.shape[0], d = b[0].view.shape[1];
    Py_ssize_t n = b[15].view.shape[0];
    int bad = b[1].view.shape[0] != n_rows || b[1].view.shape[1] != d || b[15].view.shape[1] != d ||
              b[14].view.shape[0] != n || b[16].view.shape[0] != n || b[17].view.shape[0] != n;
    for (int i = 2; i < 14 && !bad; i++)
        bad = b[i].view.shape[0] != n_rows;
    if (bad || d > 16) {
        release_all(b, 18);
        PyErr_SetString(PyExc_ValueError, "contour_error: shapes do not agree (or more than 16 axes)");
        return NULL;
    }
    double *out = (double *)b[17].view.buf;
    Py_ssize_t left = 0;
    int out_of_range = 0;
    Py_BEGIN_ALLOW_THREADS
    for (Py_ssize_t i = 0; i < n; i++) {
        long long r = QV(14, i);
        if (r < 0 || r >= n_rows) {
            out_of_range = 1;
            break;
        }
        int arc = BV(3, r) != 0;
        if (BV(4, r) || (arc && DV(5, r) != 0.0)) {
            out[i] = NAN;
            left++;
            continue;
        }
        double qi[16], st[16], dl[16], rel[16], dot = 0.0, dd = 0.0;
        for (Py_ssize_t c = 0; c < d; c++) {
            qi[c] = D2(15, i, c);
            st[c] = D2(0, r, c);
            dl[c] = D2(1, r, c);
            rel[c] = qi[c] - st[c];
            dot += rel[c] * dl[c];
            dd += dl[c] * dl[c];
        }
        double proj = clip01(dot / dd);
        if (isnan(proj))
            proj = 0.0;
        if (!arc) {
            double e2 = 0.0;
            for (Py_ssize_t c = 0; c < d; c++) {
                double e = rel[c] - proj * dl[c];
                e2 += e * e;
            }
            out[i] = sqrt(e2);
            continue;
        }
        long long f = QV(6, r), s = QV(7, r);
        double length = DV(2, r), theta0 = DV(12, r), sw = DV(13, r), r0 = DV(10, r), r1 = DV(11, r);
        double px = qi[f] - DV(8, r), py = qi[s] - DV(9, r);
        double ang = atan2(py, px);
        double nominal = theta0 + sw * clip01(DV(16, i) / length);
        double two_pi = 2.0 * M_PI;
        double m = fmod(ang - nominal + M_PI, two_pi);   /* np.remainder: the sign of the divisor */
        if (m < 0.0)
            m += two_pi;
        ang = nominal + m - M_PI;
        double frac = clip01((ang - theta0) / sw);
        double rmax = r0 > r1 ? r0 : r1;
        if (rmax * fabs(sw) < 1e-6 * length)
            frac = proj;
        double radius = r0 + (r1 - r0) * frac;
        double o2 = 0.0;
        for (Py_ssize_t c = 0; c < d; c++) {
            if (c == f || c == s)
                continue;
            double e = qi[c] - (st[c] + frac * dl[c]);
            o2 += e * e;
        }
        double radial = hypot(px, py) - radius;
        out[i] = sqrt(radial * radial + o2);
    }
    Py_END_ALLOW_THREADS
    release_all(b, 18);
    if (out_of_range) {
        PyErr_SetString(PyExc_IndexError, "contour_error: a row is outside the table");
        return NULL;
    }
    return PyLong_FromSsize_t(left);
}

/* positions(start, delta, end, length, is_arc, is_blend, spiral, turn, first, second, cx, cy, r0,
 *           r1, theta0, sweep, far_radius, row, u, out) -> number of samples left (NaN rows)
 * out[i]: the exact position of move row[i] at path length u[i], as MoveTable.positions, on
 * lines and on plain arcs (no spiral, not turned, radius up to far_radius); the other samples'
 * rows are left NaN for the NumPy form. */
static PyObject *positions(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *o[19];
    double far_radius;
    if (!PyArg_ParseTuple(args, "OOOOOOOOOOOOOOOOdOOO", &o[0], &o[1], &o[2], &o[3], &o[4], &o[5], &o[6],
                          &o[7], &o[8], &o[9], &o[10], &o[11], &o[12], &o[13], &o[14], &o[15], &far_radius,
                          &o[16], &o[17], &o[18]))
        return NULL;
    static const char *fmt[19] = {"d", "d", "d", "d", "?", "?", "?", "d", "q", "q", "d", "d", "d", "d",
                                  "d", "d", "q", "d", "d"};
    static const int nd[19] = {2, 2, 2, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 2};
    static const char *names[19] = {"start", "delta", "end", "length", "is_arc", "is_blend", "spiral",
                                    "turn", "first", "second", "cx", "cy", "r0", "r1", "theta0", "sweep",
                                    "row", "u", "out"};
    Buf b[19];
    if (take_all(o, b, 19, fmt, nd, names, BUF_STRIDED_IN) < 0)
        return NULL;
    Py_ssize_t n_rows = b[0].view.shape[0], d = b[0].view.shape[1];
    Py_ssize_t n = b[16].view.shape[0];
    int bad = b[1].view.shape[0] != n_rows || b[1].view.shape[1] != d || b[2].view.shape[0] != n_rows ||
              b[2].view.shape[1] != d || b[17].view.shape[0] != n || b[18].view.shape[0] != n ||
              b[18].view.shape[1] != d;
    for (int i = 3; i < 16 && !bad; i++)
        bad = b[i].view.shape[0] != n_rows;
    if (bad || d > 16) {
        release_all(b, 19);
        PyErr_SetString(PyExc_ValueError, "positions: shapes do not agree (or more than 16 axes)");
        return NULL;
    }
    double *out = (double *)b[18].view.buf;
    Py_ssize_t left = 0;
    int out_of_range = 0;
    Py_BEGIN_ALLOW_THREADS
    for (Py_ssize_t i = 0; i < n; i++) {
        long long r = QV(16, i);
        double *qi = out + i * d;
        if (r < 0 || r >= n_rows) {
            out_of_range = 1;
            break;
        }
        int arc = BV(4, r) != 0;
        if (BV(5, r) || (arc && (BV(6, r) || DV(7, r) != 0.0 || DV(12, r) > far_radius))) {
            for (Py_ssize_t c = 0; c < d; c++)
                qi[c] = NAN;
            left++;
            continue;
        }
        double frac = clip01(DV(17, i) / DV(3, r));
        if (frac >= 1.0) {
            for (Py_ssize_t c = 0; c < d; c++)
                qi[c] = D2(2, r, c);
            continue;
        }
        for (Py_ssize_t c = 0; c < d; c++)
            qi[c] = D2(1, r, c) * frac + D2(0, r, c);
        if (arc) {
            double theta = DV(14, r) + DV(15, r) * frac;
            double r0 = DV(12, r);
            double rad = r0 + (DV(13, r) - r0) * frac;
            qi[QV(8, r)] = DV(10, r) + rad * cos(theta);
            qi[QV(9, r)] = DV(11, r) + rad * sin(theta);
        }
    }
    Py_END_ALLOW_THREADS
    release_all(b, 19);
    if (out_of_range) {
        PyErr_SetString(PyExc_IndexError, "positions: a row is outside the table");
        return NULL;
    }
    return PyLong_FromSsize_t(left);
}

static PyMethodDef methods[] = {
    {"contour_error", contour_error, METH_VARARGS,
     "Distance of samples from their moves' programmed geometry (lines, arcs not turned)."},
    {"positions", positions, METH_VARARGS, "Exact positions of samples on lines and plain arcs."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "planner.geometry._kernels",
                                    "A move table's sample geometry in C.", -1, methods};

PyMODINIT_FUNC PyInit__kernels(void) { return PyModule_Create(&module); }

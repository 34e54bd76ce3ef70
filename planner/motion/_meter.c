/*
 * The limit meter's stencils in C: one pass per derivative order over a chunk of samples
 * (planner/motion/meter.py keeps the NumPy form, LimitMeter._measure_numpy, as the reference
 * it is tested against and the fallback where this module is not built).
 *
 * The same doubles as NumPy: k-th differences as differences of differences (np.diff),
 * divided by the same Ts^k; maxima and ratios as the NumPy form takes them; a violation's
 * details (how many stencils, the worst ratio, its value and line: the first of equal worst
 * ratios) as Worst.update finds them.
 *
 * Arrays through the buffer protocol (planner/_buffers.h), C-contiguous, checked.
 */
#include "../_buffers.h"
#include <math.h>

#define MAX_AXES 16
#define COLS 7 /* per result row: max, count, ratio, value, line, present, ratio less noise */

/* One result row: the largest value, and the stencils over their limit (Worst.update). */
typedef struct {
    double max, count, ratio, value, line, present, ratio_less_noise;
} Row;

static void row_init(Row *r)
{
    r->max = -INFINITY;
    r->count = 0.0;
    r->ratio = -INFINITY;
    r->value = 0.0;
    r->line = 0.0;
    r->present = 0.0;
    r->ratio_less_noise = -INFINITY;
}

/* an axis' stencil (its limit is the same for all: the ratio less noise comes from the max) */
static inline void row_add(Row *r, double value, double limit, long long line, double tol, double noise)
{
    r->present = 1.0;
    if (value > r->max)
        r->max = value;
    if (value > limit * (1.0 + tol) + noise) {
        r->count += 1.0;
        double ratio = value / limit;
        if (ratio > r->ratio) {
            r->ratio = ratio;
            r->value = value;
            r->line = (double)line;
        }
    }
}

/* a tangential stencil: its limit varies (the move's feed, linear or rotary) */
static inline void row_add_path(Row *r, double value, double limit, long long line, double tol, double noise)
{
    double rn = (value - noise) / limit;
    if (rn > r->ratio_less_noise)
        r->ratio_less_noise = rn;
    row_add(r, value, limit, line, tol, noise);
}

static void row_store(const Row *r, double *out)
{
    out[0] = r->max;
    out[1] = r->count;
    out[2] = r->ratio;
    out[3] = r->value;
    out[4] = r->line;
    out[5] = r->present;
    out[6] = r->ratio_less_noise;
}

/* measure(q, s, move, line, v_limit, linear, axis_limits, path_limits, params, out) -> bool
 *
 * q (N, d), s (N), move (N, int64), line (N, int64): the samples (the kept tail first);
 * v_limit (N-1): each sample pair's path speed limit; linear (d, bool): the linear axes;
 * axis_limits (3, d): v, a, j per axis; path_limits (4): a_path, a_path_rot, j_path, j_path_rot;
 * params (12): new_from, ts, ts^2, ts^3, eps, noise v a j, tol v a j, across_joints;
 * out (3, 2 d + 1, 7): per order, the axes' rows (inside moves for jerk, every stencil
 * otherwise), the axes' joint rows (jerk only) and the tangential row.
 * Returns False (out untouched) where a sample is NaN: the NumPy form measures those. */
static PyObject *measure(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *o[10];
    if (!PyArg_ParseTuple(args, "OOOOOOOOOO", &o[0], &o[1], &o[2], &o[3], &o[4], &o[5], &o[6], &o[7], &o[8],
                          &o[9]))
        return NULL;
    static const char *fmt[10] = {"d", "d", "q", "q", "d", "?", "d", "d", "d", "d"};
    static const int nd[10] = {2, 1, 1, 1, 1, 1, 2, 1, 1, 3};
    static const char *names[10] = {"q", "s", "move", "line", "v_limit", "linear", "axis_limits",
                                    "path_limits", "params", "out"};
    Buf b[10];
    if (take_all(o, b, 10, fmt, nd, names, BUF_CONTIGUOUS_IN) < 0)
        return NULL;
    Py_ssize_t n = b[0].view.shape[0], d = b[0].view.shape[1];
    int bad = d < 1 || d > MAX_AXES || b[1].view.shape[0] != n || b[2].view.shape[0] != n ||
              b[3].view.shape[0] != n || b[4].view.shape[0] != (n > 0 ? n - 1 : 0) ||
              b[5].view.shape[0] != d || b[6].view.shape[0] != 3 || b[6].view.shape[1] != d ||
              b[7].view.shape[0] != 4 || b[8].view.shape[0] != 12 || b[9].view.shape[0] != 3 ||
              b[9].view.shape[1] != 2 * d + 1 || b[9].view.shape[2] != COLS;
    if (bad) {
        release_all(b, 10);
        PyErr_SetString(PyExc_ValueError, "measure: shapes do not agree (or more than 16 axes)");
        return NULL;
    }
    const double *q = b[0].view.buf, *s = b[1].view.buf, *vlim = b[4].view.buf, *alim = b[6].view.buf;
    const double *plim = b[7].view.buf, *par = b[8].view.buf;
    const long long *move = b[2].view.buf, *line = b[3].view.buf;
    const unsigned char *linear = b[5].view.buf;
    double *out = b[9].view.buf;
    Py_ssize_t new_from = (Py_ssize_t)par[0];
    double tsk[3] = {par[1], par[2], par[3]}, eps = par[4];
    double noise[3] = {par[5], par[6], par[7]}, tol[3] = {par[8], par[9], par[10]};
    int across = par[11] != 0.0;
    int finite = 1;
    /* per sample pair: whether a linear axis moves (a stencil over k pairs is along X Y Z when
     * one of them does, along the rotary distance else) */
    unsigned char *lin_step = PyMem_RawMalloc(n > 1 ? (size_t)(n - 1) : 1);
    if (lin_step == NULL) {
        release_all(b, 10);
        return PyErr_NoMemory();
    }
    Py_BEGIN_ALLOW_THREADS
    for (Py_ssize_t m = 0; m + 1 < n; m++) {
        unsigned char step = 0;
        for (Py_ssize_t c = 0; c < d; c++)
            step |= linear[c] && fabs(q[(m + 1) * d + c] - q[m * d + c]) > eps;
        lin_step[m] = step;
    }
    for (Py_ssize_t i = 0; i < n * d && finite; i++)
        finite = !isnan(q[i]);
    for (Py_ssize_t i = 0; i < n && finite; i++)
        finite = !isnan(s[i]);
    if (finite) {
        for (int k = 1; k <= 3; k++) {
            Row axes[MAX_AXES], joint[MAX_AXES], tan;
            for (Py_ssize_t c = 0; c < d; c++) {
                row_init(&axes[c]);
                row_init(&joint[c]);
            }
            row_init(&tan);
            Py_ssize_t lo = new_from - k > 0 ? new_from - k : 0;
            for (Py_ssize_t m = lo; m + k < n; m++) {
                /* stencil m: samples m .. m + k, attributed to the line of sample m + 1 */
                long long ln = line[m + 1];
                int inside = 1, moving = 0;
                for (int p = 0; p < k; p++) {
                    inside &= move[m + p + 1] == move[m + p];
                    moving |= lin_step[m + p];
                }
                for (Py_ssize_t c = 0; c < d; c++) {
                    const double *x = q + m * d + c;
                    double v;
                    double d1a = x[d] - x[0];
                    if (k == 1) {
                        v = d1a;
                    } else {
                        double d1b = x[2 * d] - x[d];
                        double d2a = d1b - d1a;
                        if (k == 2) {
                            v = d2a;
                        } else {
                            double d1c = x[3 * d] - x[2 * d];
                            v = (d1c - d1b) - d2a;
                        }
                    }
                    double val = fabs(v) / tsk[k - 1];
                    double lim = alim[(k - 1) * d + c];
                    if (k == 3 && !inside)
                        row_add(&joint[c], val, lim, ln, tol[k - 1], noise[k - 1]);
                    else
                        row_add(&axes[c], val, lim, ln, tol[k - 1], noise[k - 1]);
                }
                if (k == 3 || !across) {
                    if (!inside)
                        continue;
                }
                double ds;
                double s1a = s[m + 1] - s[m];
                if (k == 1) {
                    ds = s1a;
                } else {
                    double s1b = s[m + 2] - s[m + 1];
                    if (k == 2) {
                        ds = s1b - s1a;
                    } else {
                        double s1c = s[m + 3] - s[m + 2];
                        ds = (s1c - s1b) - (s1b - s1a);
                    }
                }
                double val = fabs(ds) / tsk[k - 1];
                double lim = k == 1 ? vlim[m] : (k == 2 ? (moving ? plim[0] : plim[1]) : (moving ? plim[2] : plim[3]));
                row_add_path(&tan, val, lim, ln, tol[k - 1], noise[k - 1]);
            }
            double *blk = out + (Py_ssize_t)(k - 1) * (2 * d + 1) * COLS;
            for (Py_ssize_t c = 0; c < d; c++) {
                row_store(&axes[c], blk + c * COLS);
                row_store(&joint[c], blk + (d + c) * COLS);
            }
            row_store(&tan, blk + 2 * d * COLS);
        }
    }
    Py_END_ALLOW_THREADS
    PyMem_RawFree(lin_step);
    release_all(b, 10);
    return PyBool_FromLong(finite);
}

static PyMethodDef methods[] = {
    {"measure", measure, METH_VARARGS, "The limit meter's stencils over a chunk of samples."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "planner.motion._meter",
                                    "The limit meter's stencils in C.", -1, methods, NULL, NULL, NULL, NULL};

PyMODINIT_FUNC PyInit__meter(void) { return PyModule_Create(&module); }

/*
 * The look-ahead's two sequential passes in C (planner/lookahead.py keeps the Python ones as
 * the reference they are tested against, and as the fallback where this module is not built).
 *
 * Same formulas, same operations in the same order as the Python code: reachable_speed is
 * profile.reachable_speed_scalar line for line (sqrt, asinh, sinh and pow of the C library,
 * which Python's math module calls too), so the speeds are the same doubles.
 *
 * The arrays are float64, C-contiguous, taken through the buffer protocol (no NumPy headers:
 * it builds with what `make` installs).
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>

static double reachable_speed(double v0, double length, double a_max, double j_max)
{
    if (length <= 0.0)
        return v0;
    double p = 2.0 * v0 / j_max;
    double q = length / j_max;
    double x = -1.0;
    if (p > 1e-300) {
        double arg = 1.5 * q / p * sqrt(3.0 / p);
        if (arg < 1e300)
            x = 2.0 * sqrt(p / 3.0) * sinh(asinh(arg) / 3.0);
    }
    if (x < 0.0)
        x = pow(q, 1.0 / 3.0);
    double dfdx = 3.0 * x * x + p;
    if (dfdx > 0.0)
        x -= (x * x * x + p * x - q) / dfdx;
    double dv = j_max * x * x;
    if (dv * j_max > a_max * a_max) {
        double b = 2.0 * v0 + a_max * a_max / j_max;
        double c = 2.0 * a_max * (v0 * a_max / j_max - length);
        double disc = b * b - 4.0 * c;
        dv = -2.0 * c / (b + sqrt(disc > 0.0 ? disc : 0.0));
    }
    return v0 + (dv > 0.0 ? dv : 0.0);
}

typedef struct {
    Py_buffer view;
    double *data;
    Py_ssize_t n;
} Array;

static int get_array(PyObject *obj, Array *out, int writable, const char *name)
{
    int flags = PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | (writable ? PyBUF_WRITABLE : 0);
    if (PyObject_GetBuffer(obj, &out->view, flags) < 0)
        return -1;
    if (out->view.itemsize != (Py_ssize_t)sizeof(double) || out->view.format == NULL ||
        strcmp(out->view.format, "d") != 0 || out->view.ndim != 1) {
        PyErr_Format(PyExc_TypeError, "%s must be a one-dimensional float64 array", name);
        PyBuffer_Release(&out->view);
        return -1;
    }
    out->data = (double *)out->view.buf;
    out->n = out->view.shape[0];
    return 0;
}

static void release(Array *arrays, int count)
{
    for (int i = 0; i < count; i++)
        PyBuffer_Release(&arrays[i].view);
}

/* backward_pass(v, cap, length, a_t, j_t, r0, lo): v[j] = min(cap[j], reach(v[j+1], L_j)) for
 * j = len(v)-2 .. lo+1, in place (see lookahead.backward_pass). */
static PyObject *backward_pass(PyObject *self, PyObject *args)
{
    PyObject *objs[6];
    Py_ssize_t lo;
    if (!PyArg_ParseTuple(args, "OOOOOOn", &objs[0], &objs[1], &objs[2], &objs[3], &objs[4], &objs[5], &lo))
        return NULL;
    Array a[6];
    static const char *names[6] = {"v", "cap", "length", "a_t", "j_t", "r0"};
    for (int i = 0; i < 6; i++) {
        if (get_array(objs[i], &a[i], i == 0, names[i]) < 0) {
            release(a, i);
            return NULL;
        }
    }
    Py_ssize_t n = a[0].n;
    if (a[1].n < n || a[2].n < n - 1 || a[3].n < n - 1 || a[4].n < n - 1 || a[5].n < n - 1) {
        release(a, 6);
        PyErr_SetString(PyExc_ValueError, "backward_pass: arrays shorter than v");
        return NULL;
    }
    double *v = a[0].data, *cap = a[1].data, *len = a[2].data, *at = a[3].data, *jt = a[4].data,
           *r0 = a[5].data;
    Py_BEGIN_ALLOW_THREADS
    for (Py_ssize_t j = n - 2; j > lo; j--) {
        double cj = cap[j];
        double nxt = v[j + 1];
        if (cj <= nxt || cj <= r0[j]) {
            v[j] = cj;
        } else {
            double r = reachable_speed(nxt, len[j], at[j], jt[j]);
            v[j] = cj <= r ? cj : r;
        }
    }
    Py_END_ALLOW_THREADS
    release(a, 6);
    Py_RETURN_NONE;
}

/* forward_pass(v, length, a_t, j_t, r0, lo, hi): v[j+1] = min(v[j+1], reach(v[j], L_j)) for
 * j = lo .. hi-1, in place (see lookahead.forward_pass). */
static PyObject *forward_pass(PyObject *self, PyObject *args)
{
    PyObject *objs[5];
    Py_ssize_t lo, hi;
    if (!PyArg_ParseTuple(args, "OOOOOnn", &objs[0], &objs[1], &objs[2], &objs[3], &objs[4], &lo, &hi))
        return NULL;
    Array a[5];
    static const char *names[5] = {"v", "length", "a_t", "j_t", "r0"};
    for (int i = 0; i < 5; i++) {
        if (get_array(objs[i], &a[i], i == 0, names[i]) < 0) {
            release(a, i);
            return NULL;
        }
    }
    if (lo < 0 || hi >= a[0].n || hi > a[1].n || hi > a[2].n || hi > a[3].n || hi > a[4].n) {
        release(a, 5);
        PyErr_SetString(PyExc_ValueError, "forward_pass: lo or hi outside the arrays");
        return NULL;
    }
    double *v = a[0].data, *len = a[1].data, *at = a[2].data, *jt = a[3].data, *r0 = a[4].data;
    Py_BEGIN_ALLOW_THREADS
    for (Py_ssize_t j = lo; j < hi; j++) {
        double nxt = v[j + 1];
        if (nxt <= v[j] || nxt <= r0[j])
            continue;
        double r = reachable_speed(v[j], len[j], at[j], jt[j]);
        if (r < nxt)
            v[j + 1] = r;
    }
    Py_END_ALLOW_THREADS
    release(a, 5);
    Py_RETURN_NONE;
}

static PyObject *py_reachable_speed(PyObject *self, PyObject *args)
{
    double v0, length, a_max, j_max;
    if (!PyArg_ParseTuple(args, "dddd", &v0, &length, &a_max, &j_max))
        return NULL;
    return PyFloat_FromDouble(reachable_speed(v0, length, a_max, j_max));
}

static PyMethodDef methods[] = {
    {"backward_pass", backward_pass, METH_VARARGS, "The look-ahead's backward pass, in place."},
    {"forward_pass", forward_pass, METH_VARARGS, "The look-ahead's forward pass, in place."},
    {"reachable_speed", py_reachable_speed, METH_VARARGS, "profile.reachable_speed_scalar in C."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "planner._passes",
                                    "The look-ahead's sequential passes in C.", -1, methods};

PyMODINIT_FUNC PyInit__passes(void) { return PyModule_Create(&module); }

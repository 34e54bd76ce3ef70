/*
 * Arrays taken from Python through the buffer protocol, for the planner's C modules (no NumPy
 * headers: they build with what `make` installs): element format and dimensions checked, the
 * strides kept for inputs that may be strided.
 */
#ifndef PLANNER_BUFFERS_H
#define PLANNER_BUFFERS_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <string.h>

typedef struct {
    Py_buffer view;
    int held;
    Py_ssize_t s0, s1; /* strides in bytes of the first two dimensions */
} Buf;

typedef enum {
    BUF_STRIDED_IN,    /* read, any strides (a broadcast column: stride 0) */
    BUF_CONTIGUOUS_IN, /* read, C-contiguous */
    BUF_OUT,           /* written, C-contiguous */
} BufKind;

/* Take `obj` as a buffer of element format `fmt` ("d", "q" or "?") with `ndim` dimensions;
 * -1 with a TypeError naming `name` otherwise (release_all releases what was taken). */
static int take(PyObject *obj, Buf *b, const char *fmt, int ndim, BufKind kind, const char *name)
{
    int flags = kind == BUF_OUT ? (PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | PyBUF_WRITABLE)
                : kind == BUF_CONTIGUOUS_IN ? (PyBUF_C_CONTIGUOUS | PyBUF_FORMAT)
                : (PyBUF_STRIDES | PyBUF_FORMAT);
    b->held = 0;
    if (PyObject_GetBuffer(obj, &b->view, flags) < 0)
        return -1;
    b->held = 1;
    const char *f = b->view.format ? b->view.format : "B";
    if (f[0] == '<' || f[0] == '=' || f[0] == '@')
        f++;
    int same = strcmp(f, fmt) == 0 || (fmt[0] == 'q' && strcmp(f, "l") == 0 && sizeof(long) == 8);
    if (!same || b->view.ndim != ndim) {
        PyErr_Format(PyExc_TypeError, "%s must be a %d-dimensional array of format '%s'", name, ndim, fmt);
        return -1;
    }
    b->s0 = b->view.strides[0];
    b->s1 = ndim > 1 ? b->view.strides[1] : 0;
    return 0;
}

static void release_all(Buf *bufs, int count)
{
    for (int i = 0; i < count; i++)
        if (bufs[i].held)
            PyBuffer_Release(&bufs[i].view);
}

/* Take `count` arguments: the last one the output, the others inputs of kind `in_kind`;
 * -1 with everything released when one is refused. */
static int take_all(PyObject **o, Buf *b, int count, const char **fmt, const int *nd, const char **names,
                    BufKind in_kind)
{
    memset(b, 0, sizeof(Buf) * (size_t)count);
    for (int i = 0; i < count; i++)
        if (take(o[i], &b[i], fmt[i], nd[i], i == count - 1 ? BUF_OUT : in_kind, names[i]) < 0) {
            release_all(b, count);
            return -1;
        }
    return 0;
}

#endif

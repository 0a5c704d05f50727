/* MEASUREMENT PROTOTYPE, not part of rosreconf (nothing builds or imports it).
 *
 * Issue 12 asks for 1000 x 10 read and checked in <= 1 CPU s; a Python loop over PyYAML's
 * events cannot get there (docs/PERFORMANCE.md, "What is left"). This file measures what a
 * compiled reader would give: libyaml's events turned straight into yamltree's nodes
 * (YScalar/YMapping/YSequence, called as the Python classes they are), Span positions and
 * the plain data, exactly as formats/yamlfast.py builds them. It has NONE of yamlfast's
 * declines (anchors, tags, duplicate keys, flow '?', the libyaml/PyYAML differences), no
 * depth limit beyond 64 and no error handling: it is a number, not a reader.
 *
 * Build and compare (speed2 session, 2026-11-23, on the loaded 2-core machine):
 *   PY=.venv/bin/python
 *   INC=$($PY -c "import sysconfig; print(sysconfig.get_paths()['include'])")
 *   SUF=$($PY -c "import sysconfig; print(sysconfig.get_config_var('EXT_SUFFIX'))")
 *   gcc -O2 -shared -fPIC -I$INC ctree.c -lyaml -o /tmp/ctree$SUF
 *   then ctree.setup(Span, YScalar, YMapping, YSequence, resolve_plain) and
 *   ctree.read_tree(text.encode(), file) on each generated file (rosreconf generate -r 1000
 *   -k 10 --seed 1, split as benchmarks/run.py --child split-1000x10 writes it).
 * Measured in one process, alternating, 5 rounds (in-process CPU s, all 11 files): the trees
 * and plain data equal yamlfast.fast_read's on every file; yamlfast 0.87-0.95, this
 * 0.31-0.42, of which libyaml's own parse is 0.07 and the Python YScalar constructor 0.03.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <yaml.h>

static PyObject *SpanT, *YScalarT, *YMappingT, *YSequenceT, *resolve;

static PyObject *span(PyObject *file, yaml_mark_t m) {
    PyObject *t = ((PyTypeObject *)SpanT)->tp_alloc((PyTypeObject *)SpanT, 3);
    if (!t) return NULL;
    Py_INCREF(file);
    PyTuple_SET_ITEM(t, 0, file);
    PyTuple_SET_ITEM(t, 1, PyLong_FromSize_t(m.line + 1));
    PyTuple_SET_ITEM(t, 2, PyLong_FromSize_t(m.column + 1));
    return t;
}

typedef struct { PyObject *items, *spans, *plains; PyObject *key, *kspan; } Frame;

static PyObject *read_tree(PyObject *self, PyObject *args) {
    const char *buf; Py_ssize_t len; PyObject *file;
    if (!PyArg_ParseTuple(args, "s#U", &buf, &len, &file)) return NULL;
    yaml_parser_t p; yaml_event_t ev;
    yaml_parser_initialize(&p);
    yaml_parser_set_input_string(&p, (const unsigned char *)buf, len);
    Frame stack[64]; int depth = 0;
    Frame cur = {NULL, NULL, NULL, NULL, NULL};
    PyObject *root = Py_None, *root_plain = Py_None, *resolved = PyDict_New();
    Py_INCREF(root); Py_INCREF(root_plain);
    int done = 0;
    while (!done) {
        if (!yaml_parser_parse(&p, &ev)) { PyErr_SetString(PyExc_ValueError, "yaml error"); goto fail; }
        PyObject *node = NULL, *plain = NULL; int opens = 0, ismap = 0;
        switch (ev.type) {
        case YAML_SCALAR_EVENT: {
            PyObject *value = PyUnicode_DecodeUTF8((const char *)ev.data.scalar.value, ev.data.scalar.length, NULL);
            PyObject *sp = span(file, ev.start_mark);
            if (cur.spans && !cur.key) { cur.key = value; cur.kspan = sp; yaml_event_delete(&ev); continue; }
            int isplain = ev.data.scalar.style == YAML_PLAIN_SCALAR_STYLE && ev.data.scalar.plain_implicit;
            if (isplain) {
                plain = PyDict_GetItem(resolved, value);
                if (plain) Py_INCREF(plain);
                else { plain = PyObject_CallOneArg(resolve, value); PyDict_SetItem(resolved, value, plain); }
            } else { plain = value; Py_INCREF(plain); }
            PyObject *a[4] = {sp, plain, value, isplain ? Py_True : Py_False};
            node = PyObject_Vectorcall(YScalarT, a, 4, NULL);
            Py_DECREF(sp); Py_DECREF(value);
            break; }
        case YAML_MAPPING_START_EVENT: case YAML_SEQUENCE_START_EVENT: {
            ismap = ev.type == YAML_MAPPING_START_EVENT; opens = 1;
            PyObject *sp = span(file, ev.start_mark);
            PyObject *a[1] = {sp};
            node = PyObject_Vectorcall(ismap ? YMappingT : YSequenceT, a, 1, NULL);
            Py_DECREF(sp);
            plain = ismap ? PyDict_New() : PyList_New(0);
            break; }
        case YAML_MAPPING_END_EVENT: case YAML_SEQUENCE_END_EVENT:
            cur = stack[--depth]; yaml_event_delete(&ev); continue;
        case YAML_STREAM_END_EVENT: done = 1; yaml_event_delete(&ev); continue;
        default: yaml_event_delete(&ev); continue;
        }
        yaml_event_delete(&ev);
        if (!node || !plain) goto fail;
        if (cur.spans) {
            PyDict_SetItem(cur.items, cur.key, node);
            PyDict_SetItem(cur.spans, cur.key, cur.kspan);
            PyDict_SetItem(cur.plains, cur.key, plain);
            Py_DECREF(cur.key); Py_DECREF(cur.kspan); cur.key = cur.kspan = NULL;
        } else if (cur.items) {
            PyList_Append(cur.items, node); PyList_Append(cur.plains, plain);
        } else {
            Py_DECREF(root); Py_DECREF(root_plain); root = node; root_plain = plain; Py_INCREF(node); Py_INCREF(plain);
        }
        if (opens) {
            stack[depth++] = cur;
            PyObject *items = PyObject_GetAttrString(node, "items");
            cur.items = items; Py_DECREF(items);  /* borrowed: the node holds it */
            if (ismap) { PyObject *ks = PyObject_GetAttrString(node, "key_spans"); cur.spans = ks; Py_DECREF(ks); }
            else cur.spans = NULL;
            cur.plains = plain; cur.key = cur.kspan = NULL;
        }
        Py_DECREF(node); Py_DECREF(plain);
    }
    yaml_parser_delete(&p); Py_DECREF(resolved);
    PyObject *r = PyTuple_Pack(2, root, root_plain); Py_DECREF(root); Py_DECREF(root_plain);
    return r;
fail:
    yaml_parser_delete(&p); return NULL;
}

static PyObject *setup(PyObject *self, PyObject *args) {
    if (!PyArg_ParseTuple(args, "OOOOO", &SpanT, &YScalarT, &YMappingT, &YSequenceT, &resolve)) return NULL;
    Py_INCREF(SpanT); Py_INCREF(YScalarT); Py_INCREF(YMappingT); Py_INCREF(YSequenceT); Py_INCREF(resolve);
    Py_RETURN_NONE;
}

static PyMethodDef M[] = {{"read_tree", read_tree, METH_VARARGS, ""}, {"setup", setup, METH_VARARGS, ""}, {0}};
static struct PyModuleDef D = {PyModuleDef_HEAD_INIT, "ctree", NULL, -1, M};
PyMODINIT_FUNC PyInit_ctree(void) { return PyModule_Create(&D); }

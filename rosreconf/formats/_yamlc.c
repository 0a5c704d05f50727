/* rosreconf.formats._yamlc: yamlfast's loop over libyaml's events, in C.
 *
 * Why: a 1000-role library is 380,000 libyaml events. PyYAML's C binding makes a Python
 * event object with two marks for each, and yamlfast's Python loop then reads them; that
 * costs ten times libyaml's own parse (docs/PERFORMANCE.md). This module reads libyaml's
 * events itself and builds the very same tree as ``yamlfast._events``: yamltree's YScalar,
 * YMapping and YSequence (called as the Python classes they are), Span positions made from
 * libyaml's marks exactly as PyYAML's CParser hands them over (line + 1, column + 1), and
 * the plain data, with plain scalars resolved by ``resolve_plain`` once per distinct text.
 * Equal scalar texts share one str object (a library repeats its keys and interface types
 * tens of thousands of times), found by libyaml's bytes in a table of their own (``Texts``)
 * without decoding or hashing a new str, and events on one line share their line number's
 * int: equal values, less memory, which no comparison can tell apart.
 *
 * It declines (returns None) in exactly the cases yamlfast declines: a second document, an
 * anchor, an alias, a tag, a complex key, a duplicate key, nesting deeper than max_depth, a
 * plain scalar in a flow collection that is empty or holds '?', an empty plain scalar at the
 * end of the text, a block scalar header followed by '#' (asked of the Python callable
 * ``header_comment``, which is rare), and libyaml's own errors. The caller must have checked
 * ``yamlfast.fast_path_safe(text)`` first. libyaml running out of memory raises MemoryError,
 * as PyYAML's CParser does; any Python exception raised on the way (a MemoryError, one from
 * a callable) propagates. tests/test_fast_paths.py holds it to yamlfast and to the pure
 * reader on every case.
 *
 * Given None for the four types, it builds the plain data alone (no node, no Span, no key
 * position): positions are needed only to report a problem, and a clean file has none
 * (formats/loader.py reads every file this way first, and again with positions only when
 * there is something to report). The declines are the same in both modes.
 *
 * The caller pauses the cyclic garbage collector (yamlsource.parse_plain): the tree only
 * grows here.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <string.h>
#include <yaml.h>

/* What one open collection is filling; all references owned. Without positions (plain
 * only) items, spans and key_span stay NULL. */
typedef struct {
    int mapping;      /* a mapping (1) or a sequence (0) */
    PyObject *items;  /* a mapping's dict of nodes, or a sequence's list of nodes */
    PyObject *spans;  /* a mapping's dict of key positions; NULL for a sequence */
    PyObject *plains; /* the plain dict or list */
    PyObject *key;    /* a mapping's key read and waiting for its value, or NULL */
    PyObject *key_span;
} Frame;

/* One distinct scalar text: its str object and, once asked for, its resolved value as a
 * plain scalar (both owned). */
typedef struct {
    size_t hash;        /* Python's hash of the UTF-8 bytes, made odd; 0 = an empty slot */
    PyObject *text;     /* the str */
    const char *utf8;   /* its UTF-8 bytes, held by text (PyUnicode_AsUTF8AndSize) */
    Py_ssize_t size;    /* their number */
    PyObject *resolved; /* resolve_plain(text), or NULL until first asked */
} Text;

/* The distinct scalar texts read so far, by their UTF-8 bytes (open addressing): a repeated
 * text (most are: keys, interface types, layer names) is found from libyaml's bytes without
 * decoding them, making a str or hashing it, and its resolved value with it. */
typedef struct {
    Text *slots;
    size_t mask; /* slots - 1, a power of two minus one */
    size_t used;
} Texts;

/* The callables and types the tree is made of, borrowed from the caller's arguments. */
typedef struct {
    int positions; /* build the positioned tree (1) or the plain data only (0) */
    PyObject *text;
    PyObject *file;
    PyObject *span_type;
    PyObject *scalar_type;
    PyObject *mapping_type;
    PyObject *sequence_type;
    PyObject *resolve_plain;
    PyObject *header_comment;
    Py_ssize_t end;       /* len(text), in characters as libyaml's mark.index counts */
    Py_ssize_t max_depth; /* most collections open at once */
    /* State of the loop. */
    Texts texts;        /* scalar text -> the one str object of that text, and its value */
    PyObject *line;     /* the int line + 1 of the last Span made, or NULL */
    size_t line_index;  /* its libyaml line */
    PyObject *root;
    PyObject *root_plain;
    Frame *stack; /* the enclosing collections, innermost last: max_depth frames */
    Py_ssize_t depth;
    Frame cur; /* the open collection (all NULL at the top level) */
    Py_ssize_t flow;
    int documents;
} Reader;

enum { GO_ON = 0, DONE = 1, FAILED = -1, DECLINE = -2 };

static void
frame_clear(Frame *f)
{
    Py_CLEAR(f->items);
    Py_CLEAR(f->spans);
    Py_CLEAR(f->plains);
    Py_CLEAR(f->key);
    Py_CLEAR(f->key_span);
}

/* Return a new Span(file, line + 1, column + 1): a tuple of Span's type, built as
 * tuple.__new__(Span, ...) builds it. */
static PyObject *
new_span(Reader *r, yaml_mark_t mark)
{
    if (r->line == NULL || r->line_index != mark.line) {
        PyObject *number = PyLong_FromSize_t(mark.line + 1);
        if (number == NULL) {
            return NULL;
        }
        Py_XSETREF(r->line, number);
        r->line_index = mark.line;
    }
    PyObject *line = Py_NewRef(r->line);
    PyObject *column = PyLong_FromSize_t(mark.column + 1);
    if (column == NULL) {
        Py_DECREF(line);
        return NULL;
    }
    PyTypeObject *type = (PyTypeObject *)r->span_type;
    PyObject *span = type->tp_alloc(type, 3);
    if (span == NULL) {
        Py_DECREF(line);
        Py_DECREF(column);
        return NULL;
    }
    Py_INCREF(r->file);
    PyTuple_SET_ITEM(span, 0, r->file);
    PyTuple_SET_ITEM(span, 1, line);
    PyTuple_SET_ITEM(span, 2, column);
    return span;
}

/* Put a finished node and its plain value where the open collection wants it (borrowed;
 * node is NULL without positions). */
static int
attach(Reader *r, PyObject *node, PyObject *plain)
{
    Frame *c = &r->cur;
    if (c->mapping) { /* a value in a mapping */
        if (c->key == NULL) {
            return DECLINE; /* never: a collection as a key is declined where it opens */
        }
        /* one lookup: a key already there leaves the size as it was (and the whole read
         * is declined, so what it replaced does not matter) */
        Py_ssize_t before = PyDict_GET_SIZE(c->plains);
        if (PyDict_SetItem(c->plains, c->key, plain) < 0) {
            return FAILED;
        }
        if (PyDict_GET_SIZE(c->plains) == before) {
            return DECLINE; /* a duplicate key */
        }
        if (r->positions && (PyDict_SetItem(c->items, c->key, node) < 0 ||
                             PyDict_SetItem(c->spans, c->key, c->key_span) < 0)) {
            return FAILED;
        }
        Py_CLEAR(c->key);
        Py_CLEAR(c->key_span);
    }
    else if (c->plains != NULL) { /* an item in a sequence */
        if (r->positions && PyList_Append(c->items, node) < 0) {
            return FAILED;
        }
        if (PyList_Append(c->plains, plain) < 0) {
            return FAILED;
        }
    }
    else { /* the document's root */
        Py_XINCREF(node);
        Py_XSETREF(r->root, node);
        Py_INCREF(plain);
        Py_XSETREF(r->root_plain, plain);
    }
    return GO_ON;
}

static void
texts_clear(Texts *t)
{
    if (t->slots != NULL) {
        for (size_t i = 0; i <= t->mask; i++) {
            Py_XDECREF(t->slots[i].text);
            Py_XDECREF(t->slots[i].resolved);
        }
        PyMem_Free(t->slots);
    }
    memset(t, 0, sizeof(*t));
}

/* Double the table (or make its first 1024 slots); 0 on success. */
static int
texts_grow(Texts *t)
{
    size_t size = t->slots == NULL ? 1024 : 2 * (t->mask + 1);
    Text *slots = PyMem_Calloc(size, sizeof(Text));
    if (slots == NULL) {
        PyErr_NoMemory();
        return -1;
    }
    if (t->slots != NULL) {
        for (size_t i = 0; i <= t->mask; i++) {
            Text *old = &t->slots[i];
            if (old->hash != 0) {
                size_t j = old->hash & (size - 1);
                while (slots[j].hash != 0) {
                    j = (j + 1) & (size - 1);
                }
                slots[j] = *old;
            }
        }
        PyMem_Free(t->slots);
    }
    t->slots = slots;
    t->mask = size - 1;
    return 0;
}

/* Return the entry of the scalar text ``bytes`` (borrowed), made on first sight; NULL with
 * an exception set on failure (not UTF-8, out of memory). */
static Text *
text_of(Texts *t, const char *bytes, size_t size)
{
    /* Python's own (keyed, randomised) hash of bytes: a file cannot be written to make many
     * texts collide and the table's probes quadratic, as with a fixed hash it could. */
#if PY_VERSION_HEX >= 0x030E0000
    size_t hash = (size_t)Py_HashBuffer(bytes, (Py_ssize_t)size);
#else
    size_t hash = (size_t)_Py_HashBytes(bytes, (Py_ssize_t)size);
#endif
    hash |= 1; /* never 0, the mark of an empty slot */
    if (t->slots == NULL && texts_grow(t) < 0) {
        return NULL;
    }
    size_t i = hash & t->mask;
    for (;;) {
        Text *e = &t->slots[i];
        if (e->hash == 0) {
            break;
        }
        if (e->hash == hash && (size_t)e->size == size && memcmp(e->utf8, bytes, size) == 0) {
            return e;
        }
        i = (i + 1) & t->mask;
    }
    PyObject *text = PyUnicode_DecodeUTF8(bytes, (Py_ssize_t)size, "strict");
    if (text == NULL) {
        return NULL;
    }
    Py_ssize_t utf8_size;
    const char *utf8 = PyUnicode_AsUTF8AndSize(text, &utf8_size);
    if (utf8 == NULL) {
        Py_DECREF(text);
        return NULL;
    }
    if (2 * (t->used + 1) > t->mask + 1) { /* keep at most half the slots used */
        if (texts_grow(t) < 0) {
            Py_DECREF(text);
            return NULL;
        }
        i = hash & t->mask;
        while (t->slots[i].hash != 0) {
            i = (i + 1) & t->mask;
        }
    }
    Text *e = &t->slots[i];
    e->hash = hash;
    e->text = text;
    e->utf8 = utf8;
    e->size = utf8_size;
    e->resolved = NULL;
    t->used++;
    return e;
}

/* Return the resolved value of a plain scalar's text (new reference), once per text. */
static PyObject *
resolve(Reader *r, Text *e)
{
    if (e->resolved == NULL) {
        e->resolved = PyObject_CallOneArg(r->resolve_plain, e->text);
        if (e->resolved == NULL) {
            return NULL;
        }
    }
    return Py_NewRef(e->resolved);
}

static int
on_scalar(Reader *r, yaml_event_t *event)
{
    if (event->data.scalar.anchor != NULL || event->data.scalar.tag != NULL) {
        return DECLINE;
    }
    yaml_mark_t mark = event->start_mark;
    const char *text = (const char *)event->data.scalar.value;
    size_t length = event->data.scalar.length;
    yaml_scalar_style_t style = event->data.scalar.style;
    /* PyYAML's style "" (plain) or None (any): yamlfast's `not style` */
    int plain_style = style == YAML_PLAIN_SCALAR_STYLE || style == YAML_ANY_SCALAR_STYLE;
    if (plain_style) {
        if (r->flow && (length == 0 || memchr(text, '?', length) != NULL)) {
            return DECLINE;
        }
        if (length == 0 && mark.index >= (size_t)r->end) {
            return DECLINE;
        }
    }
    else if (style == YAML_LITERAL_SCALAR_STYLE || style == YAML_FOLDED_SCALAR_STYLE) {
        PyObject *at = PyLong_FromSize_t(mark.index);
        if (at == NULL) {
            return FAILED;
        }
        PyObject *found = PyObject_CallFunctionObjArgs(r->header_comment, r->text, at, NULL);
        Py_DECREF(at);
        if (found == NULL) {
            return FAILED;
        }
        int comment = PyObject_IsTrue(found);
        Py_DECREF(found);
        if (comment < 0) {
            return FAILED;
        }
        if (comment) {
            return DECLINE;
        }
    }
    Text *entry = text_of(&r->texts, text, length);
    if (entry == NULL) {
        return FAILED;
    }
    PyObject *value = Py_NewRef(entry->text);
    PyObject *span = NULL;
    if (r->positions) {
        span = new_span(r, mark);
        if (span == NULL) {
            Py_DECREF(value);
            return FAILED;
        }
    }
    Frame *c = &r->cur;
    if (c->mapping && c->key == NULL) { /* a mapping's key: its text, as written */
        c->key = value;
        c->key_span = span;
        return GO_ON;
    }
    int resolved = plain_style && event->data.scalar.plain_implicit;
    PyObject *plain;
    if (resolved) {
        plain = resolve(r, entry);
        if (plain == NULL) {
            Py_XDECREF(span);
            Py_DECREF(value);
            return FAILED;
        }
    }
    else {
        Py_INCREF(value);
        plain = value;
    }
    PyObject *node = NULL;
    if (r->positions) {
        PyObject *args[4] = {span, plain, value, resolved ? Py_True : Py_False};
        node = PyObject_Vectorcall(r->scalar_type, args, 4, NULL);
        Py_DECREF(span);
        if (node == NULL) {
            Py_DECREF(value);
            Py_DECREF(plain);
            return FAILED;
        }
    }
    Py_DECREF(value);
    int status = attach(r, node, plain);
    Py_XDECREF(node);
    Py_DECREF(plain);
    return status;
}

static int
on_collection_start(Reader *r, yaml_event_t *event)
{
    int mapping = event->type == YAML_MAPPING_START_EVENT;
    int flow_style;
    if (mapping) {
        if (event->data.mapping_start.anchor != NULL || event->data.mapping_start.tag != NULL) {
            return DECLINE;
        }
        flow_style = event->data.mapping_start.style == YAML_FLOW_MAPPING_STYLE;
    }
    else {
        if (event->data.sequence_start.anchor != NULL ||
            event->data.sequence_start.tag != NULL) {
            return DECLINE;
        }
        flow_style = event->data.sequence_start.style == YAML_FLOW_SEQUENCE_STYLE;
    }
    if (r->depth >= r->max_depth) {
        return DECLINE;
    }
    if (r->cur.mapping && r->cur.key == NULL) {
        return DECLINE; /* a complex key */
    }
    if (r->flow || flow_style) {
        r->flow++;
    }
    Frame open = {mapping, NULL, NULL, NULL, NULL, NULL};
    PyObject *node = NULL;
    open.plains = mapping ? PyDict_New() : PyList_New(0);
    if (open.plains == NULL) {
        return FAILED;
    }
    if (r->positions) {
        PyObject *span = new_span(r, event->start_mark);
        if (span == NULL) {
            frame_clear(&open);
            return FAILED;
        }
        if (mapping) {
            open.items = PyDict_New();
            open.spans = PyDict_New();
            if (open.items != NULL && open.spans != NULL) {
                PyObject *args[3] = {span, open.items, open.spans};
                node = PyObject_Vectorcall(r->mapping_type, args, 3, NULL);
            }
        }
        else {
            open.items = PyList_New(0);
            if (open.items != NULL) {
                PyObject *args[2] = {span, open.items};
                node = PyObject_Vectorcall(r->sequence_type, args, 2, NULL);
            }
        }
        Py_DECREF(span);
        if (node == NULL) {
            frame_clear(&open);
            return FAILED;
        }
    }
    int status = attach(r, node, open.plains);
    Py_XDECREF(node);
    if (status != GO_ON) {
        frame_clear(&open);
        return status;
    }
    /* its children come next */
    r->stack[r->depth++] = r->cur;
    r->cur = open;
    return GO_ON;
}

static int
on_event(Reader *r, yaml_event_t *event)
{
    switch (event->type) {
    case YAML_SCALAR_EVENT:
        return on_scalar(r, event);
    case YAML_MAPPING_START_EVENT:
    case YAML_SEQUENCE_START_EVENT:
        return on_collection_start(r, event);
    case YAML_MAPPING_END_EVENT:
    case YAML_SEQUENCE_END_EVENT:
        if (r->depth == 0) {
            return DECLINE; /* libyaml never ends what it did not start */
        }
        frame_clear(&r->cur);
        r->cur = r->stack[--r->depth];
        memset(&r->stack[r->depth], 0, sizeof(Frame));
        if (r->flow) {
            r->flow--;
        }
        return GO_ON;
    case YAML_DOCUMENT_START_EVENT:
        r->documents++;
        return r->documents > 1 ? DECLINE : GO_ON;
    case YAML_STREAM_END_EVENT:
        return DONE;
    case YAML_ALIAS_EVENT:
        return DECLINE;
    default:
        return GO_ON; /* stream start and document end */
    }
}

/* Run libyaml over the UTF-8 text; leave the tree in r. */
static int
run(Reader *r, const char *data, Py_ssize_t size)
{
    yaml_parser_t parser;
    if (!yaml_parser_initialize(&parser)) {
        PyErr_NoMemory();
        return FAILED;
    }
    yaml_parser_set_input_string(&parser, (const unsigned char *)data, (size_t)size);
    int status = GO_ON;
    while (status == GO_ON) {
        yaml_event_t event;
        if (!yaml_parser_parse(&parser, &event)) {
            if (parser.error == YAML_MEMORY_ERROR) {
                PyErr_NoMemory();
                status = FAILED;
            }
            else {
                status = DECLINE; /* a syntax error: the pure reader gives the message */
            }
            break;
        }
        status = on_event(r, &event);
        yaml_event_delete(&event);
    }
    yaml_parser_delete(&parser);
    return status;
}

PyDoc_STRVAR(read_doc,
             "read(text, file, max_depth, span, scalar, mapping, sequence, resolve_plain, "
             "header_comment, /)\n--\n\n"
             "Return (tree, plain data) for text, or None where yamlfast declines.\n\n"
             "text must have passed yamlfast.fast_path_safe. span, scalar, mapping and\n"
             "sequence are yamltree's Span, YScalar, YMapping and YSequence, or all None\n"
             "for the plain data alone (then the tree is None: no node, no position is\n"
             "made); resolve_plain resolves a plain scalar's text; header_comment(text,\n"
             "index) tells whether a block scalar's header at index is followed by '#'.");

static PyObject *
read_tree(PyObject *module, PyObject *const *args, Py_ssize_t nargs)
{
    (void)module;
    if (nargs != 9) {
        PyErr_Format(PyExc_TypeError, "read() takes 9 positional arguments (%zd given)", nargs);
        return NULL;
    }
    Reader r;
    memset(&r, 0, sizeof(r));
    r.text = args[0];
    r.file = args[1];
    r.span_type = args[3];
    r.scalar_type = args[4];
    r.mapping_type = args[5];
    r.sequence_type = args[6];
    r.resolve_plain = args[7];
    r.header_comment = args[8];
    if (!PyUnicode_Check(r.text) || !PyUnicode_Check(r.file)) {
        PyErr_SetString(PyExc_TypeError, "read(): text and file must be str");
        return NULL;
    }
    int nones = (r.span_type == Py_None) + (r.scalar_type == Py_None) +
                (r.mapping_type == Py_None) + (r.sequence_type == Py_None);
    if (nones != 0 && nones != 4) {
        PyErr_SetString(PyExc_TypeError,
                        "read(): span, scalar, mapping and sequence must be all given or all None");
        return NULL;
    }
    r.positions = nones == 0;
    if (r.positions && (!PyType_Check(r.span_type) ||
                        !PyType_IsSubtype((PyTypeObject *)r.span_type, &PyTuple_Type))) {
        PyErr_SetString(PyExc_TypeError, "read(): span must be a tuple type");
        return NULL;
    }
    r.max_depth = PyLong_AsSsize_t(args[2]);
    if (r.max_depth == -1 && PyErr_Occurred()) {
        return NULL;
    }
    if (r.max_depth < 0) {
        PyErr_SetString(PyExc_ValueError, "read(): max_depth must be >= 0");
        return NULL;
    }
    r.end = PyUnicode_GetLength(r.text);
    if (r.end < 0) {
        return NULL;
    }
    PyObject *encoded = PyUnicode_AsUTF8String(r.text);
    if (encoded == NULL) {
        return NULL;
    }
    PyObject *result = NULL;
    r.stack = PyMem_Calloc(r.max_depth > 0 ? (size_t)r.max_depth : 1, sizeof(Frame));
    if (r.stack == NULL) {
        PyErr_NoMemory();
    }
    else {
        int status = run(&r, PyBytes_AS_STRING(encoded), PyBytes_GET_SIZE(encoded));
        if (status == DONE) {
            result = PyTuple_Pack(2, r.root != NULL ? r.root : Py_None,
                                  r.root_plain != NULL ? r.root_plain : Py_None);
        }
        else if (status == DECLINE) {
            result = Py_NewRef(Py_None);
        }
    }
    if (r.stack != NULL) {
        for (Py_ssize_t i = 0; i < r.depth; i++) {
            frame_clear(&r.stack[i]);
        }
        PyMem_Free(r.stack);
    }
    frame_clear(&r.cur);
    Py_XDECREF(r.root);
    Py_XDECREF(r.root_plain);
    texts_clear(&r.texts);
    Py_XDECREF(r.line);
    Py_DECREF(encoded);
    return result;
}

static PyMethodDef methods[] = {
    {"read", (PyCFunction)(void (*)(void))read_tree, METH_FASTCALL, read_doc},
    {NULL, NULL, 0, NULL},
};

PyDoc_STRVAR(module_doc,
             "yamlfast's loop over libyaml's events, in C (rosreconf/formats/yamlfast.py).");

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "rosreconf.formats._yamlc", module_doc, 0, methods,
    NULL,                  NULL,                       NULL,       NULL,
};

PyMODINIT_FUNC
PyInit__yamlc(void)
{
    return PyModuleDef_Init(&module);
}

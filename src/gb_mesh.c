/* gb_mesh — OFF, OBJ and STL read strictly (see gb_mesh.h). */
#include "gb_mesh.h"

#include "gb_error.h"
#include "gb_file.h"
#include "gb_parse.h"

#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* words a line: a face of up to 1024 vertices (a 64-gon coin's face, and more); the words live on the heap */
#define MAX_TOKENS 1025
#define MAX_TOKEN 128

/* ---------------------------------------------------------------- the mesh being built */

typedef struct builder {
    const char *name;
    gb_mesh *mesh;
    size_t vertex_cap, triangle_cap;
} builder;

static int add_vertex(builder *b, const double x[3], size_t line)
{
    gb_mesh *m = b->mesh;
    for (int k = 0; k < 3; k++)
        if (!isfinite(x[k])) return gb_error_set(GB_EDOM, "%s:%zu: a vertex coordinate is not finite (allowed: finite numbers)", b->name, line);
    if (m->vertex_count == GB_MESH_MAX_VERTICES)
        return gb_error_set(GB_EDOM, "%s:%zu: more than %d vertices (allowed: at most %d)", b->name, line, GB_MESH_MAX_VERTICES,
                            GB_MESH_MAX_VERTICES);
    if (m->vertex_count == b->vertex_cap) {
        const size_t cap = 2 * b->vertex_cap + 64;
        double *v = realloc(m->vertices, 3 * cap * sizeof *v);
        if (v) m->vertices = v;
        size_t *l = realloc(m->vertex_line, cap * sizeof *l);
        if (l) m->vertex_line = l;
        if (!v || !l) return gb_error_set(GB_ENOMEM, "%s: out of memory for the mesh's vertices", b->name);
        b->vertex_cap = cap;
    }
    memcpy(m->vertices + 3 * m->vertex_count, x, 3 * sizeof *x);
    m->vertex_line[m->vertex_count++] = line;
    return GB_OK;
}

static int add_triangle(builder *b, size_t i, size_t j, size_t k, size_t line)
{
    gb_mesh *m = b->mesh;
    if (i == j || j == k || i == k)
        return gb_error_set(GB_EINVAL, "%s:%zu: a face names one vertex twice (allowed: distinct vertices)", b->name, line);
    if (m->triangle_count == b->triangle_cap) {
        const size_t cap = 2 * b->triangle_cap + 64;
        size_t *t = realloc(m->triangles, 3 * cap * sizeof *t);
        if (!t) return gb_error_set(GB_ENOMEM, "%s: out of memory for the mesh's faces", b->name);
        m->triangles = t, b->triangle_cap = cap;
    }
    size_t *t = m->triangles + 3 * m->triangle_count++;
    t[0] = i, t[1] = j, t[2] = k;
    return GB_OK;
}

/* ---------------------------------------------------------------- lines and tokens */

typedef struct cursor {
    const unsigned char *data;
    size_t size, at, line;
} cursor;

/* The next line's tokens (white space separated; a '#' starts a comment); 0 at the end of the data. */
static int next_line(const builder *b, cursor *c, char (*tokens)[MAX_TOKEN], int *count, int *status)
{
    *count = 0;
    if (c->at >= c->size) return 0;
    c->line++;
    size_t end = c->at;
    while (end < c->size && c->data[end] != '\n') end++;
    size_t p = c->at;
    int comment = 0;
    while (p < end && !*status) {
        const unsigned char ch = c->data[p];
        if (ch == '#') comment = 1;
        if (comment) {
            p++;
            continue;
        }
        if (ch == ' ' || ch == '\t' || ch == '\r' || ch == '\f' || ch == '\v') {
            p++;
            continue;
        }
        if (ch == '\0' || ch >= 0x80 || !isprint(ch)) {
            *status = gb_error_set(GB_EINVAL, "%s:%zu: a byte that is not printable ASCII (0x%02x) (allowed: a text mesh)", b->name,
                                   c->line, ch);
            break;
        }
        size_t q = p;
        while (q < end && !isspace(c->data[q]) && c->data[q] != '#') q++;
        for (size_t k = p; k < q; k++) /* every byte of the word, not its first alone: '1<NUL>5' is no number */
            if (c->data[k] == '\0' || c->data[k] >= 0x80 || !isprint(c->data[k])) {
                *status = gb_error_set(GB_EINVAL, "%s:%zu: a byte that is not printable ASCII (0x%02x) at column %zu (allowed: a "
                                       "text mesh)", b->name, c->line, c->data[k], k - c->at + 1);
                break;
            }
        if (*status) break;
        if (*count == MAX_TOKENS || q - p >= MAX_TOKEN) {
            *status = gb_error_set(GB_EINVAL, "%s:%zu: a line of more than %d words or a word of more than %d characters", b->name,
                                   c->line, MAX_TOKENS, MAX_TOKEN - 1);
            break;
        }
        memcpy(tokens[*count], c->data + p, q - p);
        tokens[(*count)++][q - p] = '\0';
        p = q;
    }
    c->at = end < c->size ? end + 1 : end;
    return 1;
}

static int read_number(const builder *b, size_t line, const char *token, const char *what, double *out)
{
    const gb_parse_result r = gb_parse_double(token, out);
    if (r != GB_PARSE_OK)
        return gb_error_set(GB_EINVAL, "%s:%zu: %s '%s' is %s (allowed: a decimal number)", b->name, line, what, token,
                            gb_parse_describe(r, "a number"));
    return GB_OK;
}

static int read_point(const builder *b, size_t line, char (*tokens)[MAX_TOKEN], double x[3])
{
    int status = GB_OK;
    for (int k = 0; k < 3 && !status; k++) status = read_number(b, line, tokens[k], "a coordinate", &x[k]);
    return status;
}

/* ---------------------------------------------------------------- OFF */

static int read_off(builder *b, cursor *c, char (*tokens)[MAX_TOKEN])
{
    int n = 0, status = GB_OK;
    while (next_line(b, c, tokens, &n, &status) && !status && n == 0) {}
    if (status) return status;
    if (n < 1 || strcmp(tokens[0], "OFF"))
        return gb_error_set(GB_EINVAL, "%s:%zu: the first line is not 'OFF' (allowed: an OFF file starts with the word OFF)", b->name,
                            c->line);
    int t0 = 1;
    if (n == 1) {
        while (next_line(b, c, tokens, &n, &status) && !status && n == 0) {}
        if (status) return status;
        t0 = 0;
    }
    unsigned long long counts[3];
    if (n - t0 != 3)
        return gb_error_set(GB_EINVAL, "%s:%zu: the counts line needs three counts, vertices faces edges (allowed: three counts)",
                            b->name, c->line);
    for (int k = 0; k < 3; k++)
        if (gb_parse_count(tokens[t0 + k], GB_MESH_MAX_VERTICES * 4ULL, &counts[k]) != GB_PARSE_OK)
            return gb_error_set(GB_EINVAL, "%s:%zu: the count '%s' is not a count up to %llu", b->name, c->line, tokens[t0 + k],
                                GB_MESH_MAX_VERTICES * 4ULL);
    if (counts[0] > GB_MESH_MAX_VERTICES)
        return gb_error_set(GB_EDOM, "%s:%zu: %llu vertices (allowed: at most %d)", b->name, c->line, counts[0], GB_MESH_MAX_VERTICES);
    for (unsigned long long v = 0; v < counts[0] && !status; v++) {
        while (next_line(b, c, tokens, &n, &status) && !status && n == 0) {}
        if (status) break;
        if (n != 3)
            return gb_error_set(GB_EINVAL, "%s:%zu: a vertex line needs three coordinates (found %d words%s)", b->name, c->line, n,
                                c->at >= c->size && n == 0 ? ": the file ends early" : "");
        double x[3];
        status = read_point(b, c->line, tokens, x);
        if (!status) status = add_vertex(b, x, c->line);
    }
    for (unsigned long long f = 0; f < counts[1] && !status; f++) {
        while (next_line(b, c, tokens, &n, &status) && !status && n == 0) {}
        if (status) break;
        unsigned long long m;
        if (n < 1 || gb_parse_count(tokens[0], MAX_TOKENS - 1, &m) != GB_PARSE_OK || m < 3 || (int)m + 1 > n)
            return gb_error_set(GB_EINVAL, "%s:%zu: a face line is a count of at least 3 and that many vertex indices", b->name, c->line);
        size_t index[MAX_TOKENS];
        for (unsigned long long k = 0; k < m; k++) {
            unsigned long long i;
            if (gb_parse_count(tokens[1 + k], b->mesh->vertex_count ? b->mesh->vertex_count - 1 : 0, &i) != GB_PARSE_OK ||
                !b->mesh->vertex_count)
                return gb_error_set(GB_EDOM, "%s:%zu: the vertex index '%s' (allowed: 0 to %zu)", b->name, c->line, tokens[1 + k],
                                    b->mesh->vertex_count ? b->mesh->vertex_count - 1 : 0);
            index[k] = (size_t)i;
        }
        /* extra words after the indices: an OFF face may carry a colour */
        for (unsigned long long k = 1; k + 1 < m && !status; k++) status = add_triangle(b, index[0], index[k], index[k + 1], c->line);
    }
    if (status) return status;
    while (next_line(b, c, tokens, &n, &status) && !status)
        if (n) return gb_error_set(GB_EINVAL, "%s:%zu: words after the last face (allowed: the counted vertices and faces)", b->name, c->line);
    return status;
}

/* ---------------------------------------------------------------- OBJ */

/* An OBJ vertex reference "i", "i/t", "i//n" or "i/t/n": i from 1, or negative (from the end). */
static int obj_index(const builder *b, size_t line, const char *token, size_t *out)
{
    char head[MAX_TOKEN];
    size_t k = 0;
    while (token[k] && token[k] != '/') head[k] = token[k], k++;
    head[k] = '\0';
    const int negative = head[0] == '-';
    unsigned long long i;
    const size_t have = b->mesh->vertex_count;
    if (gb_parse_count(head + negative, GB_MESH_MAX_VERTICES, &i) != GB_PARSE_OK || i == 0 || i > have)
        return gb_error_set(GB_EDOM, "%s:%zu: the vertex reference '%s' (allowed: 1 to %zu, or -1 to -%zu, among the vertices "
                            "read so far)", b->name, line, token, have, have);
    *out = negative ? have - (size_t)i : (size_t)i - 1;
    return GB_OK;
}

static int read_obj(builder *b, cursor *c, char (*tokens)[MAX_TOKEN])
{
    static const char *const ignored[] = {"o", "g", "s", "usemtl", "mtllib", "vt", "vn", NULL};
    int n = 0, status = GB_OK;
    while (!status && next_line(b, c, tokens, &n, &status)) {
        if (status || n == 0) continue;
        if (!strcmp(tokens[0], "v")) {
            if (n != 4 && n != 5) /* a fourth number is the weight w, which must be 1 */
                return gb_error_set(GB_EINVAL, "%s:%zu: a 'v' line needs three coordinates (found %d)", b->name, c->line, n - 1);
            double x[3], w = 1.0;
            status = read_point(b, c->line, tokens + 1, x);
            if (!status && n == 5) status = read_number(b, c->line, tokens[4], "the weight", &w);
            if (!status && w != 1.0)
                return gb_error_set(GB_EDOM, "%s:%zu: the weight %s (allowed: 1, a point in space)", b->name, c->line, tokens[4]);
            if (!status) status = add_vertex(b, x, c->line);
        } else if (!strcmp(tokens[0], "f")) {
            if (n < 4) return gb_error_set(GB_EINVAL, "%s:%zu: an 'f' line needs at least three vertices (found %d)", b->name, c->line, n - 1);
            size_t index[MAX_TOKENS];
            for (int k = 1; k < n && !status; k++) status = obj_index(b, c->line, tokens[k], &index[k - 1]);
            for (int k = 1; k + 1 < n - 1 && !status; k++) status = add_triangle(b, index[0], index[k], index[k + 1], c->line);
        } else {
            int known = 0;
            for (int k = 0; ignored[k]; k++) known |= !strcmp(tokens[0], ignored[k]);
            if (!known)
                return gb_error_set(GB_EINVAL, "%s:%zu: the statement '%s' (allowed: v, f, and o, g, s, usemtl, mtllib, vt, vn, which "
                                    "are ignored)", b->name, c->line, tokens[0]);
        }
    }
    return status;
}

/* ---------------------------------------------------------------- STL */

/* STL repeats a vertex per triangle: positions equal bit for bit are one vertex (a hash of the bits). */
typedef struct vertex_table {
    size_t cap;
    size_t *slot; /* index + 1, 0 empty */
} vertex_table;

static uint64_t bits_hash(const double x[3])
{
    uint64_t h = 1469598103934665603ULL;
    const unsigned char *p = (const unsigned char *)x;
    for (size_t k = 0; k < 3 * sizeof(double); k++) h = (h ^ p[k]) * 1099511628211ULL;
    return h;
}

static int stl_vertex(builder *b, vertex_table *t, const double x[3], size_t line, size_t *out)
{
    double key[3];
    for (int k = 0; k < 3; k++) key[k] = x[k] == 0.0 ? 0.0 : x[k]; /* -0 and +0 are one point */
    if (4 * (b->mesh->vertex_count + 1) > 3 * t->cap) { /* grow and rehash at 3/4 full */
        const size_t cap = t->cap ? 2 * t->cap : 1024;
        size_t *slot = calloc(cap, sizeof *slot);
        if (!slot) return gb_error_set(GB_ENOMEM, "%s: out of memory for the mesh's vertices", b->name);
        for (size_t v = 0; v < b->mesh->vertex_count; v++) {
            size_t h = bits_hash(b->mesh->vertices + 3 * v) & (cap - 1);
            while (slot[h]) h = (h + 1) & (cap - 1);
            slot[h] = v + 1;
        }
        free(t->slot);
        t->slot = slot, t->cap = cap;
    }
    size_t h = bits_hash(key) & (t->cap - 1);
    while (t->slot[h]) {
        if (!memcmp(b->mesh->vertices + 3 * (t->slot[h] - 1), key, sizeof key)) {
            *out = t->slot[h] - 1;
            return GB_OK;
        }
        h = (h + 1) & (t->cap - 1);
    }
    const int status = add_vertex(b, key, line);
    if (!status) t->slot[h] = b->mesh->vertex_count, *out = b->mesh->vertex_count - 1;
    return status;
}

static int read_stl_ascii(builder *b, cursor *c, char (*tokens)[MAX_TOKEN])
{
    int n = 0, status = GB_OK, stage = 0, corners = 0; /* stage: 0 solid, 1 facet, 2 loop, 3 endloop, 4 endfacet */
    size_t index[3];
    vertex_table table = {0, NULL};
    int ended = 0;
    while (!status && next_line(b, c, tokens, &n, &status)) {
        if (status || n == 0) continue;
        const char *w = tokens[0];
        if (ended) status = gb_error_set(GB_EINVAL, "%s:%zu: words after 'endsolid'", b->name, c->line);
        else if (!strcmp(w, "solid") && stage == 0 && c->line == 1) stage = 4;
        else if (!strcmp(w, "facet") && stage == 4 && n == 5 && !strcmp(tokens[1], "normal")) {
            double normal[3];
            status = read_point(b, c->line, tokens + 2, normal); /* read, and recomputed from the vertices */
            stage = 1;
        } else if (!strcmp(w, "outer") && stage == 1 && n == 2 && !strcmp(tokens[1], "loop")) stage = 2, corners = 0;
        else if (!strcmp(w, "vertex") && stage == 2 && n == 4 && corners < 3) {
            double x[3];
            status = read_point(b, c->line, tokens + 1, x);
            if (!status) status = stl_vertex(b, &table, x, c->line, &index[corners++]);
        } else if (!strcmp(w, "endloop") && stage == 2 && corners == 3) stage = 3;
        else if (!strcmp(w, "endfacet") && stage == 3) {
            status = add_triangle(b, index[0], index[1], index[2], c->line);
            stage = 4;
        } else if (!strcmp(w, "endsolid") && stage == 4) ended = 1;
        else
            status = gb_error_set(GB_EINVAL, "%s:%zu: '%s' out of place (allowed: solid, then per triangle facet normal NX NY NZ, "
                                  "outer loop, three vertex X Y Z lines, endloop, endfacet; then endsolid)", b->name, c->line, w);
    }
    if (!status && !ended) status = gb_error_set(GB_EINVAL, "%s:%zu: the file ends before 'endsolid'", b->name, c->line);
    free(table.slot);
    return status;
}

static double little_float(const unsigned char *p)
{
    const uint32_t u = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    float f;
    memcpy(&f, &u, sizeof f);
    return (double)f;
}

static int read_stl_binary(builder *b, const unsigned char *data, size_t size)
{
    if (size < 84) return gb_error_set(GB_EINVAL, "%s: a binary STL of %zu bytes (allowed: an 80-byte header, a count, 50 bytes a triangle)", b->name, size);
    const uint32_t count = (uint32_t)data[80] | (uint32_t)data[81] << 8 | (uint32_t)data[82] << 16 | (uint32_t)data[83] << 24;
    if ((size - 84) / 50 != count || (size - 84) % 50)
        return gb_error_set(GB_EINVAL, "%s: a binary STL counts %u triangles in %zu bytes (allowed: 84 + 50 x count bytes, %llu here)",
                            b->name, count, size, 84ULL + 50ULL * count);
    vertex_table table = {0, NULL};
    int status = GB_OK;
    for (uint32_t t = 0; t < count && !status; t++) {
        const unsigned char *p = data + 84 + 50 * (size_t)t;
        size_t index[3];
        for (int v = 0; v < 3 && !status; v++) {
            const double x[3] = {little_float(p + 12 + 12 * v), little_float(p + 16 + 12 * v), little_float(p + 20 + 12 * v)};
            status = stl_vertex(b, &table, x, t + 1, &index[v]);
        }
        if (!status) status = add_triangle(b, index[0], index[1], index[2], t + 1);
        if (status && strstr(gb_error_message(), ":"))
            status = gb_error_set(status, "%s (triangle %u of the binary STL)", gb_error_message(), t + 1);
    }
    free(table.slot);
    return status;
}

/* ---------------------------------------------------------------- entry points */

const char *gb_mesh_format_name(gb_mesh_format format)
{
    static const char *const names[] = {"OFF", "OBJ", "ASCII STL", "binary STL"};
    return format >= GB_MESH_OFF && format <= GB_MESH_STL_BINARY ? names[format] : "?";
}

/* The format from the name's extension (.off, .obj, .stl; any case); an .stl file is binary when its size is
 * exactly 84 + 50 × the count its header gives (whatever the header's words), else unless it starts with "solid"
 * (after a UTF-8 byte-order mark, if any) followed by a line with "facet". GB_EINVAL for another extension. */
static int format_of(const char *name, const unsigned char *data, size_t size, gb_mesh_format *out)
{
    const char *dot = strrchr(name, '.');
    if (dot && !strcasecmp(dot, ".off")) return *out = GB_MESH_OFF, GB_OK;
    if (dot && !strcasecmp(dot, ".obj")) return *out = GB_MESH_OBJ, GB_OK;
    if (dot && !strcasecmp(dot, ".stl")) {
        /* ASCII when it starts with "solid" (after a UTF-8 byte-order mark, if any) and a "facet" follows within the
         * first lines; binary otherwise, and binary whenever its size is exactly 84 + 50 x the count its header
         * gives (a binary header may begin "solid ... facet", as some exporters write it) */
        const size_t bom = size >= 3 && !memcmp(data, "\xEF\xBB\xBF", 3) ? 3 : 0;
        if (size >= 84) {
            const uint64_t count = (uint64_t)data[80] | (uint64_t)data[81] << 8 | (uint64_t)data[82] << 16 | (uint64_t)data[83] << 24;
            if (!bom && 84 + 50 * count == size) return *out = GB_MESH_STL_BINARY, GB_OK;
        }
        data += bom, size -= bom;
        int ascii = size >= 5 && !memcmp(data, "solid", 5);
        if (ascii) {
            const size_t look = size < 1024 ? size : 1024;
            ascii = 0;
            for (size_t k = 5; k + 5 <= look && !ascii; k++) ascii = !memcmp(data + k, "facet", 5) || !memcmp(data + k, "endsolid", 5);
        }
        return *out = ascii ? GB_MESH_STL_ASCII : GB_MESH_STL_BINARY, GB_OK;
    }
    return gb_error_set(GB_EINVAL, "%s: the mesh format is unknown (allowed: a name ending .off, .obj or .stl)", name);
}

int gb_mesh_read_buffer(const char *name, const unsigned char *data, size_t size, gb_mesh *out)
{
    memset(out, 0, sizeof *out);
    gb_mesh_format format = GB_MESH_OFF; /* set by format_of on success */
    int status = format_of(name, data, size, &format);
    if (status) return status;
    out->format = format;
    builder b = {name, out, 0, 0};
    /* a UTF-8 byte-order mark before a text mesh is no part of it */
    const size_t bom = format != GB_MESH_STL_BINARY && size >= 3 && !memcmp(data, "\xEF\xBB\xBF", 3) ? 3 : 0;
    cursor c = {data + bom, size - bom, 0, 0};
    char (*tokens)[MAX_TOKEN] = format == GB_MESH_STL_BINARY ? NULL : malloc(MAX_TOKENS * sizeof *tokens);
    if (format != GB_MESH_STL_BINARY && !tokens) return gb_error_set(GB_ENOMEM, "%s: out of memory for a line's words", name);
    switch (format) {
    case GB_MESH_OFF: status = read_off(&b, &c, tokens); break;
    case GB_MESH_OBJ: status = read_obj(&b, &c, tokens); break;
    case GB_MESH_STL_ASCII: status = read_stl_ascii(&b, &c, tokens); break;
    default: status = read_stl_binary(&b, data, size); break;
    }
    free(tokens);
    if (!status && (out->vertex_count < 4 || out->triangle_count < 4))
        status = gb_error_set(GB_EINVAL, "%s: %zu vertices and %zu triangles (allowed: a closed body, at least 4 of each)", name,
                              out->vertex_count, out->triangle_count);
    if (status) gb_mesh_free(out);
    return status;
}

int gb_mesh_read(const char *path, gb_mesh *out)
{
    memset(out, 0, sizeof *out);
    char *data;
    size_t size;
    int status = gb_file_read(path, GB_MESH_FILE_MAX, "mesh file", "an OFF, OBJ or STL file", &data, &size);
    if (status) return status;
    status = gb_mesh_read_buffer(path, (const unsigned char *)data, size, out);
    free(data);
    return status;
}

void gb_mesh_free(gb_mesh *mesh)
{
    if (!mesh) return;
    free(mesh->vertices);
    free(mesh->vertex_line);
    free(mesh->triangles);
    memset(mesh, 0, sizeof *mesh);
}

/* gomboc check — is an output set whole? A run's NAME-summary.json and a scan's NAME-scan.json are
 * the manifests of their sets: each lists the other files of its set with their sizes and checksums.
 * A set mixed by a kill between two renames (a new history beside an old summary, an old CSV beside a
 * new JSON) or changed since is found here; for a run, a NAME-* output the manifest does not list (a
 * stale file of an earlier run) is found too. */
#include "gomboc_cli.h"

#include "gb_error.h"
#include "gb_file.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const char *usage_check =
    "usage: gomboc check MANIFEST\n"
    "\n"
    "  MANIFEST  a run's NAME-summary.json or a scan's NAME-scan.json\n"
    "\n"
    "Checks that every file the manifest lists stands beside it with the size and FNV-1a 64 checksum it\n"
    "records, and (for a run) that no other NAME-* output of `gomboc run` stands there. Prints a line a\n"
    "file; exit 0 when the set is whole, 1 when it is mixed or incomplete, 2 when MANIFEST is not one.\n";

enum { MANIFEST_MAX = 64 << 20 };

/* One listed file against what stands in `dir`: 1 when it matches (a line is printed either way). */
static int check_member(const char *dir, const cJSON *item)
{
    const cJSON *name = cJSON_GetObjectItemCaseSensitive(item, "name");
    const cJSON *bytes = cJSON_GetObjectItemCaseSensitive(item, "bytes");
    const cJSON *sum = cJSON_GetObjectItemCaseSensitive(item, "fnv1a64");
    if (!cJSON_IsString(name) || !cJSON_IsNumber(bytes) || !cJSON_IsString(sum) || strchr(name->valuestring, '/') ||
        !name->valuestring[0]) {
        printf("BAD ENTRY (allowed: {name, bytes, fnv1a64})\n");
        return 0;
    }
    char *path = malloc(strlen(dir) + strlen(name->valuestring) + 2);
    if (!path) return 0;
    sprintf(path, "%s/%s", dir, name->valuestring);
    uint64_t size, checksum;
    int ok = 0;
    if (gb_file_digest(path, &size, &checksum)) {
        printf("MISSING %s\n", name->valuestring);
    } else {
        char hex[17];
        snprintf(hex, sizeof hex, "%016" PRIx64, checksum);
        ok = (double)size == bytes->valuedouble && !strcmp(hex, sum->valuestring);
        if (ok) printf("ok %s\n", name->valuestring);
        else
            printf("CHANGED %s: %" PRIu64 " bytes, checksum %s (the manifest: %.0f bytes, %s)\n", name->valuestring, size, hex,
                   bytes->valuedouble, sum->valuestring);
    }
    free(path);
    return ok;
}

/* A run's outputs of this NAME that the manifest does not list: the count (a line each). Only regular
 * files count: a FIFO, a device or a directory of such a name is no output (a run never writes one and
 * leaves it alone). */
static int unlisted_outputs(const char *dir, const char *manifest_name, const cJSON *files)
{
    const char *tail = "-summary.json";
    const size_t n = strlen(manifest_name), t = strlen(tail);
    if (n <= t || strcmp(manifest_name + n - t, tail)) return 0;
    int extra = 0;
    for (const char *const *suffix = cli_run_suffixes; *suffix; suffix++) {
        char name[1024];
        snprintf(name, sizeof name, "%.*s-%s", (int)(n - t), manifest_name, *suffix);
        if (!strcmp(name, manifest_name)) continue;
        int listed = 0;
        const cJSON *item;
        cJSON_ArrayForEach(item, files)
        {
            const cJSON *entry = cJSON_GetObjectItemCaseSensitive(item, "name");
            listed |= cJSON_IsString(entry) && !strcmp(entry->valuestring, name);
        }
        char *path = malloc(strlen(dir) + strlen(name) + 2);
        if (!path) continue;
        sprintf(path, "%s/%s", dir, name);
        struct stat st;
        if (!listed && lstat(path, &st) == 0 && S_ISREG(st.st_mode)) {
            printf("NOT IN THE SET %s\n", name);
            extra++;
        }
        free(path);
    }
    return extra;
}

int command_check(int argc, char **argv)
{
    const char *manifest = NULL;
    for (int i = 0; i < argc; i++) {
        const int positional = cli_positional("check", argv[i], &manifest, "manifest", "MANIFEST");
        if (positional) {
            if (positional == 1) continue;
            return positional;
        }
        const char *value = NULL;
        const int kind = cli_next_option("check", argc, argv, &i, usage_check, (const char *const[]){NULL},
                                         " (allowed: --help)", NULL, NULL, &value);
        return kind == CLI_HELP ? 0 : kind;
    }
    if (!manifest)
        return cli_input_error("check", "missing %s%s", "MANIFEST", " (allowed: a run's NAME-summary.json or a scan's NAME-scan.json)");
    char *text;
    size_t size;
    if (gb_file_read(manifest, MANIFEST_MAX, "manifest", "a run's NAME-summary.json or a scan's NAME-scan.json", &text, &size))
        return cli_input_error("check", "%s", gb_error_message());
    cJSON *root = cJSON_ParseWithLength(text, size);
    free(text);
    const cJSON *files = cJSON_GetObjectItemCaseSensitive(root, "files");
    if (!cJSON_IsArray(files)) {
        cJSON_Delete(root);
        return cli_input_error("check", "%s: not a manifest: no \"files\" list (allowed: a run's NAME-summary.json or a "
                               "scan's NAME-scan.json written by this version)", manifest);
    }
    const char *slash = strrchr(manifest, '/');
    char *dir = slash ? strndup(manifest, (size_t)(slash - manifest + (slash == manifest))) : strdup(".");
    int listed = 0, whole = 0;
    const cJSON *item;
    cJSON_ArrayForEach(item, files)
    {
        listed++;
        whole += check_member(dir, item);
    }
    const int extra = unlisted_outputs(dir, slash ? slash + 1 : manifest, files);
    free(dir);
    cJSON_Delete(root);
    const int ok = whole == listed && extra == 0;
    printf("%s: %s (%d of %d listed files as recorded%s)\n", manifest, ok ? "the set is whole" : "the set is MIXED or incomplete",
           whole, listed, extra ? ", and files not in the set" : "");
    return ok ? 0 : EXIT_COMPUTE;
}
